//! `sphere_uv`: the texture a sphere map is written with, as `conformap sphere -o` writes
//! it (equirectangular, one `vt` per face corner, split along the seam meridian).

use numpy::PyArray2;
use pyo3::prelude::*;

use conformap::Failure;

use crate::arrays::{faces_array, mesh_input, to_array};
use crate::errors::to_py;

/// The equirectangular texture of a sphere map `S` (`(n, 3)` unit vectors, as `sphere_map`
/// returns) of the faces `F`: `(uv, F_uv)`, one row of `uv` per distinct corner value and
/// one row of `F_uv` per face, for `write_mesh(path, V, F, uv=uv, F_uv=F_uv)`. See
/// `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (S, F))]
#[allow(non_snake_case)] // spelled as libigl users write it
#[allow(clippy::type_complexity)]
pub fn sphere_uv<'py>(
    py: Python<'py>,
    S: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>)> {
    let input = mesh_input(S, F)?;
    let points = input.mesh.positions().to_vec();
    let tex = py
        .detach(|| conformap_sphere::equirectangular_corner_uv(&input.mesh, &points))
        .map_err(|e| {
            to_py(Failure::BadInput(
                e.to_string(),
                Some(SPHERE_UV_HINT.to_string()),
            ))
        })?;
    Ok((to_array(py, &tex.texcoords)?, faces_array(py, &tex.faces)?))
}

const SPHERE_UV_HINT: &str = "pass the S that sphere_map returns and the F it was given";
