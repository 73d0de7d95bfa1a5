"""The neuroimaging and scanner formats against independent implementations: nibabel
writes GIfTI and FreeSurfer surfaces that the CLI maps, and reads what the CLI wrote
(radius-100 spheres, the input's triangles and order, the quality overlay, recomputed
here with numpy); the GIfTI files shipped with nibabel are read; PLY, STL and OFF written
by numpy (ascii and binary) give the OBJ run's map."""
import json
import os
import pathlib
import struct
import subprocess

import numpy as np
import pytest

nib = pytest.importorskip("nibabel")  # CI installs it (.ci/run)
import nibabel.freesurfer as nfs  # noqa: E402
from nibabel.gifti import GiftiCoordSystem, GiftiDataArray, GiftiImage  # noqa: E402

import conformap  # noqa: E402
from conftest import FIXTURES, cli_binary  # noqa: E402

SHARED = pathlib.Path(os.environ.get("CONFORMAP_SHARED_MESHES", "/work/shared/meshes"))
POINTSET, TRIANGLE = 1008, 1009  # NIFTI_INTENT_POINTSET, NIFTI_INTENT_TRIANGLE


def cli(*args):
    return subprocess.run([str(cli_binary()), *map(str, args)], capture_output=True, text=True,
                          check=False)


# a scanner-to-Talairach transform on the point set, kept in the sphere --flat writes
XFORM = np.array([[2.0, 0.0, 0.0, -1.5], [0.0, 0.0, 1.0, 2.0], [0.0, -1.0, 0.0, 0.25],
                  [0.0, 0.0, 0.0, 1.0]])


def write_gifti(path, V, F):
    img = GiftiImage()
    coordsys = GiftiCoordSystem(dataspace=3, xformspace=3, xform=XFORM)  # NIFTI_XFORM_TALAIRACH
    img.add_gifti_data_array(GiftiDataArray(V.astype(np.float32), intent="NIFTI_INTENT_POINTSET",
                                            coordsys=coordsys))
    img.add_gifti_data_array(GiftiDataArray(F.astype(np.int32), intent="NIFTI_INTENT_TRIANGLE"))
    nib.save(img, str(path))


def corner_angles(P, F):
    """Corner angles (radians) of every face of points P, shape (m, 3)."""
    out = np.empty(F.shape)
    for k in range(3):
        a, b, c = P[F[:, k]], P[F[:, (k + 1) % 3]], P[F[:, (k + 2) % 3]]
        u, v = b - a, c - a
        out[:, k] = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
    return out


def quality_numpy(V, F, S):
    """The overlay by its definition: mean corner angle distortion (degrees) per vertex and
    ln(image area share / mesh area share), a third of each face's area per corner; S are
    the image points (the sphere map's chord triangles)."""
    n = len(V)
    diff = np.degrees(np.abs(corner_angles(V, F) - corner_angles(S, F)))
    area = lambda P: 0.5 * np.linalg.norm(np.cross(P[F[:, 1]] - P[F[:, 0]], P[F[:, 2]] - P[F[:, 0]]), axis=1)
    count = np.bincount(F.ravel(), minlength=n)
    angle = np.bincount(F.ravel(), weights=diff.ravel(), minlength=n) / count
    share = lambda a: np.bincount(F.ravel(), weights=np.repeat(a / 3, 3), minlength=n) / a.sum()
    return angle, np.log(share(area(S))) - np.log(share(area(V)))


def check_sphere_outputs(V, F, sphere, overlay, report):
    """What nibabel reads back from `conformap sphere`'s GIfTI or FreeSurfer sphere and
    overlay: radius 100, the input's triangles and vertex count, the overlay's arrays."""
    S, F_out = sphere
    assert S.shape == V.shape and np.array_equal(F_out, F)
    r = np.linalg.norm(S.astype(np.float64), axis=1)
    assert np.max(np.abs(r - 100.0)) < 1e-4  # float32 points at radius 100
    ov = nib.load(str(overlay))
    names = [d.meta.get("Name") for d in ov.darrays]
    assert names == ["angle_distortion_deg", "area_log_ratio"]
    angle, logr = (d.data.astype(np.float64) for d in ov.darrays)
    assert angle.shape == logr.shape == (len(V),)
    want_angle, want_log = quality_numpy(V, F, S.astype(np.float64) / 100.0)
    # float32 points and values: 1e-3 degrees, 1e-4 in the log
    assert np.max(np.abs(angle - want_angle)) < 1e-3
    assert np.max(np.abs(logr - want_log)) < 1e-4
    # the report's mean over all corners, from the per-vertex means and corner counts
    count = np.bincount(F.ravel(), minlength=len(V))
    mean = float(np.sum(angle * count) / count.sum())
    assert abs(mean - report["metrics"]["angle_distortion_deg"]["mean"]) < 1e-3


