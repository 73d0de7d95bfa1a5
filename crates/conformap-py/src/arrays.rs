//! Arrays in and out: any real `(n, 3)` array as f64 points and any integer `(m, 3)` array
//! as u32 faces, in C or Fortran order (coerced by `numpy.ascontiguousarray`, which copies
//! nothing when the array is already float64 / int64 and C-contiguous); results as new
//! float64 arrays.

use conformap::failure::{mesh_hint, Failure};
use conformap::pipeline::Input;
use conformap_io::{Format, SourceInfo};
use conformap_mesh::TriMesh;
use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::{bad_input, bad_input_hint, to_py};

/// The path reports give for a mesh passed as arrays.
pub const MEMORY_PATH: &str = "<arrays>";

/// `numpy.ascontiguousarray(obj, dtype)` after checking that `obj`'s dtype kind is in
/// `kinds` (`"fiu"` real, `"iu"` integer); `name` names the argument in errors.
fn contiguous<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
    kinds: &str,
    dtype: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let np = obj.py().import("numpy")?;
    let arr = np.call_method1("asarray", (obj,))?;
    let kind: String = arr.getattr("dtype")?.getattr("kind")?.extract()?;
    if !kinds.contains(kind.as_str()) {
        let dt = arr.getattr("dtype")?.str()?.to_string();
        let want = if kinds == "iu" {
            "an integer"
        } else {
            "a real"
        };
        return Err(bad_input(format!(
            "{name} must be {want} array, got dtype {dt}"
        )));
    }
    np.call_method1("ascontiguousarray", (arr, dtype))
}

/// Reads `obj` as a `(n, cols)` array of f64.
pub fn points(obj: &Bound<'_, PyAny>, name: &str, cols: usize) -> PyResult<Vec<f64>> {
    let arr = contiguous(obj, name, "fiu", "float64")?;
    let arr: PyReadonlyArray2<'_, f64> = arr.extract().map_err(|_| shape_error(obj, name, cols))?;
    if arr.shape()[1] != cols {
        return Err(shape_error(obj, name, cols));
    }
    Ok(arr.as_slice()?.to_vec())
}

/// Reads `obj` as a `(m, 3)` integer array of faces, each index in `0..n`; `name` names
/// it in errors (`F`, `F_uv`). Unsigned arrays are read as such (a `uint64` 2**64 − 1 is
/// that number, not −1); 1-based indices get a hint.
pub fn faces(obj: &Bound<'_, PyAny>, name: &str, n: usize) -> PyResult<Vec<[u32; 3]>> {
    let np = obj.py().import("numpy")?;
    let kind: String = np
        .call_method1("asarray", (obj,))?
        .getattr("dtype")?
        .getattr("kind")?
        .extract()
        .unwrap_or_default();
    let flat: Vec<i128> = if kind == "u" {
        let arr = contiguous(obj, name, "iu", "uint64")?;
        let arr: PyReadonlyArray2<'_, u64> =
            arr.extract().map_err(|_| shape_error(obj, name, 3))?;
        check_cols(obj, name, arr.shape())?;
        arr.as_slice()?.iter().map(|&i| i128::from(i)).collect()
    } else {
        let arr = contiguous(obj, name, "iu", "int64")?;
        let arr: PyReadonlyArray2<'_, i64> =
            arr.extract().map_err(|_| shape_error(obj, name, 3))?;
        check_cols(obj, name, arr.shape())?;
        arr.as_slice()?.iter().map(|&i| i128::from(i)).collect()
    };
    let mut out = Vec::with_capacity(flat.len() / 3);
    for (f, tri) in flat.chunks_exact(3).enumerate() {
        let mut face = [0u32; 3];
        for k in 0..3 {
            match u32::try_from(tri[k]) {
                Ok(v) if (v as usize) < n => face[k] = v,
                _ => return Err(index_error(name, f, k, tri[k], n, &flat)),
            }
        }
        out.push(face);
    }
    Ok(out)
}

fn check_cols(obj: &Bound<'_, PyAny>, name: &str, shape: &[usize]) -> PyResult<()> {
    if shape.get(1) == Some(&3) {
        Ok(())
    } else {
        Err(shape_error(obj, name, 3))
    }
}

/// The error for index `value` at corner `k` of face `f`; when no index is 0 and the
/// largest is `n`, the hint says the array looks 1-based.
fn index_error(name: &str, f: usize, k: usize, value: i128, n: usize, all: &[i128]) -> PyErr {
    let place = if name == "F" {
        String::new()
    } else {
        format!("{name}: ")
    };
    let message = format!(
        "{place}face {f}: vertex index {value} (corner {k}) is not in 0..{n} (V has {n} rows)"
    );
    let min = all.iter().copied().min().unwrap_or(0);
    let max = all.iter().copied().max().unwrap_or(0);
    if min == 1 && max == n as i128 {
        bad_input_hint(
            message,
            format!("{name} looks 1-based (as OBJ numbers vertices): pass {name} - 1"),
        )
    } else if value < 0 {
        bad_input_hint(message, "vertex indices are 0-based and non-negative")
    } else {
        bad_input(message)
    }
}

