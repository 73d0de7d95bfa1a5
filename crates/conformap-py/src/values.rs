//! Keyword values: Python objects turned into the jobs' option values (an option enum by
//! its name, boundary targets and their values, vertex and face lists), each checked with
//! the message the CLI gives. Shared by the map functions and [`crate::keywords`]; it uses
//! no other module of the package but arrays and errors, so no file circle passes through it.

use std::fmt::Write;

use conformap::jobs::param::region_face;
use conformap::Choice;
use conformap_disk::BoundarySpec;
use pyo3::prelude::*;

use crate::errors::{bad_input, to_py, usage};

/// A value of a job's option enum (`method`, `ordering`, `mobius`) by its name.
pub(crate) fn choice<T: Choice>(name: &str, value: &str) -> PyResult<T> {
    T::parse_name(value).map_err(|e| {
        usage(format!(
            "{name} must be one of {}, got {value:?}",
            e.names.join(", ")
        ))
    })
}

/// The boundary target from its name and, for `scale`, `angles` and `polygon`, its values.
pub(crate) fn boundary_spec(
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
pub(crate) fn pairs(values: &Bound<'_, PyAny>) -> PyResult<Vec<(u32, f64)>> {
    let items = match values.cast::<pyo3::types::PyDict>() {
        Ok(d) => d.items().into_any(),
        Err(_) => values.clone(),
    };
    items.extract::<Vec<(u32, f64)>>().map_err(|_| {
        usage("values must be a dict {vertex: value} or a sequence of (vertex, value) pairs (0-based vertices)".to_string())
    })
}

/// Vertex indices from a Python sequence of integers; `name` names it in errors.
pub(crate) fn vertex_list(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<usize>> {
    let values: Vec<i64> = obj.extract().map_err(|_| {
        bad_input(format!(
            "{name} must be a sequence of integer vertex indices (0-based)"
        ))
    })?;
    values
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            usize::try_from(v)
                .map_err(|_| bad_input(format!("{name}[{k}]: {v} is not a vertex index (0-based)")))
        })
        .collect()
}

/// The faces of `region` (any integer sequence or array), each checked against `faces`
/// with the CLI's message (`region[k]` standing for the file and line).
pub fn region_faces(region: &Bound<'_, PyAny>, faces: usize) -> PyResult<Vec<usize>> {
    let np = region.py().import("numpy")?;
    let arr = np.call_method1("asarray", (region,))?;
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    let ndim: usize = arr.getattr("ndim")?.extract()?;
    let size: usize = arr.getattr("size")?.extract()?;
    // an empty list has dtype float64: let it through as no face
    if ndim != 1 || (size > 0 && !"iu".contains(kind.as_str())) {
        return Err(bad_input(format!(
            "region must be a 1-D sequence of integer face indices, got {} with dtype {}",
            arr.getattr("shape")?.str()?,
            arr.getattr("dtype")?.str()?
        )));
    }
    let values: Vec<i64> = if size == 0 {
        Vec::new()
    } else {
        arr.call_method1("astype", ("int64",))?
            .call_method0("tolist")?
            .extract()?
    };
    values
        .iter()
        .enumerate()
        .map(|(k, &f)| {
            let place = format!("region[{k}]");
            let f = usize::try_from(f)
                .map_err(|_| bad_input(format!("{place}: {f} is not a face index (0-based)")))?;
            region_face(f, faces, &place).map_err(to_py)
        })
        .collect()
}