def sphere_run(tmp_path, surface, flat_name):
    out = tmp_path / "out"
    out.mkdir()
    proc = cli("sphere", surface, "-o", out / "map.obj", "--flat", out / flat_name,
               "--quality-overlay", out / "quality.shape.gii", "--report", out / "r.json", "-q")
    assert proc.returncode == 0, proc.stderr
    return out, json.loads((out / "r.json").read_text())


def spot():
    V, F = conformap.read_mesh(FIXTURES / "spot.obj")
    return V.astype(np.float32).astype(np.float64), F


def test_gifti_written_by_nibabel_maps_and_reads_back(tmp_path):
    V, F = spot()
    write_gifti(tmp_path / "spot.surf.gii", V, F)
    out, report = sphere_run(tmp_path, tmp_path / "spot.surf.gii", "spot.sphere.surf.gii")
    assert report["input"]["vertices"] == len(V)
    img = nib.load(str(out / "spot.sphere.surf.gii"))
    S, F_out = img.agg_data(("pointset", "triangle"))
    check_sphere_outputs(V, F, (S, F_out), out / "quality.shape.gii", report)
    kept = img.darrays[0].coordsys  # the input's coordinate system, read as nibabel reads it
    assert (kept.dataspace, kept.xformspace) == (3, 3) and np.array_equal(kept.xform, XFORM)


def test_freesurfer_written_by_nibabel_maps_and_reads_back(tmp_path):
    V, F = spot()
    surf = tmp_path / "lh.white"
    volume_info = {"head": np.array([2, 0, 20], dtype=np.int32), "valid": "1  # volume info valid",
                   "filename": "orig.mgz", "volume": np.array([256, 256, 256]),
                   "voxelsize": np.array([1.0, 1.0, 1.0]), "xras": np.array([-1.0, 0.0, 0.0]),
                   "yras": np.array([0.0, 0.0, -1.0]), "zras": np.array([0.0, 1.0, 0.0]),
                   "cras": np.array([1.5, -2.0, 3.25])}
    nfs.write_geometry(str(surf), V, F, create_stamp="created by nibabel for conformap",
                       volume_info=volume_info)
    out, report = sphere_run(tmp_path, surf, "lh.sphere")
    S, F_out, meta = nfs.read_geometry(str(out / "lh.sphere"), read_metadata=True)
    check_sphere_outputs(V, F, (S, F_out), out / "quality.shape.gii", report)
    for key in ("volume", "voxelsize", "xras", "yras", "zras", "cras"):
        assert np.allclose(meta[key], volume_info[key]), key  # the volume geometry kept


def test_quality_overlay_must_be_gifti(tmp_path):
    proc = cli("disk", FIXTURES / "woody.obj", "-o", tmp_path / "w.obj",
               "--quality-overlay", tmp_path / "q.txt")
    assert proc.returncode == 2 and ".shape.gii" in proc.stderr
    assert not any(tmp_path.iterdir())


def test_disk_quality_overlay_on_obj_input(tmp_path):
    """A planar map's overlay: the numpy recomputation from the flat (u, v, 0) mesh."""
    out = tmp_path
    proc = cli("disk", FIXTURES / "woody.obj", "-o", out / "w.obj", "--flat", out / "flat.obj",
               "--quality-overlay", out / "w.shape.gii", "-q")
    assert proc.returncode == 0, proc.stderr
    V, F = conformap.read_mesh(FIXTURES / "woody.obj")
    P, _ = conformap.read_mesh(out / "flat.obj")
    angle, logr = (d.data for d in nib.load(str(out / "w.shape.gii")).darrays)
    want_angle, want_log = quality_numpy(V, F, P)
    assert np.max(np.abs(angle - want_angle)) < 1e-4 and np.max(np.abs(logr - want_log)) < 1e-5


def nibabel_gifti_files():
    return sorted((pathlib.Path(nib.__file__).parent / "gifti" / "tests" / "data").glob("*.gii"))


