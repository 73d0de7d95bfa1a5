//! `atlas`: the `atlas` job (a texture atlas of any mesh) on arrays.

use conformap::jobs::atlas::AtlasJob;
use conformap::pipeline::{InputOptions, OutputOptions, TexCoords};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{faces_array, mesh_input, to_array, MEMORY_PATH};
use crate::errors::bad_input;
use crate::maps::{report_dict, run};

/// A texture atlas, as `conformap atlas`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (v, f, cones = None, *, resolution = 1024, margin = 2.0, strict = false,
    max_memory = None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity)]
pub fn atlas<'py>(
    py: Python<'py>,
    v: &Bound<'py, PyAny>,
    f: &Bound<'py, PyAny>,
    cones: Option<usize>,
    resolution: usize,
    margin: f64,
    strict: bool,
    max_memory: Option<u64>,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let mut job = AtlasJob::new(
        InputOptions::new(MEMORY_PATH),
        OutputOptions::new(MEMORY_PATH).with_strict(strict),
    );
    job.cones = cones;
    job.resolution = resolution;
    job.margin = margin;
    let input = mesh_input(v, f)?;
    let (solved, report) = run(py, &job, &input, max_memory, strict)?;
    let TexCoords::PerCorner(c) = &solved.uv else {
        return Err(bad_input("atlas: a per-corner layout was expected"));
    };
    let uv = to_array(py, &c.texcoords)?;
    Ok((
        uv,
        faces_array(py, &c.faces)?.into_any(),
        report_dict(py, &report)?,
    ))
}
