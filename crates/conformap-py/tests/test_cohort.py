"""`conformap.batch_one` and examples/python/cohort.py write what `conformap batch` writes:
the same outputs and the same JSON lines (times and memory peaks masked), for ok, failed
and skipped inputs; cohort.py on a real dask.distributed cluster of worker processes."""
import json
import pathlib
import shutil
import subprocess
import sys

import pytest

import conformap
from conftest import FIXTURES, ROOT, cli_binary

COHORT = ROOT / "examples" / "python" / "cohort.py"
sys.path.insert(0, str(COHORT.parent))
from cohort import json_line  # noqa: E402

# what differs between two runs of one input
VARYING = ("timings_ms", "memory", "time_ms")


def masked(line, out_dir, cli_dir):
    """The line without times and memory, its outputs named in the CLI's directory."""
    line = {k: v for k, v in line.items() if k not in VARYING}
    if "outputs" in line:
        line["outputs"] = [p.replace(str(out_dir), str(cli_dir)) for p in line["outputs"]]
    if "summary" in line:
        line["summary"] = {k: v for k, v in line["summary"].items()
                           if k not in ("total_ms", "peak_rss_bytes")}
    return line


def batch(command, out_dir, inputs, *extra, options=()):
    proc = subprocess.run(
        [str(cli_binary()), "batch", "--command", command, "--out-dir", str(out_dir), *extra,
         *map(str, inputs), *(["--", *options] if options else [])],
        capture_output=True, text=True, check=False)
    return proc, proc.stdout.splitlines()


@pytest.mark.parametrize("command, names, options, kwargs", [
    ("disk", ["woody.obj", "spot.obj", "halftunnel.obj"], ["--method", "cem", "--max-iter", "30"],
     {"method": "cem", "max_iter": 30}),
    ("global", ["eightsim.obj", "woody.obj"], ["--quiet"], {"quiet": True}),
])
def test_batch_one_dict_is_batch_line(command, names, options, kwargs, tmp_path):
    inputs = [FIXTURES / n for n in names]
    proc, lines = batch(command, tmp_path / "cli", inputs, options=options)
    assert proc.returncode == 4, proc.stderr  # spot (disk), woody (global) fail
    statuses = set()
    for path, text in zip(inputs, lines):
        theirs = json.loads(text)
        mine = conformap.batch_one(path, command, tmp_path / "py", **kwargs)
        assert masked(mine, tmp_path / "py", tmp_path / "cli") == masked(theirs, 0, 0)
        assert set(mine) == set(theirs) and set(mine.get("memory", {})) == set(theirs.get("memory", {}))
        statuses.add(mine["status"])
        if mine["status"] == "ok":
            for a, b in zip(mine["outputs"][:1], theirs["outputs"]):
                assert open(a, "rb").read() == open(b, "rb").read()  # the mesh, byte for byte
    assert statuses == {"ok", "failed"}
    # skipped: the outputs exist; the line has no time, so it equals batch's exactly
    proc, again = batch(command, tmp_path / "cli", inputs, "--skip-existing", options=options)
    skipped = [json.loads(t) for t in again[:-1] if json.loads(t)["status"] == "skipped"]
    assert skipped
    for line in skipped:
        assert conformap.batch_one(line["input"], command, tmp_path / "cli", skip_existing=True,
                                   **kwargs) == line


def test_batch_one_refuses_what_batch_refuses(tmp_path):
    with pytest.raises(conformap.ConformapError) as e:
        conformap.batch_one(FIXTURES / "woody.obj", "disk", tmp_path, no_such_option=3)
    assert e.value.exit_code == 2 and "--no-such-option" in str(e.value)
    with pytest.raises(conformap.ConformapError) as e:
        conformap.batch_one(FIXTURES / "woody.obj", "disc", tmp_path)
    assert e.value.exit_code == 2 and "disk" in str(e.value)
    with pytest.raises(conformap.ConformapError) as e:
        conformap.batch_one(FIXTURES / "README.md", "disk", tmp_path)
    assert e.value.exit_code == 2 and "one by one" in str(e.value)


def test_json_line_writes_serde_json_numbers():
    for x, text in [(0.0, "0.0"), (-0.0, "-0.0"), (3.0, "3.0"), (1e15, "1000000000000000.0"),
                    (1e16, "1e16"), (1.5e17, "1.5e17"), (0.25, "0.25"), (1e-5, "0.00001"),
                    (1.25e-5, "0.0000125"), (1e-6, "1e-6"), (-2.5e-12, "-2.5e-12"),
                    (123.456, "123.456"), (float("nan"), "null")]:
        assert json_line(x) == text, x
    assert json_line({"b": [1, 2.5, None], "a": "é\n"}) == '{"a":"é\\n","b":[1,2.5,null]}'


