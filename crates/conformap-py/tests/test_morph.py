"""morph against the CLI's `conformap morph` (frames and report), its errors with the CLI's
messages, coercion, and the GIL released during the morph. Small key surfaces (woody and a
bent copy) keep it fast; the ICT faces are the CLI's and the library's tests."""

import numpy as np
import pytest

import conformap
from conftest import assert_gil_released, FIXTURES, after_place, cli_error, run_cli

TOL = 1e-9


def assert_close(a, b, where="morph"):
    """JSON values equal, numbers to TOL (relative above 1), `*_ms` timings skipped."""
    if isinstance(a, dict):
        assert set(a) == set(b), where
        for key in a:
            if not (key.endswith("_ms") or key == "timings_ms"):
                assert_close(a[key], b[key], f"{where}.{key}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_close(x, y, f"{where}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        assert abs(a - b) <= TOL * max(1.0, abs(b)), (where, a, b)
    else:
        assert a == b, (where, a, b)


def interior_vertices(F):
    edges = np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1)
    uniq, count = np.unique(edges, axis=0, return_counts=True)
    boundary = set(uniq[count == 1].ravel())
    return np.array([v for v in range(F.max() + 1) if v not in boundary])


@pytest.fixture(scope="module")
def keys():
    """Two key surfaces (woody, and woody bent over a cylinder and stretched) and five
    landmarks: the interior vertices nearest five points of woody."""
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    c, size = V.mean(axis=0), np.ptp(V, axis=0).max()
    W = V.copy()
    W[:, 0] *= 1.3
    W[:, 2] = 0.3 * size * np.sin(V[:, 1] / size * 2.0)
    inner = interior_vertices(F)
    targets = c + size * np.array([[0, 0, 0], [0.15, 0, 0], [0, 0.2, 0], [-0.1, -0.2, 0], [0.05, 0.3, 0]])
    lm = [int(inner[np.argmin(np.linalg.norm(V[inner] - t, axis=1))]) for t in targets]
    return (V, F), (W, F), lm


def write_inputs(tmp_path, keys, landmark_lists):
    (V, F), (W, _), _ = keys
    paths = []
    for k, (X, lms) in enumerate(zip([V, W], landmark_lists)):
        mesh, lmf = tmp_path / f"s{k}.obj", tmp_path / f"s{k}.landmarks.txt"
        conformap.write_mesh(mesh, X, F)
        lmf.write_text("".join(f"{v} {j}\n" for j, v in enumerate(lms)))
        paths.append((mesh, lmf))
    return paths


def test_morph_matches_cli(keys, tmp_path):
    (V, F), (W, _), lm = keys
    frames, Fm, report = conformap.morph([(V, F), (W, F)], [lm, lm], 5)
    assert frames.shape == (5, V.shape[0], 3) and frames.dtype == np.float64
    assert np.array_equal(Fm, F)
    assert np.array_equal(frames[0], V)  # frame 0 is S1, bit for bit
    paths = write_inputs(tmp_path, keys, [lm, lm])
    out = tmp_path / "frames"
    out.mkdir()
    code, cli, err = run_cli(["morph", *[str(m) for m, _ in paths], "--landmarks", *[str(l) for _, l in paths],
                              "--frames", "5", "-o", f"{out}/"], tmp_path)
    assert code == 0, err
    for i in range(5):
        P, _ = conformap.read_mesh(out / f"frame_{i:04d}.obj")
        assert np.max(np.abs(P - frames[i])) < TOL, i
    assert set(report) == set(cli)
    assert report["key_frames"] == cli["key_frames"] == [0, 4]
    assert report["method"] == cli["method"] == "soft"
    assert report["landmark_files"] == ["<landmarks[0]>", "<landmarks[1]>"]
    assert [i["path"] for i in report["inputs"]] == ["<surfaces[0]>", "<surfaces[1]>"]
    # the library's report, number for number (timings aside)
    assert_close(report["morph"], cli["morph"])
    # the landmarks of the last key frame land near the second surface's
    assert report["morph"]["keys"][1]["landmark_error_max_rel"] < 0.05


