"""conformap: conformal parameterization of triangle meshes on numpy arrays.

Array in, array out (libigl style). ``V`` is any real ``(n, 3)`` array, ``F`` any integer
``(m, 3)`` array of 0-based vertex indices, in C or Fortran order (coerced with
``numpy.ascontiguousarray``: no copy when already float64 / int64 C-contiguous). Every map
function runs the CLI's own command and returns its report: the same dict as the CLI's
``--report`` JSON (with ``input.path == "<arrays>"`` and ``read``/``write`` timings 0).
The GIL is released during all computation.

Example::

    import conformap
    V, F = conformap.read_mesh("fixtures/woody.obj")
    uv, report = conformap.disk_map(V, F)
    assert report["metrics"]["flipped_faces"] == 0
    print(report["metrics"]["conformal_energy"])

Every map command of the CLI is bound: ``disk_map``, ``sphere_map``, ``mobius``,
``global_map`` (a seamed layout: ``uv`` and ``F_uv``), ``morph``, ``flatten``, ``atlas``; and
``metrics``, ``info``, ``read_mesh``, ``write_mesh``, ``repair`` (the CLI's ``--repair``).
Arguments are spelled as here (``V``, ``F``, ``max_iter``, ...), by position or by keyword.

Exceptions carry ``exit_code`` (the CLI's: 1 bad input, 2 usage error, 3 numerical failure)
and ``hint`` (the CLI's ``hint:`` line, or ``None``). Messages name keywords, not CLI flags
(``tol``, ``outer=5``); errors about the arrays passed start with ``<arrays>:``. A negative
count (``max_iter``, ``frames``, ``form``, ...) or ``max_memory=0`` raises ConformapError with
``exit_code`` 2, as the CLI's parser refuses such flags.
"""

import os
from typing import Any, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]
Report = dict[str, Any]

class ConformapError(ValueError):
    """Bad input: invalid mesh (the element named), wrong topology for the map, bad option.

    The message is the CLI's ``error:`` line (path ``<arrays>``), then its ``hint:`` line.
    ``exit_code`` is the CLI's (1 bad input, 2 usage error), ``hint`` its hint or ``None``.
    """

    exit_code: int
    hint: Optional[str]

class NumericalError(RuntimeError):
    """A numerical failure (the CLI's exit 3), e.g. ``strict=True`` and no convergence."""

    exit_code: int
    hint: Optional[str]

def disk_map(
    V: ArrayLike,
    F: ArrayLike,
    method: Literal["ccem-qn", "ccem", "cem", "harmonic", "double-cover"] = "ccem-qn",
    *,
    outer: Optional[int] = None,
    max_iter: Optional[int] = None,
    tol: Optional[float] = None,
    keep_folds: bool = False,
    ordering: Literal["auto", "amd", "nd"] = "auto",
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], Report]:
    """Conformal map onto the unit disk, as ``conformap disk``.

    One boundary loop: the unit disk. Several: the unit disk with circular holes (Koebe
    iteration; ``outer`` picks the loop on the unit circle, default the longest).
    Options are the CLI's flags (``--max-iter``, ``--tol``, ``--keep-folds``,
    ``--ordering``, ``--strict``, ``--max-memory`` in bytes).

    Returns ``(uv, report)``: ``uv`` (n, 2) float64, the map ``u + i v`` per vertex in the
    input's order (the CLI writes ``vt = (uv + 1) / 2``); ``report`` the CLI's report dict.

    Raises ConformapError for bad input, NumericalError for numerical failure.

    Example::

        uv, report = conformap.disk_map(V, F, method="cem")
        report["metrics"]["conformal_energy"]
    """

