"""Map a folder of meshes in parallel, writing the JSON lines of `conformap batch`.

    python examples/python/cohort.py MESH_DIR --out-dir OUT [--command disk|sphere|global]
                                     [--workers N] [--skip-existing] [--ext obj|gltf|glb]
                                     [--report cohort.jsonl]

Uses Dask (a LocalCluster, one thread per worker process) when it is installed, else
``concurrent.futures.ThreadPoolExecutor``: conformap releases the GIL, so threads run maps
in parallel. The outputs and lines are those of ``conformap batch --command C --out-dir OUT``:
``OUT/<stem>.<ext>`` (the mesh with the map as texture coordinates, as the command's ``-o``
writes it) and ``OUT/<stem>.json`` (the command's report); one JSON line per mesh, in input
order, with the fields of batch's lines (``ok``: input, status, command, method, outputs,
converged, metrics, timings_ms, memory; ``failed``: input, status, exit_code, exit_class,
error, hint, time_ms; ``skipped``: input, status, outputs), then batch's summary line.
Exit code 0, or 4 when some mesh failed, as batch.

On a cluster, replace the LocalCluster by ``Client("tcp://scheduler:8786")`` (or a
dask-jobqueue ``SLURMCluster`` / ``PBSCluster``, one core per job): the task takes a path
and returns a dict, so it runs on any worker that has the wheel installed and sees the
files. Give each worker one thread (each map already uses the machine's rayon threads).
"""

import argparse
import json
import math
import pathlib
import resource
import sys
import time

import numpy as np

import conformap

MESH_SUFFIXES = {".obj", ".gltf", ".glb"}
EXIT_CLASS = {1: "bad input", 2: "usage", 3: "numerical"}


def equirectangular(S):
    """Texture coordinates of sphere points, as `conformap sphere -o` writes them."""
    u = (np.arctan2(S[:, 1], S[:, 0]) + math.pi) / (2 * math.pi)
    v = (np.arcsin(np.clip(S[:, 2], -1.0, 1.0)) + math.pi / 2) / math.pi
    return np.stack([u, v], axis=1)


def outputs_of(path: pathlib.Path, out_dir: pathlib.Path, ext):
    """batch's outputs of one input: OUT/<stem>.<ext> (ext: the input's) and OUT/<stem>.json."""
    ext = (ext or path.suffix.lstrip(".")).lower()
    ext = ext if ext in ("obj", "gltf", "glb") else "obj"
    return out_dir / f"{path.stem}.{ext}", out_dir / f"{path.stem}.json"


def map_one(path: str, out_dir: str, command: str, ext=None, skip_existing=False) -> dict:
    """Maps one mesh and writes its outputs; never raises (a failure is a `failed` line)."""
    p = pathlib.Path(path)
    mesh_out, report_out = outputs_of(p, pathlib.Path(out_dir), ext)
    outputs = [str(mesh_out), str(report_out)]
    if skip_existing and mesh_out.exists() and report_out.exists():
        return {"input": str(p), "status": "skipped", "outputs": outputs}
    t0 = time.perf_counter()
    try:
        V, F = conformap.read_mesh(p)
        read_ms = 1000.0 * (time.perf_counter() - t0)
        if command == "disk":
            uv, report = conformap.disk_map(V, F)
            write = lambda: conformap.write_mesh(mesh_out, V, F, uv=(uv + 1.0) / 2.0)
        elif command == "sphere":
            S, report = conformap.sphere_map(V, F)
            write = lambda: conformap.write_mesh(mesh_out, V, F, uv=equirectangular(S))
        else:
            uv, F_uv, report = conformap.global_map(V, F)
            g = report["global"]
            vt = (uv - np.array(g["uv_offset"])) * g["uv_scale"]
            write = lambda: conformap.write_mesh(mesh_out, V, F, uv=vt, F_uv=F_uv)
        t = time.perf_counter()
        write()
        # the report as the CLI writes it: the input's path; read, write and total timed here
        report["input"]["path"] = str(p)
        timings = report["timings_ms"]
        timings.update(read=read_ms, write=1000.0 * (time.perf_counter() - t),
                       total=1000.0 * (time.perf_counter() - t0))
        report_out.write_text(json.dumps(report, indent=2))
        return {
            "input": str(p),
            "status": "ok",
            "command": report["command"],
            "method": report["method"],
            "outputs": outputs,
            "converged": report["solver"]["converged"],
            "metrics": report["metrics"],
            "timings_ms": timings,
            # the worker process's peak so far (tasks share it), as batch says with --jobs > 1
            "memory": {**report["memory"], "peak_rss_scope": "process"},
        }
    except (conformap.ConformapError, conformap.NumericalError) as e:
        message = str(e).splitlines()[0]
        if message.startswith("<arrays>: "):  # the CLI names the file where we name arrays
            message = f"{p}: {message.removeprefix('<arrays>: ')}"
        return {
            "input": str(p),
            "status": "failed",
            "exit_code": e.exit_code,
            "exit_class": EXIT_CLASS[e.exit_code],
            "error": message,
            "hint": e.hint,
            "time_ms": 1000.0 * (time.perf_counter() - t0),
        }
    except OSError as e:
        return {"input": str(p), "status": "failed", "exit_code": 1, "exit_class": "bad input",
                "error": f"cannot write the outputs of {p}: {e}", "hint": None,
                "time_ms": 1000.0 * (time.perf_counter() - t0)}


def run(paths, out_dir, command, workers, ext=None, skip_existing=False):
    """Yields one line per mesh, in input order."""
    kwargs = dict(out_dir=out_dir, command=command, ext=ext, skip_existing=skip_existing)
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(max_workers=workers) as pool:
            futures = [pool.submit(map_one, str(p), **kwargs) for p in paths]
            for f in futures:
                yield f.result()
        return
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True) as cluster:
        with Client(cluster) as client:
            for f in client.map(map_one, [str(p) for p in paths], **kwargs):
                yield f.result()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh_dir", type=pathlib.Path)
    ap.add_argument("--out-dir", type=pathlib.Path, required=True)
    ap.add_argument("--command", choices=["disk", "sphere", "global"], default="disk")
    ap.add_argument("--workers", type=int, default=2, help="parallel maps (default 2: one per core here)")
    ap.add_argument("--ext", choices=["obj", "gltf", "glb"], help="output format (default: the input's)")
    ap.add_argument("--skip-existing", action="store_true", help="skip inputs whose outputs exist")
    ap.add_argument("--report", type=pathlib.Path, help="also write the lines to this file")
    args = ap.parse_args(argv)
    paths = sorted(p for p in args.mesh_dir.iterdir() if p.suffix.lower() in MESH_SUFFIXES)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    sink = args.report.open("w") if args.report else None
    counts = {"ok": 0, "failed": 0, "skipped": 0}
    t0 = time.perf_counter()

    def emit(line):
        text = json.dumps(line)
        print(text, flush=True)
        if sink:
            sink.write(text + "\n")

    workers = max(1, min(args.workers, len(paths)))
    for line in run(paths, str(args.out_dir), args.command, workers, args.ext, args.skip_existing):
        counts[line["status"]] += 1
        emit(line)
    exit_code = 4 if counts["failed"] else 0
    emit({"summary": {
        "command": args.command,
        "inputs": len(paths),
        **counts,
        "jobs": workers,
        "exit_code": exit_code,
        # this process's peak (with Dask, the workers' own are in each line's "memory")
        "peak_rss_bytes": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024,
        "total_ms": 1000.0 * (time.perf_counter() - t0),
    }})
    if sink:
        sink.close()
    return exit_code


if __name__ == "__main__":
    sys.exit(main())
