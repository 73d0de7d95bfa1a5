"""The API as its stubs spell it: keyword names, defaults, errors in the package's own
spellings (`<arrays>:` in front, keywords instead of CLI flags, hints that apply to arrays),
every bad value a ConformapError (never OverflowError), and the CLI's repairs."""

import ast
import inspect
import pathlib

import numpy as np
import pytest

import conformap
from conftest import FIXTURES, torus

STUBS = pathlib.Path(__file__).resolve().parents[1] / "conformap.pyi"


def stub_functions():
    """{name: [(parameter, default or inspect.Parameter.empty)]} of the stubs' functions
    (the first of overloads)."""
    tree = ast.parse(STUBS.read_text())
    out = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef) and node.name not in out:
            a = node.args
            positional = a.posonlyargs + a.args
            defaults = [inspect.Parameter.empty] * (len(positional) - len(a.defaults)) + [
                ast.literal_eval(d) for d in a.defaults
            ]
            params = list(zip([p.arg for p in positional], defaults))
            params += [
                (p.arg, inspect.Parameter.empty if d is None else ast.literal_eval(d))
                for p, d in zip(a.kwonlyargs, a.kw_defaults)
            ]
            out[node.name] = params
    return out


def test_signatures_are_the_stubs():
    stubs = stub_functions()
    assert len(stubs) == 12
    for name, params in stubs.items():
        runtime = inspect.signature(getattr(conformap, name)).parameters
        assert [p for p, _ in params] == list(runtime), name
        for p, default in params:
            assert runtime[p].default == default, (name, p, runtime[p].default, default)


def test_max_area_scale_default_shown():
    assert inspect.signature(conformap.mobius).parameters["max_area_scale"].default == 10.0


@pytest.fixture(scope="module")
def woody():
    return conformap.read_mesh(FIXTURES / "woody.obj")


def test_every_function_by_keyword(woody, tmp_path):
    V, F = woody
    uv, _ = conformap.disk_map(V=V, F=F, method="harmonic")
    assert uv.shape == (V.shape[0], 2)
    assert conformap.metrics(V=V, F=F, param=uv)["metrics"]["flipped_faces"] == 0
    assert conformap.info(V=V, F=F)["boundary_loop_sizes"] == [119]
    flat, _ = conformap.flatten(V=V, F=F, boundary="free")
    assert flat.shape == uv.shape
    moved, _ = conformap.mobius(V=V, F=F, param=uv)
    assert moved.shape == uv.shape
    auv, afuv, _ = conformap.atlas(V=V, F=F)
    assert afuv.shape == F.shape
    Vs, Fs = conformap.read_mesh(path=FIXTURES / "spot.obj")
    S, _ = conformap.sphere_map(V=Vs, F=Fs)
    assert np.allclose(np.linalg.norm(S, axis=1), 1.0)
    Vt, Ft = torus()
    guv, gfuv, _ = conformap.global_map(V=Vt, F=Ft)
    assert gfuv.shape == Ft.shape
    out = tmp_path / "w.obj"
    conformap.write_mesh(path=out, V=V, F=F, uv=(uv + 1) / 2, F_uv=None)
    assert conformap.read_mesh(out)[1].shape == F.shape
    W = V.copy()
    W[:, 2] = 0.001 * V[:, 0]
    P, PF, _ = conformap.morph(surfaces=[(V, F), (W, F)], landmarks=[[300, 400], [300, 400]], frames=2)
    assert P.shape == (2, V.shape[0], 3)
    R, RF, origin = conformap.repair(V=V, F=F)
    assert RF.shape == F.shape and (origin == np.arange(V.shape[0])).all()


def raises(call, exit_code=None):
    """The ConformapError `call()` raises (not OverflowError, TypeError, …)."""
    with pytest.raises(conformap.ConformapError) as info:
        call()
    if exit_code is not None:
        assert info.value.exit_code == exit_code, str(info.value)
    return info.value


def test_errors_use_python_spellings(woody):
    V, F = woody
    cases = [
        (lambda: conformap.disk_map(V, F, tol=-1.0), "tol"),
        (lambda: conformap.disk_map(V, F, outer=5), "outer=5"),
        (lambda: conformap.global_map(*torus(), root=10**6), "root=1000000"),
        (lambda: conformap.morph([(V, F), (V, F)], [[300, 400], [300, 400]], frames=1), "frames=1"),
        (lambda: conformap.morph([(V, F), (V, F)], [[300, 400], [300, 400]], 4, lambda_=-1.0), "lambda_"),
    ]
    for call, keyword in cases:
        e = raises(call)
        assert keyword in str(e), str(e)
        assert "--" not in str(e), str(e)


def test_array_errors_say_arrays_first(woody):
    V, F = woody
    bad = F.copy()
    bad[0, 1] = V.shape[0] + 5
    for call in [
        lambda: conformap.disk_map(V, bad),
        lambda: conformap.disk_map(V[:, :2], F),
        lambda: conformap.disk_map(V, F.astype(np.float64)),
        lambda: conformap.info(V, np.vstack([F, F[:1]])),
    ]:
        assert str(raises(call, 1)).startswith("<arrays>: ")