def flatten(
    V: ArrayLike,
    F: ArrayLike,
    boundary: Literal["free", "circle", "rectangle", "scale", "angles", "polygon"] = "free",
    values: Optional[Union[Mapping[int, float], Sequence[Tuple[int, float]]]] = None,
    *,
    corners: Optional[Tuple[int, int, int, int]] = None,
    aspect: Optional[float] = None,
    interior: Literal["harmonic", "conjugate"] = "harmonic",
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], Report]:
    """Boundary first flattening, as ``conformap flatten``.

    ``boundary``: ``free`` (u = 0: the boundary keeps its lengths, the least area
    distortion), ``circle``, ``rectangle`` (``corners`` in boundary order, ``aspect`` width
    over height), or ``scale`` / ``angles`` / ``polygon`` with ``values``: a dict or pairs
    ``(0-based vertex, value)`` — the scale factor u, or the exterior angle in degrees (every
    boundary vertex for ``scale`` and ``angles``, the corners in boundary order for
    ``polygon``).

    Returns ``(uv, report)``: ``uv`` (n, 2) float64, the flat layout per vertex in the
    input's order; ``report`` the CLI's report dict (``report["flatten"]``: boundary mode,
    corners, closure residual, boundary scale range, overlap).

    Raises ConformapError for bad input, NumericalError for numerical failure.

    Example::

        uv, report = conformap.flatten(V, F, "rectangle", aspect=2.0)
        report["flatten"]["aspect"]
    """

def atlas(
    V: ArrayLike,
    F: ArrayLike,
    cones: Union[int, Literal["auto"], ArrayLike, None] = None,
    *,
    resolution: int = 1024,
    margin: float = 2.0,
    max_area_spread: float = 1.0,
    pack: Literal["square", "none"] = "square",
    scale: Literal["uniform", "per-chart"] = "uniform",
    seamless: bool = False,
    polish: Union[bool, Literal["auto", "always", "never"], None] = None,
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.uint32], Report]:
    """A texture atlas of any mesh, as ``conformap atlas``.

    Every connected component is charted (closed ones cut through ``cones`` cones, 8 by
    default, and their handles; genus-0 ones with boundary by the free boundary), charts
    that would overlap are split, and all are packed into the unit square with one texel
    density and ``margin`` texels between them at ``resolution``.

    ``cones``: an integer (cones placed automatically per closed component), ``"auto"``
    (as many per component as bring its area spread to ``max_area_spread``, at most 32;
    ``report["atlas"]["auto_cones"]`` says how many and where the cap stopped), or
    ``(vertex, cone angle in degrees)`` pairs used as given (``--cones FILE``; the same
    checks: interior vertices, angles in (0, 720], on a closed genus-0 component
    ``sum(360 - angle) == 720``). ``report["atlas"]["cone_list"]`` holds the cones of a run
    in that form. ``pack="none"`` keeps the charts in their own coordinates (``uv`` may
    leave [0, 1]²); ``scale="per-chart"`` gives every chart the same texture area.
    ``seamless=True`` (``--seamless``): cone angles multiples of 90° and every seam a
    rotation by a multiple of 90° plus a translation (genus ≥ 1: a holomorphic 1-form's
    layout, seams pure translations), charts packed with quarter turns only;
    ``report["atlas"]["seam_rotation_error_max"]`` (radians) and
    ``["seam_rigid_residual_max"]`` (relative to the edge length) measure it. Not with
    ``cones="auto"``. ``polish`` (``--polish=WHEN``): which charts' layouts are polished
    after they are flattened, one Gauss–Newton step that lowers the area spread and the
    angle distortion with the seams held rigid. ``None`` or ``"auto"`` (the default): the
    charts whose cone metric spreads 0.5 or more, on components of up to 20,000 vertices;
    ``True`` or ``"always"``: every chart with cones; ``False`` or ``"never"``: none.
    ``report["atlas"]["polished_components"]`` counts them, ``["polish_energy"]`` is the
    energy before and after (``None`` when nothing was polished); with ``seamless`` the
    seams keep their quarter turns.

    Returns ``(uv, F_uv, report)``: ``uv`` (k, 2) texture coordinates in [0, 1]², ``F_uv``
    (m, 3) their indices per face corner (face ``i`` of ``F`` has ``uv[F_uv[i]]``),
    ``report`` the CLI's report dict (``report["atlas"]``: components, charts, cones,
    flipped faces, overlap, packing efficiency).

    Example::

        uv, F_uv, report = conformap.atlas(V, F)
        report["atlas"]["overlap"]["covered_twice"]   # 0
    """

