//! `flatten`: the `flatten` job (boundary first flattening) on arrays, the boundary values
//! given in memory instead of a file.

use std::fmt::Write;

use conformap::jobs::flatten::{FlattenJob, Interior};
use conformap::pipeline::{InputOptions, OutputOptions};
use conformap_disk::BoundarySpec;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{mesh_input, to_array, MEMORY_PATH};
use crate::errors::usage;
use crate::maps::{choice, report_dict, run};

/// The boundary target from its name and, for `scale`, `angles` and `polygon`, its values.
fn boundary_spec(
    boundary: &str,
    values: Option<&[(u32, f64)]>,
) -> PyResult<(BoundarySpec, Option<String>)> {
    let named = |what: &str| std::path::PathBuf::from(format!("<{what} values>"));
    let spec = match boundary {
        "scale" => BoundarySpec::Scale(named("scale")),
        "angles" => BoundarySpec::Angles(named("angles")),
        "polygon" => BoundarySpec::Polygon(named("polygon")),
        other => BoundarySpec::parse(other).map_err(|_| {
            usage(format!(
                "boundary must be one of free, circle, rectangle, scale, angles, polygon, got \
                 {other:?}"
            ))
        })?,
    };
    let wants = matches!(
        spec,
        BoundarySpec::Scale(_) | BoundarySpec::Angles(_) | BoundarySpec::Polygon(_)
    );
    match (wants, values) {
        (true, Some(v)) => {
            let mut text = String::new();
            for (vertex, value) in v {
                let _ = writeln!(text, "{vertex} {value:?}");
            }
            Ok((spec, Some(text)))
        }
        (true, None) => Err(usage(format!(
            "boundary={boundary:?} needs values: a dict or a sequence of (vertex, value) pairs"
        ))),
        (false, Some(_)) => Err(usage(format!(
            "values are for boundary='scale', 'angles' or 'polygon', not {boundary:?}"
        ))),
        (false, None) => Ok((spec, None)),
    }
}

/// `(vertex, value)` pairs from a dict or a sequence of pairs.
fn pairs(values: &Bound<'_, PyAny>) -> PyResult<Vec<(u32, f64)>> {
    let items = match values.cast::<pyo3::types::PyDict>() {
        Ok(d) => d.items().into_any(),
        Err(_) => values.clone(),
    };
    items.extract::<Vec<(u32, f64)>>().map_err(|_| {
        usage("values must be a dict {vertex: value} or a sequence of (vertex, value) pairs (0-based vertices)".to_string())
    })
}

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
    let values = values.map(pairs).transpose()?;
    let (spec, text) = boundary_spec(boundary, values.as_deref())?;
    let mut job = FlattenJob::new(
        InputOptions::new(MEMORY_PATH),
        OutputOptions::new(MEMORY_PATH),
    )
    .with_boundary(spec)
    .with_interior(choice::<Interior>("interior", interior)?);
    job.corners = corners;
    job.aspect = aspect;
    job.boundary_text = text;
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
