"""disk_map / sphere_map against the CLI on the fixtures, coercion, metrics, I/O."""
import numpy as np
import pytest

import conformap
from conftest import FIXTURES, run_cli

E_C_TOL = 1e-9  # the bound on |E_C(python) - E_C(CLI)|


@pytest.mark.parametrize("name", ["woody.obj", "halftunnel.obj"])
def test_disk_map_matches_cli(name, tmp_path):
    V, F = conformap.read_mesh(FIXTURES / name)
    uv, report = conformap.disk_map(V, F)
    code, cli, err = run_cli(["disk", str(FIXTURES / name), "-o", str(tmp_path / "uv.obj")], tmp_path)
    assert code == 0, err
    assert uv.shape == (V.shape[0], 2) and uv.dtype == np.float64
    assert report["command"] == cli["command"] == "disk"
    assert report["method"] == cli["method"]
    assert set(report) == set(cli)  # the same report, key for key
    assert set(report["metrics"]) == set(cli["metrics"])
    assert abs(report["metrics"]["conformal_energy"] - cli["metrics"]["conformal_energy"]) < E_C_TOL
    assert report["metrics"]["flipped_faces"] == cli["metrics"]["flipped_faces"] == 0
    assert report["input"]["vertices"] == cli["input"]["vertices"]
    assert np.all(np.hypot(uv[:, 0], uv[:, 1]) <= 1.0 + 1e-9)


def test_sphere_map_matches_cli(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    S, report = conformap.sphere_map(V, F)
    code, cli, err = run_cli(["sphere", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "s.obj")], tmp_path)
    assert code == 0, err
    assert S.shape == V.shape
    assert np.max(np.abs(np.linalg.norm(S, axis=1) - 1.0)) < 1e-9
    assert set(report) == set(cli)
    for key, value in cli["metrics"].items():
        if isinstance(value, float):
            assert report["metrics"][key] == pytest.approx(value, rel=1e-9, abs=1e-12), key


def test_coercion_dtype_and_order():
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    uv, _ = conformap.disk_map(V, F)
    # Fortran order, int32 faces: the same map to rounding
    uv_f, _ = conformap.disk_map(np.asfortranarray(V), np.asfortranarray(F.astype(np.int32)))
    assert np.max(np.abs(uv_f - uv)) < 1e-12
    # float32 positions and uint16 faces from nested lists work too (a different mesh, so a
    # close map, not the same one)
    uv_32, rep = conformap.disk_map(V.astype(np.float32).tolist(), F.astype(np.uint16))
    assert rep["metrics"]["flipped_faces"] == 0
    assert np.max(np.abs(uv_32 - uv)) < 1e-3


def test_metrics_and_info_are_the_cli_dicts(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    uv, report = conformap.disk_map(V, F)
    m = conformap.metrics(V, F, uv)
    assert m["command"] == "metrics"
    assert m["metrics"]["conformal_energy"] == pytest.approx(report["metrics"]["conformal_energy"], rel=1e-12)
    i = conformap.info(V, F)
    assert i["valid"] is True and i["vertices"] == V.shape[0] and i["faces"] == F.shape[0]


def test_write_read_roundtrip(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    uv, _ = conformap.disk_map(V, F)
    out = tmp_path / "woody_uv.obj"
    conformap.write_mesh(out, V, F, uv=(uv + 1) / 2)
    V2, F2 = conformap.read_mesh(out)
    assert np.array_equal(F2, F)
    assert np.max(np.abs(V2 - V)) < 1e-12
    assert "vt " in out.read_text()


def test_sphere_uv_is_the_cli_texture(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    S, _ = conformap.sphere_map(V, F)
    uv, F_uv = conformap.sphere_uv(S, F)
    assert F_uv.shape == F.shape
    corners = uv[F_uv]  # (faces, 3, 2)
    span = corners.max(axis=1) - corners.min(axis=1)
    assert span.max() <= 0.25  # no face spans the texture (the seam is split)
    out = tmp_path / "s.obj"
    conformap.write_mesh(out, V, F, uv=uv, F_uv=F_uv)
    code, _, err = run_cli(["sphere", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "cli.obj")], tmp_path)
    assert code == 0, err
    vt = lambda p: [l for l in p.read_text().splitlines() if l.startswith("vt ")]
    assert len(vt(out)) == len(vt(tmp_path / "cli.obj")) == uv.shape[0]
