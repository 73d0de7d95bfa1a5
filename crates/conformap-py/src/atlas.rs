//! `atlas`: the `atlas` job (a texture atlas of any mesh) on arrays.

use conformap::pipeline::TexCoords;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{faces_array, mesh_input_splitting, to_array};
use crate::errors::bad_input;
use crate::keywords;
use crate::maps::{report_dict, run};
use crate::options;

// the signature's literal default of `max_area_spread` (a constant would show as `...`)
const _: () = assert!(conformap::jobs::atlas::DEFAULT_MAX_AREA_SPREAD == 1.0);

/// A texture atlas, as `conformap atlas`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F, cones = None, *, resolution = 1024, margin = 2.0,
    max_area_spread = 1.0, pack = "square",
    scale = "uniform", seamless = false, polish = None, strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments, clippy::type_complexity, non_snake_case)] // `V`, `F` as the stubs spell them
pub fn atlas<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    cones: Option<&Bound<'py, PyAny>>,
    resolution: i64,
    margin: f64,
    max_area_spread: f64,
    pack: &str,
    scale: &str,
    seamless: bool,
    polish: Option<&Bound<'py, PyAny>>,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
)> {
    let job = keywords::atlas_job(
        cones,
        resolution,
        margin,
        max_area_spread,
        pack,
        scale,
        seamless,
        polish,
        strict,
    )?;
    let max_memory = options::max_memory(max_memory)?;
    let input = mesh_input_splitting(V, F)?;
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
