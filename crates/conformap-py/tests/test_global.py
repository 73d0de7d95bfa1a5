"""global_map against the CLI's `conformap global` on the fixtures (the same layout and
report numbers), its array shape for a seamed layout, errors with the CLI's message, and
the GIL released during the map."""

import numpy as np
import pytest

import conformap
from conftest import assert_gil_released, FIXTURES, after_place, cli_error, run_cli, torus

TOL = 1e-9


def read_obj(path):
    """(positions, faces) of a plain OBJ (v and f lines; f v or f v/vt)."""
    P, F = [], []
    for line in open(path):
        parts = line.split()
        if parts and parts[0] == "v":
            P.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            F.append([int(p.split("/")[0]) - 1 for p in parts[1:4]])
    return np.array(P), np.array(F, dtype=np.int64)


def cli_global(tmp_path, mesh, *options):
    flat = tmp_path / "flat.obj"
    code, report, err = run_cli(
        ["global", str(mesh), "-o", str(tmp_path / "out.obj"), "--flat", str(flat), "-q", *options], tmp_path
    )
    assert code == 0, err
    P, F = read_obj(flat)
    return P[:, :2], F, report


def assert_same_map(py, cli):
    (uv, F_uv, report), (cli_uv, cli_F, cli_report) = py, cli
    assert report["command"] == cli_report["command"] == "global"
    assert report["method"] == cli_report["method"]
    assert set(report) == set(cli_report)
    assert set(report["metrics"]) == set(cli_report["metrics"])
    assert np.array_equal(F_uv, cli_F)
    assert uv.shape == cli_uv.shape
    assert np.max(np.abs(uv - cli_uv)) < TOL
    for key in ["conformal_energy", "uniformity_energy"]:
        assert abs(report["metrics"][key] - cli_report["metrics"][key]) < TOL, key
    g, c = report["global"], cli_report["global"]
    assert g["form"] == c["form"] and g["genus"] == c["genus"]
    assert np.max(np.abs(np.array(g["period_matrix"]) - np.array(c["period_matrix"]))) < TOL
    assert g["zeros"] == c["zeros"]
    assert g["objective"]["objective"] == c["objective"]["objective"]


@pytest.mark.parametrize(
    "options",
    [
        {},  # uniform (default)
        {"objective": "basis"},
        {"objective": "least-uniform", "starts": 4},
        {"objective": "uniform", "form": 1, "conjugate": "gu-yau", "root": 5},
    ],
)
def test_eightsim_matches_cli(options, tmp_path):
    mesh = FIXTURES / "eightsim.obj"
    V, F = conformap.read_mesh(mesh)
    py = conformap.global_map(V, F, **options)
    flags = []
    for key, value in options.items():
        flags += [f"--{key}", str(value)]
    assert_same_map(py, cli_global(tmp_path, mesh, *flags))
    uv, F_uv, report = py
    # the seamed layout: one row per corner class; F_uv has F's rows, corners of a vertex
    # split only along the seams
    assert F_uv.shape == F.shape and F_uv.dtype == np.int64
    assert uv.dtype == np.float64 and uv.shape[1] == 2
    assert uv.shape[0] > V.shape[0]  # genus 2: seams split vertices
    assert set(np.unique(F_uv)) == set(range(uv.shape[0]))
    owner = np.full(uv.shape[0], -1)
    owner[F_uv.ravel()] = F.ravel()
    assert np.array_equal(owner[F_uv], F)  # every corner class belongs to one vertex
    # vt as the CLI writes it: the layout fitted into the unit square
    g = report["global"]
    vt = (uv - np.array(g["uv_offset"])) * g["uv_scale"]
    assert vt.min() > -1e-12 and vt.max() < 1 + 1e-12
    assert report["metrics"]["folds_outside_zeros"] == 0


def test_write_seamed_layout_as_the_cli(tmp_path):
    mesh = FIXTURES / "eightsim.obj"
    V, F = conformap.read_mesh(mesh)
    uv, F_uv, report = conformap.global_map(V, F)
    g = report["global"]
    out = tmp_path / "py.obj"
    conformap.write_mesh(out, V, F, uv=(uv - g["uv_offset"]) * g["uv_scale"], F_uv=F_uv)
    cli_global(tmp_path, mesh)  # writes tmp_path / "out.obj"
    body = lambda p: [l for l in p.read_text().splitlines() if not l.startswith("#")]
    mine, theirs = body(out), body(tmp_path / "out.obj")
    assert [l for l in mine if l.startswith("f ")] == [l for l in theirs if l.startswith("f ")]
    vt = lambda lines: np.array([[float(x) for x in l.split()[1:3]] for l in lines if l.startswith("vt ")])
    assert np.max(np.abs(vt(mine) - vt(theirs))) < 1e-12
    with pytest.raises(conformap.ConformapError, match="F_uv has 3 rows, F 350"):
        conformap.write_mesh(out, V, F, uv=uv, F_uv=F_uv[:3])
    with pytest.raises(conformap.ConformapError, match="F_uv needs uv"):
        conformap.write_mesh(out, V, F, F_uv=F_uv)


