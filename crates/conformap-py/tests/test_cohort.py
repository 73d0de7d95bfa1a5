"""examples/python/cohort.py writes the lines and outputs of `conformap batch`."""
import json
import shutil
import subprocess
import sys

import numpy as np
import pytest

from conftest import FIXTURES, ROOT, cli_binary

TOL = 1e-9


def lines_of(text):
    return [json.loads(l) for l in text.splitlines() if l.strip()]


def vt_of(path):
    return np.array([[float(x) for x in l.split()[1:3]] for l in open(path) if l.startswith("vt ")])


@pytest.mark.parametrize(
    "command, names",
    [("disk", ["woody.obj", "halftunnel.obj", "spot.obj"]), ("global", ["eightsim.obj", "woody.obj"])],
)
def test_cohort_lines_are_batch_lines(command, names, tmp_path):
    meshes = tmp_path / "meshes"
    meshes.mkdir()
    for n in names:
        shutil.copy(FIXTURES / n, meshes / n)
    inputs = sorted(meshes.iterdir())
    py = subprocess.run(
        [sys.executable, str(ROOT / "examples" / "python" / "cohort.py"), str(meshes),
         "--out-dir", str(tmp_path / "py"), "--command", command, "--workers", "2"],
        capture_output=True, text=True, check=False)
    cli = subprocess.run(
        [str(cli_binary()), "batch", "--command", command, "--out-dir", str(tmp_path / "cli"),
         "--jobs", "1", *map(str, inputs), *(["--", "-q"] if command == "global" else [])],
        capture_output=True, text=True, check=False)
    # spot is closed: no disk map; woody is a disk: no global map (a failed line each)
    assert py.returncode == cli.returncode == 4, (py.stderr, cli.stderr)
    mine, theirs = lines_of(py.stdout), lines_of(cli.stdout)
    assert len(mine) == len(theirs) == len(names) + 1
    for a, b in zip(mine[:-1], theirs[:-1]):
        assert a["input"] == b["input"] and a["status"] == b["status"]
        assert set(a) == set(b), (set(a) ^ set(b))
        if b["status"] == "ok":
            assert [p.replace("/py/", "/cli/") for p in a["outputs"]] == b["outputs"]
            assert a["method"] == b["method"] and a["converged"] == b["converged"]
            assert set(a["metrics"]) == set(b["metrics"])
            assert abs(a["metrics"]["conformal_energy"] - b["metrics"]["conformal_energy"]) < TOL
            assert set(a["timings_ms"]) == set(b["timings_ms"]) and set(a["memory"]) == set(b["memory"])
            # the same outputs: texture coordinates and report
            assert np.max(np.abs(vt_of(a["outputs"][0]) - vt_of(b["outputs"][0]))) < 1e-12
            ra, rb = (json.loads(open(p).read()) for p in (a["outputs"][1], b["outputs"][1]))
            assert set(ra) == set(rb) and ra["input"] == rb["input"]
        else:
            for key in ("exit_code", "exit_class", "error", "hint"):
                assert a[key] == b[key], key
    assert set(mine[-1]["summary"]) == set(theirs[-1]["summary"])
    for key in ("command", "inputs", "ok", "failed", "skipped", "exit_code"):
        assert mine[-1]["summary"][key] == theirs[-1]["summary"][key], key
