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

Not bound yet: ``mobius``, ``global_map``, ``morph``.
"""

import os
from typing import Any, Literal, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
PathLike = Union[str, "os.PathLike[str]"]
Report = dict[str, Any]

class ConformapError(ValueError):
    """Bad input: invalid mesh (the element named), wrong topology for the map, bad option.

    The message is the CLI's ``error:`` line (path ``<arrays>``), then its ``hint:`` line.
    """

class NumericalError(RuntimeError):
    """A numerical failure (the CLI's exit 3), e.g. ``strict=True`` and no convergence."""

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

def read_mesh(path: PathLike) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """Reads an OBJ / glTF / GLB mesh as ``(V, F)``: float64 (n, 3), int64 (m, 3).

    Example::

        V, F = conformap.read_mesh("fixtures/woody.obj")
    """

def write_mesh(
    path: PathLike, V: ArrayLike, F: ArrayLike, uv: Optional[ArrayLike] = None
) -> None:
    """Writes ``(V, F)`` to OBJ / glTF / GLB, with per-vertex texture coordinates ``uv``
    ((n, 2), written as given) when passed.

    Example::

        conformap.write_mesh("woody_uv.obj", V, F, uv=(uv + 1) / 2)
    """