def test_emphasize_region_and_halftunnel_match_cli(tmp_path):
    mesh = FIXTURES / "eightsim.obj"
    V, F = conformap.read_mesh(mesh)
    region = np.arange(40)
    (tmp_path / "region.txt").write_text("\n".join(map(str, region)))
    py = conformap.global_map(V, F, "emphasize", region=region)
    assert_same_map(py, cli_global(tmp_path, mesh, "--objective", "emphasize", "--region", str(tmp_path / "region.txt")))
    share = py[2]["global"]["objective"]["emphasis"]["share"]
    de = conformap.global_map(V, F, "de-emphasize", region=region.tolist())[2]["global"]["objective"]["emphasis"]["share"]
    assert share > de  # the emphasized region gets more of the parameter area
    # three boundary loops, genus 0: the double covering (genus 2)
    mesh = FIXTURES / "halftunnel.obj"
    V, F = conformap.read_mesh(mesh)
    py = conformap.global_map(V, F, return_mesh=True)
    assert_same_map(py[:3], cli_global(tmp_path, mesh))
    assert py[2]["global"]["double_covered"] is True
    assert np.array_equal(py[4], F) and np.array_equal(py[3], V)  # no chord split: the input


def test_zeros_objective_matches_cli(tmp_path):
    mesh = FIXTURES / "eightsim.obj"
    V, F = conformap.read_mesh(mesh)
    py = conformap.global_map(V, F, "zeros", zeros=[10])
    assert_same_map(py, cli_global(tmp_path, mesh, "--objective", "zeros", "--zeros", "10"))
    target = py[2]["global"]["objective"]["zeros"]["targets"][0]
    assert target["vertex"] == 10 and target["ring_distance"] is not None


def test_zeros_on_genus_1_has_the_cli_message(tmp_path):
    V, F = torus()
    path = tmp_path / "torus.obj"
    conformap.write_mesh(path, V, F)
    with pytest.raises(conformap.ConformapError) as info:
        conformap.global_map(V, F, "zeros", zeros=[3])
    code, message, hint = cli_error(["global", str(path), "-o", str(tmp_path / "o.obj"), "-q",
                                     "--objective", "zeros", "--zeros", "3"], tmp_path)
    assert code == info.value.exit_code
    assert after_place(str(info.value).splitlines()[0], "<arrays>") == after_place(message, str(path))
    assert "genus ≥ 2" in message
    # the torus itself maps (genus 1: no zeros, one period lattice)
    uv, F_uv, report = conformap.global_map(V, F)
    assert report["global"]["genus"] == 1 and report["global"]["zeros"] == []
    assert report["metrics"]["flipped_faces"] == 0


def test_global_errors(tmp_path):
    mesh = FIXTURES / "eightsim.obj"
    V, F = conformap.read_mesh(mesh)
    n, m = V.shape[0], F.shape[0]
    # a root that is not a vertex: the CLI's message (a usage error, exit 2)
    with pytest.raises(conformap.ConformapError) as info:
        conformap.global_map(V, F, root=n)
    code, message, _ = cli_error(["global", str(mesh), "-o", str(tmp_path / "o.obj"), "-q", "--root", str(n)], tmp_path)
    assert code == info.value.exit_code == 2
    # the CLI's message, the flag spelled as the keyword
    assert str(info.value).splitlines()[0] == message.replace(f"--root {n}", f"root={n}")
    # a region face out of range: the CLI's message with region[k] for the file line
    (tmp_path / "region.txt").write_text(f"1\n{m + 4}\n")
    with pytest.raises(conformap.ConformapError) as info:
        conformap.global_map(V, F, "emphasize", region=[1, m + 4])
    code, message, hint = cli_error(["global", str(mesh), "-o", str(tmp_path / "o.obj"), "-q", "--objective",
                                     "emphasize", "--region", str(tmp_path / "region.txt")], tmp_path)
    assert code == info.value.exit_code == 1 and info.value.hint == hint
    assert after_place(str(info.value).splitlines()[0], "region[1]") == after_place(
        message, f"{tmp_path / 'region.txt'} line 2")
    # a disk is not a surface with handles: the CLI's message
    W, G = conformap.read_mesh(FIXTURES / "woody.obj")
    with pytest.raises(conformap.ConformapError) as info:
        conformap.global_map(W, G)
    code, message, _ = cli_error(["global", str(FIXTURES / "woody.obj"), "-o", str(tmp_path / "o.obj"), "-q"], tmp_path)
    assert code == info.value.exit_code == 1
    assert after_place(str(info.value).splitlines()[0], "<arrays>") == after_place(message, str(FIXTURES / "woody.obj"))
    # options in Python terms
    with pytest.raises(conformap.ConformapError, match="needs region"):
        conformap.global_map(V, F, "emphasize")
    with pytest.raises(conformap.ConformapError, match="needs zeros"):
        conformap.global_map(V, F, "zeros")
    with pytest.raises(conformap.ConformapError, match="zeros is only used"):
        conformap.global_map(V, F, zeros=[1])
    with pytest.raises(conformap.ConformapError, match="objective must be one of basis|uniform"):
        conformap.global_map(V, F, "most-uniform")
    with pytest.raises(conformap.ConformapError, match=r"zeros\[0\]: -1 is not a vertex"):
        conformap.global_map(V, F, "zeros", zeros=[-1])


def test_global_coercion():
    V, F = conformap.read_mesh(FIXTURES / "eightsim.obj")
    uv, F_uv, _ = conformap.global_map(V, F)
    uv2, F_uv2, _ = conformap.global_map(np.asfortranarray(V), np.asfortranarray(F.astype(np.int32)))
    assert np.array_equal(F_uv2, F_uv) and np.max(np.abs(uv2 - uv)) < 1e-12


def test_gil_released_during_global_map():
    V, F = conformap.read_mesh(FIXTURES / "halftunnel.obj")
    assert_gil_released(lambda: conformap.global_map(V, F))
