//! `disk_map` and `sphere_map`: the `disk` and `sphere` jobs on arrays, through
//! [`run_in_memory`], with the GIL released for the solve.

use conformap::pipeline::{run_in_memory, Input, MapJob, Solved};
use conformap::report::Report;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{mesh_input, to_array, to_py_json};
use crate::errors::{bad_input, to_py};
use crate::keywords;
use crate::options;

/// Runs `job` on `input` with the GIL released ([`run_in_memory`]: usage check, memory
/// check against `max_memory` or the memory available, solve, report); `strict` refuses
/// what `--strict` refuses.
pub(crate) fn run(
    py: Python<'_>,
    job: &(dyn MapJob + Sync),
    input: &Input,
    max_memory: Option<u64>,
    strict: bool,
) -> PyResult<(Solved, Report)> {
    py.detach(|| run_in_memory(job, input, max_memory, strict))
        .map_err(to_py)
}

/// The report as a dict (the `--report` JSON).
pub(crate) fn report_dict<'py>(py: Python<'py>, report: &Report) -> PyResult<Bound<'py, PyAny>> {
    let value = serde_json::to_value(report).map_err(|e| bad_input(e.to_string()))?;
    to_py_json(py, &value)
}

/// The first `n` points of the solve's flat mesh (a refined double cover keeps the input's
/// vertices first, in the input's order).
pub(crate) fn flat_rows(solved: &Solved, n: usize) -> &[[f64; 3]] {
    &solved.flat.0[..n.min(solved.flat.0.len())]
}

/// Conformal map of a disk-like mesh onto the unit disk (several boundary loops: the unit
/// disk with circular holes), as `conformap disk`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F, method = "ccem-qn", *, outer = None, max_iter = None, tol = None,
    keep_folds = false, ordering = "auto", strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments, non_snake_case)] // `V`, `F` as the stubs (and libigl) spell them
pub fn disk_map<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    method: &str,
    outer: Option<&Bound<'py, PyAny>>,
    max_iter: Option<&Bound<'py, PyAny>>,
    tol: Option<f64>,
    keep_folds: bool,
    ordering: &str,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let args = keywords::disk_job(method, outer, max_iter, tol, keep_folds, ordering, strict)?;
    let max_memory = options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
    let (solved, report) = run(py, &args, &input, max_memory, strict)?;
    let uv: Vec<[f64; 2]> = flat_rows(&solved, input.mesh.num_vertices())
        .iter()
        .map(|p| [p[0], p[1]])
        .collect();
    Ok((to_array(py, &uv)?, report_dict(py, &report)?))
}

/// Conformal map of a closed genus-0 mesh onto the unit sphere, as `conformap sphere`.
/// See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F, mobius = "none", *, strict = false, max_memory = None))]
#[allow(non_snake_case)] // `V`, `F` as the stubs (and libigl) spell them
pub fn sphere_map<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    mobius: &str,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let args = keywords::sphere_job(mobius, strict)?;
    let max_memory = options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
    let (solved, report) = run(py, &args, &input, max_memory, strict)?;
    let points = flat_rows(&solved, input.mesh.num_vertices());
    Ok((to_array(py, points)?, report_dict(py, &report)?))
}