fn shape_error(obj: &Bound<'_, PyAny>, name: &str, cols: usize) -> PyErr {
    let shape = obj
        .getattr("shape")
        .and_then(|s| s.str().map(|s| s.to_string()))
        .unwrap_or_else(|_| "unknown".to_string());
    let rows = if name.starts_with('F') { "m" } else { "n" };
    bad_input(format!(
        "{name} must have shape ({rows}, {cols}), got {shape}"
    ))
}

/// `V` and `F` as a validated mesh wrapped as the pipeline's [`Input`] (path
/// [`MEMORY_PATH`]); validation errors are the CLI's (element named), with hints for
/// arrays.
pub fn mesh_input(v: &Bound<'_, PyAny>, f: &Bound<'_, PyAny>) -> PyResult<Input> {
    mesh_input_at(v, f, MEMORY_PATH)
}

/// [`mesh_input`] with errors prefixed by `place` (`<surfaces[1]>`) instead of `<arrays>`.
pub fn mesh_input_at(v: &Bound<'_, PyAny>, f: &Bound<'_, PyAny>, place: &str) -> PyResult<Input> {
    mesh_input_with(v, f, place, false)
}

/// [`mesh_input`] as `atlas` reads a mesh: one refused only for a non-manifold vertex or
/// edge is split there ([`conformap::pipeline::split_non_manifold_mesh`]; the report's
/// `non_manifold` says where), every other defect keeps its error.
pub fn mesh_input_splitting(v: &Bound<'_, PyAny>, f: &Bound<'_, PyAny>) -> PyResult<Input> {
    mesh_input_with(v, f, MEMORY_PATH, true)
}

fn mesh_input_with(
    v: &Bound<'_, PyAny>,
    f: &Bound<'_, PyAny>,
    place: &str,
    split: bool,
) -> PyResult<Input> {
    let at = |e: PyErr| {
        if place == MEMORY_PATH {
            e
        } else {
            crate::errors::in_place(v.py(), e, place)
        }
    };
    let flat = points(v, "V", 3).map_err(at)?;
    let positions: Vec<[f64; 3]> = flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    let faces = faces(f, "F", positions.len()).map_err(at)?;
    let n = positions.len();
    let refuse = |e: conformap_mesh::MeshError| {
        let hint = array_hint(&e).or_else(|| mesh_hint(&e).map(str::to_string));
        to_py(Failure::BadInput(format!("{place}: {e}"), hint))
    };
    let (mesh, split_input) = v
        .py()
        .detach(|| {
            use conformap_mesh::MeshError as M;
            if !split {
                return TriMesh::try_new(positions, faces).map(|m| (m, None));
            }
            // the arrays are kept for the split only when it may be needed
            match TriMesh::try_new(positions.clone(), faces.clone()) {
                Ok(mesh) => Ok((mesh, None)),
                Err(e @ (M::NonManifoldVertex { .. } | M::NonManifoldEdge { .. })) => {
                    match conformap::pipeline::split_non_manifold_mesh(&positions, &faces) {
                        Some(Ok((mesh, s))) => Ok((mesh, Some(s))),
                        Some(Err(e)) => Err(e),
                        None => Err(e),
                    }
                }
                Err(e) => Err(e),
            }
        })
        .map_err(refuse)?;
    let mut input = memory_input(mesh, n);
    input.split = split_input;
    Ok(input)
}

/// Hints for invalid arrays where the CLI's speak of files.
fn array_hint(e: &conformap_mesh::MeshError) -> Option<String> {
    use conformap_mesh::MeshError as E;
    Some(match e {
        E::NoVertices | E::NoFaces { .. } => {
            "pass a mesh with vertices and faces: V (n, 3), F (m, 3), m ≥ 1".to_string()
        }
        E::NonFiniteCoordinate { .. } => {
            "replace or remove that row of V (NaN or infinity cannot be mapped)".to_string()
        }
        _ => return None,
    })
}

/// A mesh given as arrays as the pipeline's [`Input`].
pub fn memory_input(mesh: TriMesh, file_vertex_count: usize) -> Input {
    let path = std::path::PathBuf::from(MEMORY_PATH);
    let mut source = SourceInfo::new(path.clone(), Format::Obj);
    source.file_vertex_count = file_vertex_count;
    Input {
        mesh,
        source,
        repairs: None,
        path,
        split: None,
    }
}

/// An `(n, cols)` float64 array from rows.
pub fn to_array<'py, const C: usize>(
    py: Python<'py>,
    rows: &[[f64; C]],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    numpy::PyArray1::from_vec(py, flat).reshape([rows.len(), C])
}

/// An `(m, 3)` int64 array of faces.
pub fn faces_array<'py>(
    py: Python<'py>,
    faces: &[[u32; 3]],
) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let flat: Vec<i64> = faces.iter().flatten().map(|&v| i64::from(v)).collect();
    numpy::PyArray1::from_vec(py, flat).reshape([faces.len(), 3])
}

/// A JSON value as the Python object `json.loads` would give.
pub fn to_py_json<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| bad_input(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}
