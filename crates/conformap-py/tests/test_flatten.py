"""flatten (boundary first flattening) against the CLI, boundary values in memory, errors."""
import numpy as np
import pytest

import conformap
from conftest import FIXTURES, run_cli


def test_free_boundary_matches_cli_and_keeps_lengths(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spothead.obj")
    uv, report = conformap.flatten(V, F)
    code, cli, err = run_cli(["flatten", str(FIXTURES / "spothead.obj"), "-o", str(tmp_path / "f.obj")], tmp_path)
    assert code == 0, err
    assert uv.shape == (V.shape[0], 2)
    assert set(report) == set(cli)
    assert report["flatten"]["boundary"] == "free"
    assert report["metrics"]["flipped_faces"] == cli["metrics"]["flipped_faces"] == 0
    assert report["metrics"]["conformal_energy"] == pytest.approx(cli["metrics"]["conformal_energy"], rel=1e-12)
    # u = 0: every boundary edge keeps its 3D length up to the closing (< 1e-3 relative)
    F = np.asarray(F)
    directed = {(int(a), int(b)) for f in F for a, b in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    boundary = np.array([e for e in directed if (e[1], e[0]) not in directed])
    assert len(boundary) == 48  # spothead's one loop
    l3 = np.linalg.norm(V[boundary[:, 0]] - V[boundary[:, 1]], axis=1)
    l2 = np.linalg.norm(uv[boundary[:, 0]] - uv[boundary[:, 1]], axis=1)
    assert np.max(np.abs(l2 / l3 - 1.0)) < 1e-3


def test_polygon_values_in_memory_give_a_triangle(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    _, free = conformap.flatten(V, F)
    # three corners a third of the boundary apart: an equilateral triangle
    _, rect = conformap.flatten(V, F, "rectangle")
    corners = rect["flatten"]["corners"]
    assert len(corners) == 4
    tri = {corners[0]: 120.0, corners[1]: 120.0, corners[2]: 120.0}
    uv, report = conformap.flatten(V, F, "polygon", tri)
    assert report["flatten"]["boundary"] == "polygon"
    assert report["metrics"]["flipped_faces"] == 0
    p = uv[corners[:3]]
    sides = [np.linalg.norm(p[i] - p[(i + 1) % 3]) for i in range(3)]
    # three 60° corners and straight sides: the three sides are equal
    assert max(sides) / min(sides) - 1.0 < 1e-9


def test_bad_arguments_raise_conformap_error():
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    with pytest.raises(conformap.ConformapError):
        conformap.flatten(V, F, "square")
    with pytest.raises(conformap.ConformapError):
        conformap.flatten(V, F, "polygon")  # no values
    with pytest.raises(conformap.ConformapError):
        conformap.flatten(V, F, "free", {0: 1.0})  # values for a mode without them
    S, G = conformap.read_mesh(FIXTURES / "spot.obj")
    with pytest.raises(conformap.ConformapError, match="conformap sphere"):
        conformap.flatten(S, G)


def test_atlas_of_spot_matches_cli_and_is_overlap_free(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    uv, F_uv, report = conformap.atlas(V, F)
    code, cli, err = run_cli(["atlas", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "a.obj")], tmp_path)
    assert code == 0, err
    assert F_uv.shape == F.shape
    assert uv.min() >= 0.0 and uv.max() <= 1.0
    assert report["atlas"]["overlap"]["covered_twice"] == cli["atlas"]["overlap"]["covered_twice"] == 0
    assert report["atlas"]["area_spread"] == pytest.approx(cli["atlas"]["area_spread"], rel=1e-12)
    p = uv[F_uv]
    signed = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])
    assert np.all(signed > 0)  # no face turned over


def test_atlas_seamless_matches_cli(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    uv, F_uv, report = conformap.atlas(V, F, seamless=True)
    code, cli, err = run_cli(["atlas", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "a.obj"), "--seamless"], tmp_path)
    assert code == 0, err
    a = report["atlas"]
    assert a["seamless"] is True
    assert a["seam_rotation_error_max"] <= 1e-6 and a["seam_rigid_residual_max"] <= 1e-6
    assert a["area_spread"] == pytest.approx(cli["atlas"]["area_spread"], rel=1e-12)
    for c in a["cone_list"]:
        q = c["angle_deg"] / 90.0
        assert abs(q - round(q)) < 1e-9
    assert uv.min() >= 0.0 and uv.max() <= 1.0
    with pytest.raises(conformap.ConformapError, match="seamless takes cones"):
        conformap.atlas(V, F, cones="auto", seamless=True)


def test_atlas_polish_matches_cli_and_lowers_the_distortion(tmp_path):
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    _, _, plain = conformap.atlas(V, F, polish=False)
    uv, F_uv, report = conformap.atlas(V, F, polish=True)
    code, cli, err = run_cli(["atlas", str(FIXTURES / "spot.obj"), "-o", str(tmp_path / "a.obj"), "--polish"], tmp_path)
    assert code == 0, err
    a = report["atlas"]
    assert a["area_spread"] == pytest.approx(cli["atlas"]["area_spread"], rel=1e-12)
    before, after = a["polish_energy"]
    assert after < before
    assert plain["atlas"]["polish_energy"] is None
    assert plain["atlas"]["polished_components"] == 0 and a["polished_components"] == 1
    assert a["area_spread"] < plain["atlas"]["area_spread"] - 0.03
    assert a["angle_mean_deg"] < plain["atlas"]["angle_mean_deg"]
    assert a["flipped"] == 0 and a["overlap"]["covered_twice"] == 0
    assert uv.min() >= 0.0 and uv.max() <= 1.0
    # the default ("auto") polishes spot (its cone metric spreads 0.82), as "always" does
    auto_uv, _, auto = conformap.atlas(V, F)
    assert auto["atlas"]["polish"] == "auto" and auto["atlas"]["polished_components"] == 1
    assert np.array_equal(auto_uv, uv)
    assert conformap.atlas(V, F, polish="never")[2]["atlas"]["polish_energy"] is None
    with pytest.raises(conformap.ConformapError, match="polish must be"):
        conformap.atlas(V, F, polish="sometimes")
    # with seamless the seams keep their quarter turns
    _, _, both = conformap.atlas(V, F, polish=True, seamless=True)
    assert both["atlas"]["seam_rotation_error_max"] <= 1e-6
    assert both["atlas"]["seam_rigid_residual_max"] <= 1e-6


def test_atlas_cones_given_auto_and_unpacked():
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    _, _, placed = conformap.atlas(V, F, cones=8)
    pairs = [(c["vertex"], c["angle_deg"]) for c in placed["atlas"]["cone_list"]]
    assert len(pairs) == 8
    # the placed cones given back, as a list and as an array: the same map
    for given in (pairs, np.array(pairs)):
        _, _, report = conformap.atlas(V, F, cones=given)
        assert report["atlas"]["area_spread"] == pytest.approx(placed["atlas"]["area_spread"], abs=1e-9)
    # Gauss–Bonnet: the curvatures 360 - angle must add up to 720 on closed genus 0
    with pytest.raises(conformap.ConformapError, match="Gauss–Bonnet"):
        conformap.atlas(V, F, cones=[(v, a + 10.0) for v, a in pairs])
    with pytest.raises(conformap.ConformapError, match=r"cones\[0\]"):
        conformap.atlas(V, F, cones=[(len(V), 270.0)])
    # auto: the fewest cones that reach the spread asked for
    _, _, auto = conformap.atlas(V, F, cones="auto", max_area_spread=1.2)
    assert auto["atlas"]["area_spread"] <= 1.2
    assert auto["atlas"]["auto_cones"]["counts"] == [auto["atlas"]["cones"]]
    # packing off: texture units are layout units (spot is about 1 across), no overlap
    uv, F_uv, kept = conformap.atlas(V, F, pack="none")
    assert kept["atlas"]["packing"] == "none"
    assert uv.max() > 1.0
    assert kept["atlas"]["overlap"]["covered_twice"] == 0


def test_atlas_splits_a_non_manifold_vertex_of_arrays():
    # two hexagonal fans sharing their centre (one vertex, two fans: non-manifold): atlas
    # splits it as the CLI does, every other function keeps refusing the arrays
    ring = [(np.cos(t), np.sin(t)) for t in np.linspace(0.0, 2.0 * np.pi, 7)[:-1]]
    V = [(0.0, 0.0, 0.0)]
    V += [(x, y, 0.3) for x, y in ring]
    V += [(x, 0.3, y) for x, y in ring]
    V = np.array(V)
    F = np.array([(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)] + [(0, 7 + k, 7 + (k + 1) % 6) for k in range(6)])
    uv, F_uv, report = conformap.atlas(V, F)
    split = report["atlas"]["non_manifold"]
    assert split["vertices_split"] == 1 and split["vertices_added"] == 1
    assert split["split_vertices"] == [0]
    assert F_uv.shape == F.shape
    assert uv.min() >= 0.0 and uv.max() <= 1.0
    p = uv[F_uv]
    signed = (p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1]) - (p[:, 1, 1] - p[:, 0, 1]) * (p[:, 2, 0] - p[:, 0, 0])
    assert np.all(signed > 0)
    assert report["atlas"]["overlap"]["covered_twice"] == 0
    with pytest.raises(conformap.ConformapError, match="non-manifold"):
        conformap.flatten(V, F)
