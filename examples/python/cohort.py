"""Map a folder of meshes onto the disk (or sphere) in parallel, one JSON line per mesh.

    python examples/python/cohort.py MESH_DIR --out-dir OUT [--command disk|sphere]
                                     [--workers N] [--report cohort.jsonl]

Uses Dask (a LocalCluster with one thread per worker) when it is installed, else
``concurrent.futures.ThreadPoolExecutor``: conformap releases the GIL, so threads run maps
in parallel. Each line has the fields of design.md's ``conformap batch`` lines (input,
status, metrics headline, timings, peak memory, error), then a summary line. Outputs:
``OUT/<stem>_uv.obj`` (vt = (u+1)/2 for disk maps) and ``OUT/<stem>.json`` (the report).

On a cluster, replace the LocalCluster by ``Client("tcp://scheduler:8786")`` (or a
dask-jobqueue SLURMCluster / PBSCluster): the task takes a path and returns a dict, so it
runs on any worker that has the wheel installed and sees the files.
"""

import argparse
import json
import pathlib
import sys
import time

import conformap

MESH_SUFFIXES = {".obj", ".gltf", ".glb"}


def map_one(path: str, out_dir: str, command: str) -> dict:
    """Maps one mesh; never raises (failures become a line with status "error")."""
    p, out = pathlib.Path(path), pathlib.Path(out_dir)
    line = {"input": str(p), "command": command}
    t0 = time.perf_counter()
    try:
        V, F = conformap.read_mesh(p)
        if command == "disk":
            param, report = conformap.disk_map(V, F)
            uv = (param + 1.0) / 2.0
        else:
            param, report = conformap.sphere_map(V, F)
            uv = None
        conformap.write_mesh(out / f"{p.stem}_uv.obj", V if uv is not None else param, F, uv=uv)
        (out / f"{p.stem}.json").write_text(json.dumps(report, indent=2))
        m = report["metrics"]
        line.update(
            status="ok",
            method=report["method"],
            vertices=report["input"]["vertices"],
            faces=report["input"]["faces"],
            metrics={k: m.get(k) for k in ("conformal_energy", "flipped_faces")},
            converged=report["solver"].get("converged"),
            timings_ms=report["timings_ms"],
            peak_rss_bytes=report["memory"].get("peak_rss_bytes"),
        )
    except (conformap.ConformapError, conformap.NumericalError, OSError) as e:
        line.update(status="error", error=str(e).splitlines()[0])
    line["wall_ms"] = 1000.0 * (time.perf_counter() - t0)
    return line


def run(paths, out_dir, command, workers):
    """Yields one line per mesh, as they finish."""
    try:
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        from concurrent.futures import ThreadPoolExecutor, as_completed as done

        with ThreadPoolExecutor(max_workers=workers) as pool:
            futures = [pool.submit(map_one, str(p), out_dir, command) for p in paths]
            for f in done(futures):
                yield f.result()
        return
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True) as cluster:
        with Client(cluster) as client:
            futures = client.map(map_one, [str(p) for p in paths], out_dir=out_dir, command=command)
            for f in as_completed(futures):
                yield f.result()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mesh_dir", type=pathlib.Path)
    ap.add_argument("--out-dir", type=pathlib.Path, required=True)
    ap.add_argument("--command", choices=["disk", "sphere"], default="disk")
    ap.add_argument("--workers", type=int, default=2, help="parallel maps (default 2: one per core here)")
    ap.add_argument("--report", type=pathlib.Path, help="also write the lines to this file")
    args = ap.parse_args(argv)
    paths = sorted(p for p in args.mesh_dir.iterdir() if p.suffix.lower() in MESH_SUFFIXES)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    sink = args.report.open("w") if args.report else None
    ok = failed = 0
    t0 = time.perf_counter()
    for line in run(paths, str(args.out_dir), args.command, args.workers):
        ok += line["status"] == "ok"
        failed += line["status"] != "ok"
        text = json.dumps(line)
        print(text, flush=True)
        if sink:
            sink.write(text + "\n")
    summary = json.dumps({"summary": {"inputs": len(paths), "ok": ok, "failed": failed,
                                      "wall_ms": 1000.0 * (time.perf_counter() - t0)}})
    print(summary)
    if sink:
        sink.write(summary + "\n")
        sink.close()
    return 0 if failed == 0 else 4


if __name__ == "__main__":
    sys.exit(main())
