"""mobius against the CLI's `conformap mobius` on the fixtures: the same inputs (the CLI's
own --flat map), the same optimum, the same report numbers; errors with the CLI's message."""
import numpy as np
import pytest

import conformap
from conftest import FIXTURES, after_place, cli_error, run_cli

TOL = 1e-9  # the bound on every energy and map value


def cli_flat(tmp_path, *args):
    """Runs a CLI map command with --flat; returns (flat positions, report)."""
    flat = tmp_path / "flat.obj"
    code, report, err = run_cli([*args, "-o", str(tmp_path / "out.obj"), "--flat", str(flat)], tmp_path)
    assert code == 0, err
    return conformap.read_mesh(flat)[0], report


def assert_reports_agree(py, cli, keys):
    assert py["command"] == cli["command"] == "mobius"
    assert py["method"] == cli["method"]
    assert set(py) == set(cli)
    assert set(py["metrics"]) == set(cli["metrics"])
    for key in keys:
        assert abs(py["metrics"][key] - cli["metrics"][key]) < TOL, key
    assert py["metrics"]["flipped_faces"] == cli["metrics"]["flipped_faces"]
    assert py["solver"]["converged"] == cli["solver"]["converged"]
    assert py["solver"]["iterations"] == cli["solver"]["iterations"]


def test_disk_uniform_matches_cli(tmp_path):
    mesh = str(FIXTURES / "woody.obj")
    start, _ = cli_flat(tmp_path, "disk", mesh)  # the CLI's disk map, bit for bit
    (tmp_path / "start.obj").write_bytes((tmp_path / "flat.obj").read_bytes())
    V, F = conformap.read_mesh(mesh)
    moved, report = conformap.mobius(V, F, start[:, :2], domain="disk", objective="uniform")
    cli_moved, cli = cli_flat(
        tmp_path, "mobius", mesh, str(tmp_path / "start.obj"), "--domain", "disk", "--objective", "uniform"
    )
    assert moved.shape == (V.shape[0], 2)
    assert np.max(np.abs(moved - cli_moved[:, :2])) < TOL
    assert_reports_agree(report, cli, ["conformal_energy", "uniformity_energy", "uniformity_energy_before"])
    # a real improvement, and the map stays in the disk
    assert report["metrics"]["uniformity_energy"] < report["metrics"]["uniformity_energy_before"]
    assert np.all(np.hypot(moved[:, 0], moved[:, 1]) <= 1.0 + 1e-9)
    assert report["param"] == {"path": "<array>", "map_from": "flat positions"}


def test_sphere_uniform_matches_cli(tmp_path):
    mesh = str(FIXTURES / "spot.obj")
    start, _ = cli_flat(tmp_path, "sphere", mesh)
    (tmp_path / "start.obj").write_bytes((tmp_path / "flat.obj").read_bytes())
    V, F = conformap.read_mesh(mesh)
    moved, report = conformap.mobius(V, F, start, domain="sphere")
    cli_moved, cli = cli_flat(
        tmp_path, "mobius", mesh, str(tmp_path / "start.obj"), "--domain", "sphere", "--objective", "uniform"
    )
    assert moved.shape == V.shape
    assert np.max(np.abs(moved - cli_moved)) < TOL
    assert np.max(np.abs(np.linalg.norm(moved, axis=1) - 1.0)) < 1e-9
    assert_reports_agree(report, cli, ["uniformity_energy", "uniformity_energy_before"])


