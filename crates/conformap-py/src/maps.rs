//! `disk_map` and `sphere_map`: the CLI's `disk` and `sphere` commands on arrays, through
//! [`solve_and_report`], with the GIL released for the solve.

use clap::ValueEnum;
use conformap_cli::commands::disk::{DiskArgs, Method, OrderingArg};
use conformap_cli::commands::sphere::{SphereArgs, SphereMobius};
use conformap_cli::failure::Failure;
use conformap_cli::pipeline::{
    solve_and_report, Input, InputArgs, MapCommand, MemoryCheck, OutputArgs, Solved,
};
use conformap_cli::report::Report;
use conformap_operators::available_memory;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{mesh_input, to_array, to_py_json, MEMORY_PATH};
use crate::errors::{bad_input, to_py, usage};

/// A value of a CLI enum (`--method`, `--ordering`, `--mobius`) by its command-line name.
pub(crate) fn choice<T: ValueEnum>(name: &str, value: &str) -> PyResult<T> {
    T::from_str(value, false).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
            .collect();
        usage(format!(
            "{name} must be one of {}, got {value:?}",
            names.join(", ")
        ))
    })
}

/// Runs `cmd` on `input` with the GIL released: usage check, memory check against
/// `max_memory` (or the memory available), solve, report; `strict` refuses what
/// `--strict` refuses.
pub(crate) fn run(
    py: Python<'_>,
    cmd: &(dyn MapCommand + Sync),
    input: &Input,
    max_memory: Option<u64>,
    strict: bool,
) -> PyResult<(Solved, Report)> {
    py.detach(|| {
        cmd.check_usage()?;
        let limit = match max_memory {
            Some(m) => Some((m, "max_memory")),
            None => available_memory(),
        };
        // arrays from numpy: nothing read, no file text kept
        let memory = MemoryCheck {
            read_estimate: 0,
            estimate: 0,
            file_bytes: 0,
            limit,
        };
        let (solved, report) = solve_and_report(cmd, input, memory, 0.0)?;
        if let Some(why) = solved.strict_violation.as_ref().filter(|_| strict) {
            return Err(input.fail(Failure::Numerical(format!("{why} (strict=True)"))));
        }
        Ok((solved, report))
    })
    .map_err(to_py)
}

/// The report as a dict (the CLI's `--report` JSON).
pub(crate) fn report_dict<'py>(py: Python<'py>, report: &Report) -> PyResult<Bound<'py, PyAny>> {
    let value = serde_json::to_value(report).map_err(|e| bad_input(e.to_string()))?;
    to_py_json(py, &value)
}

/// The first `n` points of the solve's flat mesh (a refined double cover keeps the input's
/// vertices first, in the input's order).
fn flat_rows(solved: &Solved, n: usize) -> &[[f64; 3]] {
    &solved.flat.0[..n.min(solved.flat.0.len())]
}

/// Conformal map of a disk-like mesh onto the unit disk (several boundary loops: the unit
/// disk with circular holes), as `conformap disk`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (v, f, method = "ccem-qn", *, outer = None, max_iter = None, tol = None,
    keep_folds = false, ordering = "auto", strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments)]
pub fn disk_map<'py>(
    py: Python<'py>,
    v: &Bound<'py, PyAny>,
    f: &Bound<'py, PyAny>,
    method: &str,
    outer: Option<usize>,
    max_iter: Option<usize>,
    tol: Option<f64>,
    keep_folds: bool,
    ordering: &str,
    strict: bool,
    max_memory: Option<u64>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let mut args = DiskArgs::new(InputArgs::new(MEMORY_PATH), OutputArgs::new(MEMORY_PATH));
    args.method = choice::<Method>("method", method)?;
    args.ordering = choice::<OrderingArg>("ordering", ordering)?;
    args.outer = outer;
    args.max_iter = max_iter;
    args.tol = tol;
    args.keep_folds = keep_folds;
    let input = mesh_input(v, f)?;
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
#[pyo3(signature = (v, f, mobius = "none", *, strict = false, max_memory = None))]
pub fn sphere_map<'py>(
    py: Python<'py>,
    v: &Bound<'py, PyAny>,
    f: &Bound<'py, PyAny>,
    mobius: &str,
    strict: bool,
    max_memory: Option<u64>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let mut args = SphereArgs {
        input: InputArgs::new(MEMORY_PATH),
        output: OutputArgs::new(MEMORY_PATH),
        mobius: SphereMobius::None,
    };
    args.mobius = choice::<SphereMobius>("mobius", mobius)?;
    let input = mesh_input(v, f)?;
    let (solved, report) = run(py, &args, &input, max_memory, strict)?;
    let points = flat_rows(&solved, input.mesh.num_vertices());
    Ok((to_array(py, points)?, report_dict(py, &report)?))
}
