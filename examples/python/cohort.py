"""Map a cohort of meshes in parallel, writing what `conformap batch` writes.

    python examples/python/cohort.py --command disk|sphere|global|flatten|atlas
        --out-dir OUT [--jobs N] [--skip-existing] [--ext obj|ply|gltf|glb] [--png]
        [--max-memory BYTES] [--report cohort.jsonl] [--scheduler ADDRESS]
        MESH|DIR... [-- COMMAND OPTIONS]

Every input is one call of ``conformap.batch_one``: the Rust function ``conformap batch``
runs for each of its inputs, with the command's options (after ``--``, as batch takes
them) parsed by the CLI's parser. So the outputs (``OUT/<stem>.<ext>``,
``OUT/<stem>.json``) and the JSON lines are batch's: one compact, key-sorted line per
input in input order, then the summary line; exit code 0, or 4 when some input failed,
2 on usage errors.

``--jobs N`` (N > 1) runs the inputs on a ``dask.distributed`` LocalCluster of N worker
processes with one thread each (or, without Dask, on N threads: conformap releases the
GIL). ``--scheduler tcp://host:8786`` sends them to a running Dask cluster instead (e.g.
a dask-jobqueue ``SLURMCluster``; see docs/cohorts.md): every worker needs the wheel and
the files. A directory stands for its mesh files, sorted by name.
"""

import argparse
import decimal
import json
import math
import pathlib
import resource
import sys
import time

import conformap

MESH_SUFFIXES = {".obj", ".gltf", ".glb", ".ply", ".stl", ".off", ".gii"}
FREESURFER_NAMES = {"white", "pial", "sphere", "inflated", "orig", "smoothwm", "midthickness"}


def json_number(x: float) -> str:
    """A float as serde_json (ryu) writes it: the shortest round-trip digits, decimal for
    exponents -5 < k <= 16, else `1.5e-7`; non-finite values as null."""
    if not math.isfinite(x):
        return "null"
    sign = "-" if math.copysign(1.0, x) < 0 else ""
    d = decimal.Decimal(repr(abs(x)))
    if d == 0:
        return sign + "0.0"
    t = d.as_tuple()
    digits, exp = list(t.digits), t.exponent
    while len(digits) > 1 and digits[-1] == 0:
        digits.pop()
        exp += 1
    s = "".join(map(str, digits))
    kk = len(s) + exp  # the position of the decimal point
    if exp >= 0 and kk <= 16:
        return f"{sign}{s}{'0' * exp}.0"
    if 0 < kk <= 16:
        return f"{sign}{s[:kk]}.{s[kk:]}"
    if -5 < kk <= 0:
        return f"{sign}0.{'0' * -kk}{s}"
    mantissa = s if len(s) == 1 else f"{s[0]}.{s[1:]}"
    return f"{sign}{mantissa}e{kk - 1}"


def json_line(value) -> str:
    """`value` as compact, key-sorted JSON text, byte for byte as `conformap batch` writes
    its lines (serde_json)."""
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return json_number(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, dict):
        items = sorted(value.items())
        return "{" + ",".join(f"{json_line(k)}:{json_line(v)}" for k, v in items) + "}"
    return "[" + ",".join(json_line(v) for v in value) + "]"


def command_options(tokens):
    """`--max-iter 50 --strict` → {"max_iter": "50", "strict": True} for batch_one."""
    options, k = {}, 0
    while k < len(tokens):
        name = tokens[k]
        if not name.startswith("--"):
            raise SystemExit(f"error: the options after -- must be --name [value], got {name!r}")
        key = name[2:].replace("-", "_")
        if k + 1 < len(tokens) and not tokens[k + 1].startswith("--"):
            options[key], k = tokens[k + 1], k + 2
        else:
            options[key], k = True, k + 1
    return options


def is_mesh(p: pathlib.Path) -> bool:
    return p.suffix.lower() in MESH_SUFFIXES or p.suffix.lstrip(".") in FREESURFER_NAMES


def expand(paths):
    """The inputs: meshes as given, directories as their mesh files sorted by name."""
    out = []
    for p in paths:
        p = pathlib.Path(p)
        out += sorted(str(q) for q in p.iterdir() if is_mesh(q)) if p.is_dir() else [str(p)]
    return out


def run(paths, args, options):
    """Yields each input's line (batch_one's dict), in input order."""
    kwargs = dict(skip_existing=args.skip_existing, ext=args.ext, png=args.png,
                  max_memory=args.max_memory, **options)
    task = lambda p: conformap.batch_one(p, args.command, str(args.out_dir), **kwargs)
    if args.scheduler is None and args.jobs == 1:
        yield from map(task, paths)
        return
    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        from concurrent.futures import ThreadPoolExecutor

        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            yield from pool.map(task, paths)
        return
    if args.scheduler is not None:
        with Client(args.scheduler) as client:
            yield from client.gather(client.map(task, paths, pure=False), asynchronous=False)
        return
    print(f"cohort: {len(paths)} inputs on a Dask LocalCluster of {args.jobs} worker processes",
          file=sys.stderr)
    with LocalCluster(n_workers=args.jobs, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        for future in client.map(task, paths, pure=False):
            yield future.result()


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    cut = argv.index("--") if "--" in argv else len(argv)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("inputs", nargs="+", help="meshes, or directories of meshes")
    ap.add_argument("--command", required=True,
                    choices=["disk", "sphere", "global", "flatten", "atlas"])
    ap.add_argument("--out-dir", type=pathlib.Path, required=True)
    ap.add_argument("--jobs", type=int, default=1, help="inputs at once (default 1)")
    ap.add_argument("--skip-existing", action="store_true")
    ap.add_argument("--ext", help="output mesh format (default: the input's)")
    ap.add_argument("--png", action="store_true")
    ap.add_argument("--max-memory", type=int, help="bytes, every run's limit")
    ap.add_argument("--report", type=pathlib.Path, help="also write the lines here")
    ap.add_argument("--scheduler", help="address of a running Dask scheduler")
    args = ap.parse_args(argv[:cut])
    options = command_options(argv[cut + 1:])
    paths = expand(args.inputs)
    args.jobs = max(1, min(args.jobs, len(paths)))
    t0 = time.perf_counter()
    sink = args.report.open("w") if args.report else None
    counts = {"ok": 0, "failed": 0, "skipped": 0}
    peak = 0

    def emit(line):
        text = json_line(line)
        print(text, flush=True)
        if sink:
            sink.write(text + "\n")
            sink.flush()

    try:
        for line in run(paths, args, options):
            counts[line["status"]] += 1
            peak = max(peak, line.get("memory", {}).get("peak_rss_bytes") or 0)
            emit(line)
    except conformap.ConformapError as e:  # what batch refuses before running anything
        print(f"error: {e}", file=sys.stderr)
        return getattr(e, "exit_code", 2)  # lost when pickled back from a Dask worker
    exit_code = 4 if counts["failed"] else 0
    own = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    emit({"summary": {
        "command": args.command,
        "inputs": len(paths),
        **counts,
        "jobs": args.jobs,
        "exit_code": exit_code,
        "peak_rss_bytes": max(own, peak),
        "total_ms": 1000.0 * (time.perf_counter() - t0),
    }})
    if sink:
        sink.close()
    return exit_code


if __name__ == "__main__":
    sys.exit(main())