def sphere_map(
    V: ArrayLike,
    F: ArrayLike,
    mobius: Literal["none", "uniform"] = "none",
    *,
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], Report]:
    """Conformal map of a closed genus-0 mesh onto the unit sphere, as ``conformap sphere``.

    Returns ``(S, report)``: ``S`` (n, 3) float64 unit vectors per vertex.

    Example::

        S, report = conformap.sphere_map(*conformap.read_mesh("fixtures/spot.obj"), mobius="uniform")
    """

def sphere_uv(
    S: ArrayLike,
    F: ArrayLike,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The texture of a sphere map, as ``conformap sphere -o`` writes it.

    Returns ``(uv, F_uv)``: equirectangular coordinates ``u = (atan2(y, x) + π)/2π``,
    ``v = (asin z + π/2)/π``, one row of ``F_uv`` per face. ``u`` is continuous within each
    face: a face crossing the seam meridian keeps its corners together (some ``u`` in
    (1, 1.25); sample with REPEAT wrapping), and faces at the poles fan out from them.

    Example::

        V, F = conformap.read_mesh("fixtures/spot.obj")
        S, report = conformap.sphere_map(V, F)
        uv, F_uv = conformap.sphere_uv(S, F)
        conformap.write_mesh("spot_sphere.obj", V, F, uv=uv, F_uv=F_uv)
    """

def mobius(
    V: ArrayLike,
    F: ArrayLike,
    param: ArrayLike,
    domain: Literal["disk", "sphere"] = "disk",
    objective: Literal["uniform", "emphasize", "emphasize-density"] = "uniform",
    region: Optional[ArrayLike] = None,
    *,
    max_area_scale: float = 10.0,
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], Report]:
    """The optimal Möbius transformation of a disk or sphere map, as ``conformap mobius``.

    ``param``: ``domain="disk"``, an (n, 2) map ``u + i v`` in the unit disk (the ``uv`` of
    ``disk_map``, or another tool's); ``domain="sphere"``, (n, 3) unit vectors (the ``S``
    of ``sphere_map``). ``objective``: ``"uniform"`` minimizes the uniformity energy
    Σ (image area share − surface area share)²; ``"emphasize"`` maximizes the image-area
    share of the faces in ``region`` (the magnification capped by ``max_area_scale``,
    ``--max-area-scale``); ``"emphasize-density"`` their mean log area magnification.
    ``region``: a sequence or integer array of 0-based face indices (needed by, and only
    by, the emphasizing objectives; a face out of range raises the CLI's message with
    ``region[k]`` in place of the file line).

    Returns ``(param, report)``: the moved map, same shape as ``param``; the CLI's report
    dict (``param.path == "<array>"``; ``solver.mobius`` holds the optimization,
    ``metrics.uniformity_energy_before`` the map given).

    Example::

        uv, _ = conformap.disk_map(V, F)
        moved, report = conformap.mobius(V, F, uv)
        report["metrics"]["uniformity_energy"] < report["metrics"]["uniformity_energy_before"]
        face_moved, _ = conformap.mobius(V, F, uv, objective="emphasize", region=range(100))
    """

@overload
def global_map(
    V: ArrayLike,
    F: ArrayLike,
    objective: Literal["uniform", "least-uniform", "emphasize", "de-emphasize", "zeros", "basis"] = "uniform",
    *,
    form: Optional[int] = None,
    region: Optional[ArrayLike] = None,
    zeros: Optional[Sequence[int]] = None,
    starts: Optional[int] = None,
    conjugate: Literal["nearest", "gu-yau"] = "nearest",
    root: Optional[int] = None,
    topology_opt: bool = False,
    return_mesh: Literal[False] = False,
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Report]: ...
@overload
def global_map(
    V: ArrayLike,
    F: ArrayLike,
    objective: Literal["uniform", "least-uniform", "emphasize", "de-emphasize", "zeros", "basis"] = "uniform",
    *,
    form: Optional[int] = None,
    region: Optional[ArrayLike] = None,
    zeros: Optional[Sequence[int]] = None,
    starts: Optional[int] = None,
    conjugate: Literal["nearest", "gu-yau"] = "nearest",
    root: Optional[int] = None,
    topology_opt: bool = False,
    return_mesh: Literal[True],
    strict: bool = False,
    max_memory: Optional[int] = None,
) -> Tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.int64],
    Report,
    npt.NDArray[np.float64],
    npt.NDArray[np.int64],
]:
    """Global conformal parameterization of a surface with handles (genus ≥ 1, or several
    boundary loops through its double covering) by a holomorphic 1-form, as
    ``conformap global``.

    Returns ``(uv, F_uv, report)``, a seamed layout as libigl (``TC``/``FTC``) and trimesh
    keep seamed texture coordinates: ``uv`` (k, 2) float64, one row per corner class (a
    vertex, split where a seam passes through it: k ≥ n); ``F_uv`` (m, 3) int64, per face
    of ``F`` the row of ``uv`` of each corner, so ``uv[F_uv[f, j]]`` is the map at corner
    ``j`` of face ``f`` (vertex ``F[f, j]``). ``uv`` is the raw layout (area equal to the
    surface's; across a seam the two sides differ by a period, a pure translation; the
    periods are ``report["global"]["period_matrix"]``), the CLI's ``--flat``. The
    texture coordinates the CLI writes (the layout fitted into the unit square) are
    ``(uv - report["global"]["uv_offset"]) * report["global"]["uv_scale"]``.

    ``objective``: ``"uniform"`` (the most uniform form; ``starts`` random starts besides
    the 2g basis forms), ``"least-uniform"``, ``"emphasize"`` / ``"de-emphasize"`` (the
    largest / smallest share of the parameter area for the faces of ``region``, face
    indices), ``"zeros"`` (zeros nearest the vertices ``zeros``; genus ≥ 2), ``"basis"``
    (the basis form of lowest uniformity energy); ``form=K`` lays out basis form K
    instead. ``conjugate``, ``root``: the CLI's ``--conjugate``, ``--root``.
    ``topology_opt=True``: the CLI's ``--topology-opt`` (Jin et al. §3.5: slits that make the
    map more uniform; also takes closed genus-0 surfaces), ``report["topology_opt"]`` says
    what was returned; when that is a sphere map (genus 0, no slit paid), ``uv`` holds its
    (n, 3) unit vectors and ``F_uv`` is ``F``.

    A surface with boundary chords (an interior edge joining two boundary vertices) is
    refined by its double covering: the layout then belongs to a refined mesh (its first
    vertices are ``V``, in order) and ``return_mesh=True`` is needed: it returns
    ``(uv, F_uv, report, V_out, F_out)``, the mesh ``F_uv`` belongs to (else the input).

    Example::

        V, F = conformap.read_mesh("fixtures/eightsim.obj")      # genus 2
        uv, F_uv, report = conformap.global_map(V, F)
        report["global"]["zeros"]        # multiplicities sum to 2g − 2 = 2
        g = report["global"]              # vt as the CLI writes them:
        conformap.write_mesh("eight_uv.obj", V, F, uv=(uv - g["uv_offset"]) * g["uv_scale"], F_uv=F_uv)
    """

def morph(
    surfaces: Sequence[Tuple[ArrayLike, ArrayLike]],
    landmarks: Sequence[Union[ArrayLike, Mapping[str, int]]],
    frames: int,
    *,
    lambda_: Optional[float] = None,
    hard: bool = False,
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], Report]:
    """A morph through two or more disk-like key surfaces with landmarks (CEM §6), as
    ``conformap morph``.

    ``surfaces``: ``[(V1, F1), (V2, F2), ...]``, each a disk (one boundary loop, genus 0);
    every frame has the vertices and faces of the first. ``landmarks``: one list per
    surface, the same number in every list: 0-based vertex indices (landmark j of every
    surface corresponds; named ``"0"``, ``"1"``, ... in the report), or dicts
    ``name -> vertex`` (the same names in every dict, matched by name: their order need not
    agree).
    The first landmark goes to the centre of the disk, the second fixes the rotation:
    both must be interior vertices. ``frames``: N ≥ number of surfaces (key surface k at
    frame round(k (N−1)/(K−1))). ``lambda_``: the landmark weight λ of Eq. 34
    (``--lambda``); ``hard=True`` puts the landmarks exactly on their counterparts.

    Returns ``(frames, F, report)``: ``frames`` (N, n, 3) float64, the positions of the
    first surface's vertices at each frame (``frames[0]`` is ``V1`` bit for bit); ``F``
    (m, 3) int64, the first surface's faces; the CLI's report dict (``inputs`` named
    ``<surfaces[k]>``, ``landmark_files`` ``<landmarks[k]>``; errors name them the same
    way). The result array is estimated first: frames that would not fit in the memory
    available raise ConformapError before any work.

    Example::

        A = conformap.read_mesh("fixtures/morph/ict_neutral.obj")
        B = conformap.read_mesh("fixtures/morph/ict_pout.obj")
        L = [4857, 3742, 1528, 3721, 1507]                 # nose tip, eye corners
        P, F, report = conformap.morph([A, B], [L, L], frames=24)
        conformap.write_mesh("frame_12.obj", P[12], F)
    """

def metrics(V: ArrayLike, F: ArrayLike, param: ArrayLike) -> Report:
    """Quality of a planar map ``param`` ((n, 2), one point per vertex), as
    ``conformap metrics --json`` (conformal energy, angle distortion, flips, ...).

    Example::

        conformap.metrics(V, F, uv)["metrics"]["flipped_faces"]
    """

def info(V: ArrayLike, F: ArrayLike) -> dict[str, Any]:
    """Topology and validity of a mesh, as ``conformap info --json``; raises
    ConformapError (with the CLI's message and hint) for an invalid mesh.

    Example::

        conformap.info(V, F)["boundary_loop_sizes"]
    """

def read_mesh(
    path: PathLike, repair: bool = False
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Reads a mesh file (OBJ, glTF / GLB, PLY, STL, OFF, GIfTI, FreeSurfer) as ``(V, F)``:
    float64 (n, 3), int64 (m, 3). A file that is not a valid mesh raises ConformapError;
    ``repair=True`` applies the CLI's ``--repair`` first (as ``repair``), so a slightly
    dirty file (duplicate faces, unreferenced or coincident vertices, faces flipped, stray
    components) loads.

    Example::

        V, F = conformap.read_mesh("fixtures/woody.obj")
        V, F = conformap.read_mesh("fixtures/bad/dirty_disk.obj", repair=True)
    """

def repair(
    V: ArrayLike, F: ArrayLike
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.int64]]:
    """The CLI's ``--repair`` on arrays: coincident vertices welded (a triangle soup becomes
    a mesh), duplicate faces and unreferenced vertices dropped, the largest component kept,
    faces oriented consistently. Defects no repair fixes safely (non-manifold elements,
    degenerate faces, NaN) raise ConformapError naming the element.

    Returns ``(V, F, vertex_map)``: the repaired mesh, and for each of its vertices the row
    of the input ``V`` it comes from (int64 (k,)).

    Example::

        V, F = conformap.read_mesh("fixtures/woody.obj")
        soup_V, soup_F = V[F.ravel()], np.arange(F.size).reshape(-1, 3)
        R, RF, vertex_map = conformap.repair(soup_V, soup_F)
        assert R.shape == V.shape and RF.shape == F.shape
    """