@pytest.mark.parametrize("path", nibabel_gifti_files(), ids=lambda p: p.name)
def test_gifti_files_shipped_with_nibabel(path):
    img = nib.load(str(path))
    intents = [d.intent for d in img.darrays]
    proc = cli("info", path, "--json")
    surface = POINTSET in intents and TRIANGLE in intents
    if surface and "ExternalFileBinary" not in path.read_text(errors="ignore"):
        P, T = img.agg_data(("pointset", "triangle"))
        if T.max() >= len(P):
            # ascii_flat_data.gii and base64bin.gii are excerpts: 10 points, triangles of the
            # full surface (index 6402); nibabel does not check, we refuse them
            assert proc.returncode == 1 and "out of range (10 points)" in proc.stderr
            assert str(path) in proc.stderr and "hint:" in proc.stderr
            return
        assert proc.returncode == 0, proc.stderr
        V, F = conformap.read_mesh(path)
        # the ASCII text is read to f64, nibabel rounds it to the declared float32
        assert np.array_equal(V.astype(np.float32), P) and np.array_equal(F, T)
    else:  # a data file (no surface) or data in an external file: refused, named, hinted
        assert proc.returncode == 1, proc.stderr
        assert str(path) in proc.stderr and "hint:" in proc.stderr


# --- PLY, STL, OFF written by numpy ---------------------------------------------------

def write_ply(path, V, F, binary):
    head = (f"ply\nformat {'binary_little_endian' if binary else 'ascii'} 1.0\n"
            f"comment written by numpy\nelement vertex {len(V)}\nproperty double x\n"
            f"property double y\nproperty double z\nelement face {len(F)}\n"
            "property list uchar int vertex_indices\nend_header\n")
    with open(path, "wb") as f:
        f.write(head.encode())
        if binary:
            f.write(V.astype("<f8").tobytes())
            rec = np.zeros(len(F), dtype=[("n", "u1"), ("i", "<i4", 3)])
            rec["n"], rec["i"] = 3, F
            f.write(rec.tobytes())
        else:
            f.write("".join(f"{x!r} {y!r} {z!r}\n" for x, y, z in V.tolist()).encode())
            f.write("".join(f"3 {a} {b} {c}\n" for a, b, c in F.tolist()).encode())


def write_off(path, V, F):
    lines = ["OFF", f"{len(V)} {len(F)} 0"] + [f"{x!r} {y!r} {z!r}" for x, y, z in V.tolist()]
    path.write_text("\n".join(lines + [f"3 {a} {b} {c}" for a, b, c in F.tolist()]) + "\n")