@pytest.mark.parametrize("objective", ["emphasize", "emphasize-density"])
def test_disk_emphasize_region_matches_cli(objective, tmp_path):
    mesh = str(FIXTURES / "spothead.obj")
    start, _ = cli_flat(tmp_path, "disk", mesh)
    (tmp_path / "start.obj").write_bytes((tmp_path / "flat.obj").read_bytes())
    V, F = conformap.read_mesh(mesh)
    region = np.arange(0, F.shape[0], 7)[:200]
    (tmp_path / "region.txt").write_text("# faces\n" + "\n".join(map(str, region)) + "\n")
    moved, report = conformap.mobius(V, F, start[:, :2], "disk", objective, region=region.astype(np.int32))
    cli_moved, cli = cli_flat(
        tmp_path, "mobius", mesh, str(tmp_path / "start.obj"), "--domain", "disk",
        "--objective", objective, "--region", str(tmp_path / "region.txt"),
    )
    assert np.max(np.abs(moved - cli_moved[:, :2])) < TOL
    assert_reports_agree(report, cli, ["conformal_energy", "uniformity_energy"])
    m, c = report["solver"]["mobius"], cli["solver"]["mobius"]
    assert abs(m["region_share_after"] - c["region_share_after"]) < TOL
    assert m["region_share_after"] > m["region_share_before"]  # the region did grow
    # a list gives the same as an int32 array
    again, _ = conformap.mobius(V, F, start[:, :2], "disk", objective, region=region.tolist())
    assert np.array_equal(again, moved)


def test_mobius_coercion(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    uv, _ = conformap.disk_map(V, F)
    moved, _ = conformap.mobius(V, F, uv)
    moved_f, _ = conformap.mobius(np.asfortranarray(V), np.asfortranarray(F.astype(np.uint32)), np.asfortranarray(uv))
    assert np.max(np.abs(moved_f - moved)) < 1e-12


def test_region_out_of_range_has_the_cli_message(tmp_path):
    mesh = str(FIXTURES / "woody.obj")
    V, F = conformap.read_mesh(mesh)
    uv, _ = conformap.disk_map(V, F)
    m = F.shape[0]
    with pytest.raises(conformap.ConformapError) as info:
        conformap.mobius(V, F, uv, objective="emphasize", region=[0, 5, m])
    (tmp_path / "region.txt").write_text(f"0\n5\n{m}\n")
    conformap.write_mesh(tmp_path / "uv.obj", V, F, uv=(uv + 1) / 2)
    code, message, hint = cli_error(
        ["mobius", mesh, str(tmp_path / "uv.obj"), "--domain", "disk", "--objective", "emphasize",
         "--region", str(tmp_path / "region.txt"), "-o", str(tmp_path / "o.obj")], tmp_path)
    assert code == info.value.exit_code == 1
    py_message = str(info.value).splitlines()[0]
    assert after_place(py_message, "region[2]") == after_place(message, f"{tmp_path / 'region.txt'} line 3")
    assert info.value.hint == hint
    assert f"face {m} is out of range (the mesh has {m} faces" in py_message


def test_mobius_usage_errors():
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    uv, _ = conformap.disk_map(V, F)
    with pytest.raises(conformap.ConformapError, match="needs region") as info:
        conformap.mobius(V, F, uv, objective="emphasize")
    assert info.value.exit_code == 2
    with pytest.raises(conformap.ConformapError, match="region is only used"):
        conformap.mobius(V, F, uv, region=[1, 2])
    with pytest.raises(conformap.ConformapError, match="domain must be one of disk, sphere"):
        conformap.mobius(V, F, uv, domain="plane")
    with pytest.raises(conformap.ConformapError, match="param has 10 rows, the mesh 694 vertices"):
        conformap.mobius(V, F, uv[:10])
    with pytest.raises(conformap.ConformapError, match=r"param must have shape \(n, 3\)"):
        conformap.mobius(V, F, uv, domain="sphere")
    with pytest.raises(conformap.ConformapError, match="region\\[1\\]: -3 is not a face index"):
        conformap.mobius(V, F, uv, objective="emphasize", region=[1, -3])
    with pytest.raises(conformap.ConformapError, match="not on the unit sphere"):
        S = np.zeros((V.shape[0], 3))
        conformap.mobius(V, F, S, domain="sphere")
