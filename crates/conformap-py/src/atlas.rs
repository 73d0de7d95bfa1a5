//! `atlas`: the `atlas` job (a texture atlas of any mesh) on arrays.

use conformap::jobs::atlas::AtlasJob;
use conformap::pipeline::{InputOptions, OutputOptions, TexCoords};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{faces_array, mesh_input, to_array, MEMORY_PATH};
use crate::errors::bad_input;
use crate::maps::{report_dict, run};
use crate::options::{self, nonneg, opt_count};

/// A texture atlas, as `conformap atlas`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F, cones = None, *, resolution = 1024, margin = 2.0, strict = false,
    max_memory = None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity, non_snake_case)] // `V`, `F` as the stubs spell them
pub fn atlas<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    cones: Option<&Bound<'py, PyAny>>,
    resolution: i64,
    margin: f64,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let mut job = AtlasJob::new(
        InputOptions::new(MEMORY_PATH),
        OutputOptions::new(MEMORY_PATH).with_strict(strict),
    );
    job.cones = opt_count(cones, "cones")?;
    job.resolution = nonneg(resolution, "resolution")?;
    job.margin = margin;
    let max_memory = options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
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