def write_mesh(
    path: PathLike,
    V: ArrayLike,
    F: ArrayLike,
    uv: Optional[ArrayLike] = None,
    F_uv: Optional[ArrayLike] = None,
) -> None:
    """Writes ``(V, F)`` to OBJ / glTF / GLB, with texture coordinates ``uv`` written as
    given when passed: one per vertex ((n, 2)), or with ``F_uv`` a seamed layout (``uv``
    (k, 2), ``F_uv`` (m, 3) rows of ``uv`` per face corner, as ``global_map`` returns:
    OBJ ``f v/vt``, glTF split along the seams).

    An empty mesh (no faces) and NaN or infinite ``uv`` raise ConformapError: what is
    written reads back with ``read_mesh``.

    Example::

        V, F = conformap.read_mesh("fixtures/woody.obj")
        uv, _ = conformap.disk_map(V, F)
        conformap.write_mesh("woody_uv.obj", V, F, uv=(uv + 1) / 2)
        V, F = conformap.read_mesh("fixtures/eightsim.obj")
        uv, F_uv, report = conformap.global_map(V, F)
        g = report["global"]
        conformap.write_mesh("eight_uv.obj", V, F, uv=(uv - g["uv_offset"]) * g["uv_scale"], F_uv=F_uv)
    """