def write_stl(path, V, F, binary):
    T = V[F].astype(np.float32)
    N = np.zeros((len(F), 3), dtype=np.float32)
    if binary:
        rec = np.zeros(len(F), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
        rec["n"], rec["v"] = N, T
        path.write_bytes(b"numpy".ljust(80, b" ") + struct.pack("<I", len(F)) + rec.tobytes())
    else:
        out = ["solid numpy"]
        for t in T.tolist():
            out += ["facet normal 0 0 0", "outer loop", *(f"vertex {x!r} {y!r} {z!r}" for x, y, z in t),
                    "endloop", "endfacet"]
        path.write_text("\n".join(out + ["endsolid numpy"]) + "\n")


def welded(V, F):
    """STL's vertices: float32 positions, bit-identical ones welded, first appearance."""
    order, index, faces = [], {}, []
    P = V.astype(np.float32)
    for f in F:
        row = []
        for v in f:
            key = P[v].tobytes()
            if key not in index:
                index[key] = len(order)
                order.append(P[v].astype(np.float64))
            row.append(index[key])
        faces.append(row)
    return np.array(order), np.array(faces)


def disk_run(tmp_path, mesh, name):
    out = tmp_path / f"{name}_uv.obj"
    proc = cli("disk", mesh, "-o", out, "--flat", tmp_path / f"{name}_flat.obj",
               "--report", tmp_path / f"{name}.json", "-q")
    assert proc.returncode == 0, proc.stderr
    report = json.loads((tmp_path / f"{name}.json").read_text())
    # the map's points as written (not through read_mesh: a disk map squeezes some of
    # hand's faces below the mesh reader's degenerate-area bound, 7e-14 of the unit disk)
    text = (tmp_path / f"{name}_flat.obj").read_text().splitlines()
    flat = np.array([[float(x) for x in l.split()[1:4]] for l in text if l.startswith("v ")])
    return report, flat


LARGE = pytest.mark.skipif(not (SHARED / "hand.obj").exists() or not os.environ.get("CONFORMAP_LARGE"),
                           reason="opt-in: CONFORMAP_LARGE=1 and the shared hand.obj")


@pytest.mark.parametrize("kind", ["ply-ascii", "ply-binary", "off", "stl-ascii", "stl-binary"])
@pytest.mark.parametrize("mesh", [FIXTURES / "woody.obj", pytest.param(SHARED / "hand.obj", marks=LARGE)],
                         ids=["woody", "hand"])
def test_numpy_written_formats_give_the_obj_run(kind, mesh, tmp_path):
    V, F = conformap.read_mesh(mesh)
    if kind.startswith("stl"):
        V, F = welded(V, F)  # the OBJ of STL's welded vertices
    conformap.write_mesh(tmp_path / "ref.obj", V, F)
    path = tmp_path / ("mesh." + kind.split("-")[0])
    if kind.startswith("ply"):
        write_ply(path, V, F, kind.endswith("binary"))
    elif kind == "off":
        write_off(path, V, F)
    else:
        write_stl(path, V, F, kind.endswith("binary"))
    ref, ref_flat = disk_run(tmp_path, tmp_path / "ref.obj", "ref")
    mine, flat = disk_run(tmp_path, path, "mine")
    assert mine["input"]["vertices"] == len(V) and mine["input"]["faces"] == len(F)
    e_ref, e = ref["metrics"]["conformal_energy"], mine["metrics"]["conformal_energy"]
    assert abs(e - e_ref) <= 1e-12 * max(1.0, abs(e_ref)), (e, e_ref)
    assert np.max(np.abs(flat - ref_flat)) < 1e-12  # the same vertex order


@pytest.mark.parametrize("command", ["disk", "sphere"])
def test_ply_output_reads_back_in_plyfile(command, tmp_path):
    """A second PLY reader (plyfile, PyPI) reads what conformap writes: the input's points
    and triangles in its order, and the texture coordinates of the OBJ output corner by
    corner — per vertex (`texture_u`, `texture_v`) for a disk map, per face corner (the
    face's `texcoord` list, as MeshLab writes it) for the sphere texture split at its
    seam."""
    plyfile = pytest.importorskip("plyfile")  # CI installs it (.ci/run)
    mesh = FIXTURES / ("woody.obj" if command == "disk" else "spot.obj")
    V, F = conformap.read_mesh(mesh)
    ply, obj = tmp_path / "out.ply", tmp_path / "out.obj"
    for out in (ply, obj):
        proc = cli(command, mesh, "-o", out, "-q")
        assert proc.returncode == 0, proc.stderr
    data = plyfile.PlyData.read(str(ply))
    vert, face = data["vertex"], data["face"]
    P = np.stack([vert["x"], vert["y"], vert["z"]], axis=1)
    Fp = np.stack(face["vertex_indices"]).astype(np.int64)
    assert np.array_equal(Fp, F) and np.max(np.abs(P - V)) == 0.0
    # the OBJ output's texture coordinate of every corner
    vt, fvt = [], []
    for line in obj.read_text().splitlines():
        if line.startswith("vt "):
            vt.append([float(x) for x in line.split()[1:3]])
        elif line.startswith("f "):
            fvt.append([int(c.split("/")[1]) - 1 for c in line.split()[1:4]])
    corners = np.array(vt)[np.array(fvt)]  # (faces, 3, 2)
    if command == "disk":
        UV = np.stack([vert["texture_u"], vert["texture_v"]], axis=1)[Fp]
    else:
        UV = np.stack(face["texcoord"]).reshape(-1, 3, 2)
        assert np.max(np.ptp(UV[:, :, 0], axis=1)) <= 0.25  # no face spans the texture
    assert np.max(np.abs(UV - corners)) < 1e-12


@pytest.mark.skipif(not (SHARED / "brain.obj").exists() or not os.environ.get("CONFORMAP_LARGE"),
                    reason="opt-in: CONFORMAP_LARGE=1 and the shared brain.obj")
@pytest.mark.parametrize("fmt", ["gifti", "freesurfer"])
def test_brain_sphere_through_nibabel(fmt, tmp_path):
    V, F = conformap.read_mesh(SHARED / "brain.obj")
    V = V.astype(np.float32).astype(np.float64)
    if fmt == "gifti":
        write_gifti(tmp_path / "brain.surf.gii", V, F)
        out, report = sphere_run(tmp_path, tmp_path / "brain.surf.gii", "brain.sphere.surf.gii")
        S, F_out = nib.load(str(out / "brain.sphere.surf.gii")).agg_data(("pointset", "triangle"))
    else:
        nfs.write_geometry(str(tmp_path / "lh.white"), V, F)
        out, report = sphere_run(tmp_path, tmp_path / "lh.white", "lh.sphere")
        S, F_out = nfs.read_geometry(str(out / "lh.sphere"))
    check_sphere_outputs(V, F, (S, F_out), out / "quality.shape.gii", report)