def test_morph_hard_and_coercion(keys):
    (V, F), (W, _), lm = keys
    hard, _, report = conformap.morph([(V, F), (W, F)], [lm, lm], 3, hard=True)
    assert report["method"] == "hard"
    assert report["morph"]["keys"][1]["landmark_error_max_rel"] < 1e-9
    # Fortran order, int32 faces, landmark arrays, a dict of named landmarks: the same frames
    lm_arr = np.array(lm, dtype=np.int32)
    same, _, _ = conformap.morph(
        [(np.asfortranarray(V), np.asfortranarray(F.astype(np.int32))), (W.tolist(), F)],
        [lm_arr, {str(j): v for j, v in enumerate(lm)}], 3, hard=True)
    assert np.max(np.abs(same - hard)) < 1e-12


def test_landmark_lists_of_different_lengths_have_the_cli_message(keys, tmp_path):
    (V, F), (W, _), lm = keys
    with pytest.raises(conformap.ConformapError) as info:
        conformap.morph([(V, F), (W, F)], [lm, lm[:4]], 4)
    paths = write_inputs(tmp_path, keys, [lm, lm[:4]])
    code, message, hint = cli_error(["morph", *[str(m) for m, _ in paths], "--landmarks",
                                     *[str(l) for _, l in paths], "--frames", "4",
                                     "-o", str(tmp_path / "m.glb")], tmp_path)
    assert code == info.value.exit_code == 1
    assert info.value.hint == hint
    py = str(info.value).splitlines()[0]
    assert after_place(py, "<landmarks[1]>") == after_place(message, str(paths[1][1]))
    assert "landmark 4 is \"<none>\"" in py


def test_morph_errors(keys, tmp_path):
    (V, F), (W, _), lm = keys
    # a landmark that is not a vertex: the CLI's message
    bad = lm[:-1] + [V.shape[0] + 2]
    with pytest.raises(conformap.ConformapError) as info:
        conformap.morph([(V, F), (W, F)], [lm, bad], 4)
    paths = write_inputs(tmp_path, keys, [lm, bad])
    code, message, hint = cli_error(["morph", *[str(m) for m, _ in paths], "--landmarks",
                                     *[str(l) for _, l in paths], "--frames", "4",
                                     "-o", str(tmp_path / "m.glb")], tmp_path)
    assert code == info.value.exit_code == 1 and info.value.hint == hint
    assert after_place(str(info.value).splitlines()[0], "<landmarks[1]>") == after_place(message, str(paths[1][1]))
    # counts and options: the CLI's usage messages (exit 2)
    with pytest.raises(conformap.ConformapError, match="2 surfaces but 1 landmark files") as info:
        conformap.morph([(V, F), (W, F)], [lm], 4)
    assert info.value.exit_code == 2
    with pytest.raises(conformap.ConformapError, match="a morph needs at least two surfaces"):
        conformap.morph([(V, F)], [lm], 4)
    with pytest.raises(conformap.ConformapError, match="frames=1 cannot hold 2 key surfaces"):
        conformap.morph([(V, F), (W, F)], [lm, lm], 1)
    with pytest.raises(conformap.ConformapError, match="lambda_ must be a finite number > 0"):
        conformap.morph([(V, F), (W, F)], [lm, lm], 4, lambda_=-1.0)
    with pytest.raises(conformap.ConformapError, match="exclude each other"):
        conformap.morph([(V, F), (W, F)], [lm, lm], 4, lambda_=1.0, hard=True)
    # a bad surface is named
    G = F.copy()
    G[3, 0] = V.shape[0]
    with pytest.raises(conformap.ConformapError, match=r"^<surfaces\[1\]>: face 3: vertex index"):
        conformap.morph([(V, F), (W, G)], [lm, lm], 4)
    with pytest.raises(conformap.ConformapError, match=r"<landmarks\[0\]>: 1 landmark\(s\) given"):
        conformap.morph([(V, F), (W, F)], [lm[:1], lm], 4)


def test_gil_released_during_morph(keys):
    (V, F), (W, _), lm = keys
    assert_gil_released(lambda: conformap.morph([(V, F), (W, F)], [lm, lm], 10))
