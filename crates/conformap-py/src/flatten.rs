//! `flatten`: the `flatten` job (boundary first flattening) on arrays, the boundary values
//! given in memory instead of a file.

use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{mesh_input, to_array};
use crate::keywords;
use crate::maps::{report_dict, run};

/// Boundary first flattening, as `conformap flatten`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F, boundary = "free", values = None, *, corners = None, aspect = None,
    interior = "harmonic", strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments, non_snake_case)] // `V`, `F` as the stubs spell them
pub fn flatten<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    boundary: &str,
    values: Option<&Bound<'py, PyAny>>,
    corners: Option<[u32; 4]>,
    aspect: Option<f64>,
    interior: &str,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let job = keywords::flatten_job(boundary, values, corners, aspect, interior, strict)?;
    let max_memory = crate::options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
    let (solved, report) = run(py, &job, &input, max_memory, strict)?;
    let n = input.mesh.num_vertices();
    let uv: Vec<[f64; 2]> = solved.flat.0[..n.min(solved.flat.0.len())]
        .iter()
        .map(|p| [p[0], p[1]])
        .collect();
    Ok((to_array(py, &uv)?, report_dict(py, &report)?))
}