def test_face_index_messages(woody):
    V, F = woody
    big = F.astype(np.uint64)
    big[3, 2] = 2**64 - 1
    e = raises(lambda: conformap.disk_map(V, big), 1)
    assert "18446744073709551615" in str(e) and "face 3" in str(e), str(e)
    e = raises(lambda: conformap.disk_map(V, F[:, :2]), 1)
    assert "(m, 3)" in str(e), str(e)
    e = raises(lambda: conformap.disk_map(V, F + 1), 1)
    assert e.hint is not None and "1-based" in e.hint and "F - 1" in e.hint, e.hint


def test_negative_counts_are_conformap_errors(woody):
    V, F = woody
    W = V.copy()
    W[:, 2] = 0.001 * V[:, 0]
    for call, name in [
        (lambda: conformap.disk_map(V, F, max_iter=-1), "max_iter"),
        (lambda: conformap.disk_map(V, F, max_memory=-1), "max_memory"),
        (lambda: conformap.global_map(*torus(), form=-1), "form"),
        (lambda: conformap.morph([(V, F), (W, F)], [[300, 400], [300, 400]], frames=-3), "frames"),
        (lambda: conformap.atlas(V, F, resolution=-1), "resolution"),
        (lambda: conformap.disk_map(V, F, max_iter=2**70), "max_iter"),
    ]:
        e = raises(call, 2)
        assert name in str(e), str(e)


def test_max_memory_zero_is_refused_like_the_cli(woody):
    V, F = woody
    e = raises(lambda: conformap.disk_map(V, F, max_memory=0), 2)
    assert "max_memory" in str(e)
    # one byte is a limit, and the refusal says so in bytes, keyword-spelled
    e = raises(lambda: conformap.disk_map(V, F, max_memory=1), 1)
    assert "max_memory" in str(e) and "--" not in str(e) + str(e.hint), str(e)


def test_hints_apply_to_arrays(woody):
    V, F = woody
    e = raises(lambda: conformap.disk_map(V, np.vstack([F, F[:1]])), 1)
    assert "conformap.repair(V, F)" in e.hint and "--" not in e.hint, e.hint
    nan = V.copy()
    nan[7, 1] = np.nan
    e = raises(lambda: conformap.disk_map(nan, F), 1)
    assert "vertex 7" in str(e) and "file" not in e.hint and "--" not in e.hint, e.hint


def test_write_mesh_refuses_nan_uv_and_empty_meshes(woody, tmp_path):
    V, F = woody
    uv = np.zeros((V.shape[0], 2))
    uv[5] = np.nan
    e = raises(lambda: conformap.write_mesh(tmp_path / "a.obj", V, F, uv=uv), 1)
    assert "row 5" in str(e) and "bug" not in str(e), str(e)
    e = raises(lambda: conformap.write_mesh(tmp_path / "b.obj", np.zeros((0, 3)), np.zeros((0, 3), int)), 1)
    assert not (tmp_path / "b.obj").exists()


def test_repair_matches_the_cli(tmp_path):
    # a triangle soup: every face its own three vertices; welding gives back woody
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    soup_V = V[F.ravel()]
    soup_F = np.arange(3 * F.shape[0]).reshape(-1, 3)
    raises(lambda: conformap.disk_map(soup_V, soup_F))
    R, RF, origin = conformap.repair(soup_V, soup_F)
    assert R.shape == V.shape and RF.shape == F.shape
    assert np.array_equal(R, soup_V[origin])
    assert conformap.info(R, RF)["boundary_loop_sizes"] == [119]
    # the file of the same soup, read with repair=True: the same arrays
    path = tmp_path / "soup.obj"
    conformap.write_mesh(path, soup_V, soup_F)
    assert conformap.read_mesh(path)[0].shape == soup_V.shape  # valid, but 1267 pieces
    V2, F2 = conformap.read_mesh(path, repair=True)
    assert np.array_equal(V2, R) and np.array_equal(F2, RF)
    # a dirty file the CLI repairs
    Vd, Fd = conformap.read_mesh(FIXTURES / "bad" / "dirty_disk.obj", repair=True)
    assert conformap.info(Vd, Fd)["boundary_loop_sizes"]


def test_global_map_topology_opt():
    V, F = torus()
    uv, F_uv, report = conformap.global_map(V, F, topology_opt=True)
    assert F_uv.shape == F.shape
    assert "topology_opt" in report, sorted(report)


def test_landmark_dicts_match_by_name(woody):
    V, F = woody
    W = V.copy()
    W[:, 0] *= 1.2
    a = {"nose": 300, "eye": 400, "ear": 350}
    b = {"ear": 350, "nose": 300, "eye": 400}  # the same landmarks, another insertion order
    P1, _, r1 = conformap.morph([(V, F), (W, F)], [a, a], frames=3)
    P2, _, r2 = conformap.morph([(V, F), (W, F)], [a, b], frames=3)
    assert np.array_equal(P1, P2)


def test_morph_too_many_frames_raises_before_allocating(woody):
    V, F = woody
    W = V.copy()
    W[:, 0] *= 1.2
    e = raises(lambda: conformap.morph([(V, F), (W, F)], [[300, 400], [300, 400]], frames=10**9), 1)
    assert "frames=1000000000" in str(e) and e.hint, str(e)