def batch_one(
    path: PathLike,
    command: Literal["disk", "sphere", "global", "flatten", "atlas"],
    out_dir: PathLike,
    *,
    skip_existing: bool = False,
    ext: Optional[str] = None,
    png: bool = False,
    max_memory: Optional[int] = None,
    **options: Any,
) -> dict[str, Any]:
    """Maps one mesh file as ``conformap batch --command COMMAND --out-dir OUT_DIR PATH --
    OPTIONS`` does, by the same Rust function, and returns that input's JSON line as a
    dict: ``OUT_DIR/<stem>.<ext>`` and ``OUT_DIR/<stem>.json`` are written as batch writes
    them; a failing input is a ``"failed"`` line (``exit_code``, ``exit_class``, ``error``,
    ``hint``), an input whose outputs exist with ``skip_existing`` a ``"skipped"`` line.

    ``options`` are the keywords of the command's function, with its defaults and checks
    (the same Rust code builds the job): ``disk`` takes ``disk_map``'s (``method``,
    ``outer``, ``max_iter``, ``tol``, ``keep_folds``, ``ordering``, ``strict``), ``sphere``
    ``sphere_map``'s (``mobius``, ``strict``), ``global`` ``global_map``'s but
    ``return_mesh`` (``region`` faces are checked against each input's mesh when it is
    mapped), ``flatten`` ``flatten``'s (``values`` in memory) and ``atlas`` ``atlas``'s.
    ``None`` is the default. ``skip_existing``, ``ext``, ``png`` and ``max_memory`` are
    batch's own options (``max_memory`` is every input's memory limit).

    The GIL is released while the mesh is mapped: a thread pool or a Dask cluster (one
    thread per worker process) maps a cohort in parallel; ``examples/python/cohort.py``
    writes batch's lines from these dicts.

    Raises ``ConformapError`` (exit code 2) for what batch refuses before running anything:
    an unknown command, a keyword the command's function does not take (the message names
    it, its ``hint`` lists the accepted ones), a bad value (the function's own message), a
    path that is not a mesh (a manifest).

    Example::

        line = conformap.batch_one("fixtures/woody.obj", "disk", "out", method="cem")
        assert line["status"] == "ok" and line["outputs"] == ["out/woody.obj", "out/woody.json"]
    """
