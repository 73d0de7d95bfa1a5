//! `conformap` for Python: the conformap command pipeline on numpy arrays (pyo3 + numpy,
//! an abi3 wheel built by maturin).
//!
//! Every map function builds the job of crate `conformap` the CLI runs
//! ([`conformap::jobs`]) and runs it through [`conformap::run_in_memory`] on an in-memory
//! mesh, so its report is the dict of the CLI's `--report` JSON, built by the same code. The GIL is released for all
//! computation.
//!
//! # Modules
//! - [`arrays`]: coercion of `V` / `F` / map arrays to f64 / u32 data, and back to numpy.
//! - [`errors`]: `ConformapError` (a `ValueError`) and `NumericalError` (a
//!   `RuntimeError`), from the CLI's failures.
//! - [`maps`]: `disk_map`, `sphere_map`.
//! - [`atlas`]: `atlas` (a texture atlas: `uv`, `F_uv`).
//! - [`flatten`]: `flatten` (boundary first flattening; boundary values in memory).
//! - [`mobius`]: `mobius` (the map and the region in memory).
//! - [`global`]: `global_map` (a seamed layout: `uv`, `F_uv`).
//! - [`morph`]: `morph` (frames of a morph through key surfaces).
//! - [`meshes`]: `info`, `metrics`, `read_mesh`, `write_mesh`, `repair`.
//! - [`options`]: keyword arguments checked as the CLI's parser checks its flags.
//! - [`keywords`]: the keyword → job conversion the map functions and `batch_one` share.
//! - [`values`]: keyword values turned into option values (shared by the map functions
//!   and [`keywords`]).
//! - [`batch`]: `batch_one` (one input of `conformap batch`, for cohorts on a cluster).

pub mod arrays;
pub mod atlas;
pub mod batch;
pub mod errors;
pub mod flatten;
pub mod global;
pub mod keywords;
pub mod maps;
pub mod meshes;
pub mod mobius;
pub mod morph;
pub mod options;
pub mod sphere_uv;
pub mod values;

use pyo3::prelude::*;

/// The Python module `conformap`.
#[pymodule(name = "conformap")]
fn conformap_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("ConformapError", py.get_type::<errors::ConformapError>())?;
    m.add("NumericalError", py.get_type::<errors::NumericalError>())?;
    m.add_function(wrap_pyfunction!(maps::disk_map, m)?)?;
    m.add_function(wrap_pyfunction!(maps::sphere_map, m)?)?;
    m.add_function(wrap_pyfunction!(sphere_uv::sphere_uv, m)?)?;
    m.add_function(wrap_pyfunction!(flatten::flatten, m)?)?;
    m.add_function(wrap_pyfunction!(atlas::atlas, m)?)?;
    m.add_function(wrap_pyfunction!(mobius::mobius, m)?)?;
    m.add_function(wrap_pyfunction!(global::global_map, m)?)?;
    m.add_function(wrap_pyfunction!(morph::morph, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::info, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::metrics, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::read_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::write_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(meshes::repair, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch_one, m)?)?;
    Ok(())
}
