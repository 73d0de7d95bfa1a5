#!/usr/bin/env python3
"""Time libigl's harmonic disk map (Python bindings) beside `conformap disk` on the same files.

libigl's map is the usual baseline: boundary vertices to the circle by arc length
(`map_vertices_to_circle`), then one harmonic solve (`harmonic`, k = 1): one factorization,
no boundary optimization. conformap's time is taken from its JSON report as the solver's
wall-clock total, `solver.timings_ms.total` (assembly, analysis, factorization and the map;
file reading and writing excluded on both sides).

Usage:
    python3 -m venv /tmp/iglenv && /tmp/iglenv/bin/pip install libigl numpy scipy
    cargo build --release -p conformap-cli
    /tmp/iglenv/bin/python tools/peers/libigl_harmonic.py [--runs 5] [--method cem] MESH.obj ...
    /tmp/iglenv/bin/python tools/peers/libigl_harmonic.py --whole [--runs 5] MESH.obj ...

Prints a Markdown table: V, F, libigl ms (median), conformap ms (median), ratio, and the
conformal energy of both maps as judged by `conformap metrics`.

`--whole` times the whole job instead, file to file, runs interleaved: libigl's
`read_triangle_mesh` + the harmonic map + `writeOBJ` with the map as texture coordinates,
timed inside Python (the interpreter's start and `import igl` are not counted, in libigl's
favour), against the wall-clock time of the whole `conformap disk MESH -o OUT.obj` process
(start to exit: reading, validation, the map, metrics, writing). Both write `v`, `vt` and
`f v/vt` lines.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import igl
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CONFORMAP = os.path.join(ROOT, "target", "release", "conformap")


def igl_map(v, f):
    bnd = igl.boundary_loop(f)
    bnd_uv = igl.map_vertices_to_circle(v, bnd)
    return igl.harmonic(v, f, bnd, bnd_uv, 1)


def write_flat(path, uv, f):
    with open(path, "w") as out:
        for x, y in uv:
            out.write(f"v {float(x)!r} {float(y)!r} 0\n")
        for a, b, c in f:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")


def conformap_metrics(mesh, param):
    out = subprocess.run([CONFORMAP, "metrics", mesh, param, "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        return float("nan")
    return json.loads(out.stdout)["metrics"]["conformal_energy"]


def whole(args):
    """The `--whole` table: file to file, interleaved runs, medians."""
    print(f"median of {args.runs} interleaved runs; whole job, file to file; times in ms\n")
    print("| mesh | MB | libigl read + harmonic + writeOBJ | conformap disk (process) | "
          "of which read + write (report) | conformap / libigl |")
    print("|---|---:|---:|---:|---:|---:|")
    tmp = tempfile.mkdtemp(prefix="conformap-peers-")
    for mesh in args.meshes:
        igl_ms, ours, io = [], [], []
        for _ in range(args.runs):
            out = os.path.join(tmp, "igl.obj")
            t = time.perf_counter()
            v, f = igl.read_triangle_mesh(mesh)
            uv = igl_map(v, f)
            igl.writeOBJ(out, v, f, TC=np.ascontiguousarray(uv), FTC=f)
            igl_ms.append((time.perf_counter() - t) * 1e3)
            rep = os.path.join(tmp, "r.json")
            cmd = [CONFORMAP, "disk", mesh, "-o", os.path.join(tmp, "o.obj"), "--report", rep]
            t = time.perf_counter()
            done = subprocess.run(cmd, capture_output=True, text=True)
            ours.append((time.perf_counter() - t) * 1e3)
            if done.returncode != 0:
                sys.exit(f"conformap failed on {mesh}: {done.stderr.strip()}")
            tm = json.load(open(rep))["timings_ms"]
            io.append(tm["read"] + tm["write"])
        a, b = statistics.median(igl_ms), statistics.median(ours)
        mb = os.path.getsize(mesh) / 1e6
        name = os.path.basename(mesh)
        print(f"| {name} | {mb:.1f} | {a:.0f} | {b:.0f} | {statistics.median(io):.0f} | {b / a:.2f} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--method", default=None, help="conformap disk --method (default: its default)")
    ap.add_argument("--whole", action="store_true", help="time the whole job, file to file")
    ap.add_argument("meshes", nargs="+")
    args = ap.parse_args()
    if not os.path.exists(CONFORMAP):
        sys.exit(f"build conformap first: cargo build --release -p conformap-cli ({CONFORMAP})")
    if args.whole:
        whole(args)
        return
    print(f"median of {args.runs} runs; map computation only (no file I/O); times in ms\n")
    print("| mesh | V | F | libigl harmonic | conformap | conformap / libigl | E_C libigl | E_C conformap |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    tmp = tempfile.mkdtemp(prefix="conformap-peers-")
    for mesh in args.meshes:
        v, f = igl.read_triangle_mesh(mesh)
        v = np.asarray(v, dtype=np.float64)
        f = np.asarray(f, dtype=np.int64)
        times = []
        uv = None
        for _ in range(args.runs):
            t = time.perf_counter()
            uv = igl_map(v, f)
            times.append((time.perf_counter() - t) * 1e3)
        flat = os.path.join(tmp, "igl_flat.obj")
        write_flat(flat, uv, f)
        ec_igl = conformap_metrics(mesh, flat)
        ours = []
        ec_ours = float("nan")
        for _ in range(args.runs):
            rep = os.path.join(tmp, "r.json")
            cmd = [CONFORMAP, "disk", mesh, "-o", os.path.join(tmp, "o.obj"), "--report", rep]
            if args.method:
                cmd += ["--method", args.method]
            out = subprocess.run(cmd, capture_output=True, text=True)
            if out.returncode != 0:
                print(f"conformap failed on {mesh}: {out.stderr.strip()}", file=sys.stderr)
                break
            r = json.load(open(rep))
            # the solver's own wall-clock total: assembly, analysis (overlapped with the
            # assembly), numeric factorization and everything after (`timings_ms.factor`
            # already includes `analyse`: adding both counted the analysis twice)
            ours.append(r["solver"]["timings_ms"]["total"])
            ec_ours = r["metrics"]["conformal_energy"]
        igl_ms = statistics.median(times)
        our_ms = statistics.median(ours) if ours else float("nan")
        name = os.path.basename(mesh)
        print(f"| {name} | {len(v)} | {len(f)} | {igl_ms:.0f} | {our_ms:.0f} | {our_ms / igl_ms:.2f} | {ec_igl:.5f} | {ec_ours:.5f} |")


if __name__ == "__main__":
    main()