def test_cohort_on_dask_workers_writes_batch_lines(tmp_path):
    """Two real worker processes (CI installs dask[distributed]; skipped without it, as the
    thread fallback is not what this tests). One command: batch_one's lines for the other
    commands are checked above."""
    pytest.importorskip("dask.distributed")
    command, names, options = "disk", ["woody.obj", "halftunnel.obj", "spot.obj"], ["--method", "cem"]

    meshes = tmp_path / "meshes"
    meshes.mkdir()
    for n in names:
        shutil.copy(FIXTURES / n, meshes / n)
    inputs = sorted(meshes.iterdir())
    py = subprocess.run(
        [sys.executable, str(COHORT), "--command", command, "--out-dir", str(tmp_path / "py"),
         "--jobs", "2", "--report", str(tmp_path / "py.jsonl"), str(meshes),
         *(["--", *options] if options else [])],
        capture_output=True, text=True, check=False)
    cli, lines = batch(command, tmp_path / "cli", inputs, "--jobs", "2", options=options)
    assert py.returncode == cli.returncode == 4, (py.stderr, cli.stderr)
    assert "Dask LocalCluster of 2 worker processes" in py.stderr, py.stderr
    mine = py.stdout.splitlines()
    assert len(mine) == len(lines) == len(names) + 1
    assert (tmp_path / "py.jsonl").read_text().splitlines() == mine
    for a, b in zip(mine, lines):
        # the same text once times and peaks are masked, and batch's own text is what
        # json_line writes (the numbers formatted alike)
        assert json_line(json.loads(b)) == b
        ma = masked(json.loads(a), tmp_path / "py", tmp_path / "cli")
        assert json_line(ma) == json_line(masked(json.loads(b), 0, 0))
    # halftunnel and woody are disks (ok), spot is closed (failed); inputs in name order
    assert [json.loads(t)["status"] for t in mine[:-1]] == ["ok", "failed", "ok"]
    woody = json.loads(mine[2])
    assert 0 < woody["metrics"]["conformal_energy"] < 0.07
    assert json.loads((tmp_path / "py" / "woody.json").read_text())["metrics"]["conformal_energy"] \
        == woody["metrics"]["conformal_energy"]
    for line in map(json.loads, mine[:-1]):
        if line["status"] == "ok":
            cli_mesh = line["outputs"][0].replace(str(tmp_path / "py"), str(tmp_path / "cli"))
            assert open(line["outputs"][0], "rb").read() == open(cli_mesh, "rb").read()


def test_snakemake_rule(tmp_path):
    """examples/snakemake/Snakefile with --cores 2 on a two-subject derivatives tree (opt-in:
    Snakemake installs too slowly for CI; runs wherever it is installed)."""
    import os

    if shutil.which("snakemake", path=str(pathlib.Path(sys.executable).parent)) is None:
        pytest.skip("snakemake is not installed in this venv")
    import nibabel as nib
    import nibabel.freesurfer as nfs
    import numpy as np

    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    deriv = tmp_path / "derivatives"
    for sub, hemi, scale in [("01", "lh", 1.0), ("02", "rh", 40.0)]:
        (deriv / f"sub-{sub}" / "surf").mkdir(parents=True)
        nfs.write_geometry(str(deriv / f"sub-{sub}" / "surf" / f"{hemi}.white"), V * scale, F)
    env = {**os.environ, "PATH": f"{cli_binary().parent}{os.pathsep}{os.environ['PATH']}"}
    snakemake = pathlib.Path(sys.executable).parent / "snakemake"
    proc = subprocess.run(
        [str(snakemake), "-s", str(ROOT / "examples" / "snakemake" / "Snakefile"), "--cores", "2",
         "--config", f"derivatives={deriv}", "--directory", str(tmp_path), "--quiet"],
        capture_output=True, text=True, check=False, env=env)
    assert proc.returncode == 0, proc.stderr[-3000:]
    for sub, hemi in [("01", "lh"), ("02", "rh")]:
        out = deriv / f"sub-{sub}" / "conformap"
        S, T = nib.load(str(out / f"{hemi}.sphere.conformal.surf.gii")).agg_data(("pointset", "triangle"))
        assert np.array_equal(T, F) and np.max(np.abs(np.linalg.norm(S, axis=1) - 100)) < 1e-4
        overlay = nib.load(str(out / f"{hemi}.sphere.conformal.quality.shape.gii"))
        assert [d.data.shape for d in overlay.darrays] == [(len(V),), (len(V),)]
        assert json.loads((out / f"{hemi}.sphere.conformal.json").read_text())["solver"]["converged"]
