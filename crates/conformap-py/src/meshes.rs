//! `info`, `metrics`, `read_mesh`, `write_mesh`: the CLI's `info --json` and
//! `metrics --json` dicts on arrays, and conformap-io's readers and writers.

use conformap::failure::Failure;
use conformap::jobs::info::{available_repairs, describe};
use conformap::jobs::metrics::metrics_report;
use conformap::jobs::param::PlanarMap;
use num_complex::Complex64;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{faces, faces_array, mesh_input, points, to_array, to_py_json};
use crate::errors::{bad_input, to_py};

/// Topology and validity of a mesh, as `conformap info --json`. See `conformap.pyi`.
#[pyfunction]
pub fn info<'py>(
    py: Python<'py>,
    v: &Bound<'py, PyAny>,
    f: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let input = mesh_input(v, f)?;
    let value = py.detach(|| {
        let mut info = describe(&input.mesh, &input.path);
        info.repairs_available = Some(available_repairs(&input.mesh));
        serde_json::to_value(&info)
    });
    to_py_json(py, &value.map_err(|e| bad_input(e.to_string()))?)
}

/// Quality of a planar map `param` ((n, 2), one point per vertex), as
/// `conformap metrics --json`. See `conformap.pyi`.
#[pyfunction]
pub fn metrics<'py>(
    py: Python<'py>,
    v: &Bound<'py, PyAny>,
    f: &Bound<'py, PyAny>,
    param: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let input = mesh_input(v, f)?;
    let flat = points(param, "param", 2)?;
    let n = input.mesh.num_vertices();
    if flat.len() != 2 * n {
        return Err(bad_input(format!(
            "param has {} rows, the mesh {n} vertices: one map point per vertex is needed",
            flat.len() / 2
        )));
    }
    let map = PlanarMap::PerVertex(
        flat.chunks_exact(2)
            .map(|p| Complex64::new(p[0], p[1]))
            .collect(),
    );
    let report = py
        .detach(|| metrics_report(&input.mesh, &input.path, &map, "<array>", "array (u, v)"))
        .map_err(to_py)?;
    let value = serde_json::to_value(&report).map_err(|e| bad_input(e.to_string()))?;
    to_py_json(py, &value)
}

/// `(V, F)` as numpy arrays: float64 (n, 3), int64 (m, 3).
pub type MeshArrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>);

/// Reads an OBJ / glTF / GLB mesh as `(V, F)`: float64 (n, 3) and int64 (m, 3).
#[pyfunction]
pub fn read_mesh<'py>(py: Python<'py>, path: std::path::PathBuf) -> PyResult<MeshArrays<'py>> {
    let loaded = py
        .detach(|| conformap_io::read_mesh(&path))
        .map_err(|e| to_py(Failure::from(e)))?;
    let mesh = &loaded.mesh;
    Ok((
        to_array(py, mesh.positions())?,
        faces_array(py, mesh.faces())?,
    ))
}

/// Writes `(V, F)` to an OBJ / glTF / GLB file, with texture coordinates `uv` written as
/// given when passed: one per vertex ((n, 2)), or, with `F_uv`, a seamed layout (`uv`
/// (k, 2), `F_uv` (m, 3) rows of `uv` per face corner, as `global_map` returns; OBJ
/// `f v/vt`, glTF split along the seams).
#[pyfunction]
#[pyo3(signature = (path, v, f, uv = None, F_uv = None))]
#[allow(non_snake_case)] // the keyword argument is spelled as libigl users write it
pub fn write_mesh(
    py: Python<'_>,
    path: std::path::PathBuf,
    v: &Bound<'_, PyAny>,
    f: &Bound<'_, PyAny>,
    uv: Option<&Bound<'_, PyAny>>,
    F_uv: Option<&Bound<'_, PyAny>>,
) -> PyResult<()> {
    let written = match (uv, F_uv) {
        (None, Some(_)) => return Err(bad_input("F_uv needs uv, the rows it indexes")),
        (None, None) => {
            let flat = points(v, "V", 3)?;
            let pts: Vec<[f64; 3]> = flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
            let faces = faces(f, pts.len())?;
            py.detach(|| conformap_io::write_flat(&path, &pts, &faces))
        }
        (Some(uv), None) => {
            let input = mesh_input(v, f)?;
            let flat = points(uv, "uv", 2)?;
            let n = input.mesh.num_vertices();
            if flat.len() != 2 * n {
                return Err(bad_input(format!(
                    "uv has {} rows, V {n}: one texture coordinate per vertex is needed (or \
                     pass F_uv for a seamed layout)",
                    flat.len() / 2
                )));
            }
            let uv: Vec<[f64; 2]> = flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
            py.detach(|| conformap_io::write_mesh_with_uv(&path, &input.mesh, &uv, None))
        }
        (Some(uv), Some(f_uv)) => {
            let input = mesh_input(v, f)?;
            let flat = points(uv, "uv", 2)?;
            let texcoords: Vec<[f64; 2]> = flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
            let tex_faces = faces(f_uv, texcoords.len()).map_err(|e| {
                crate::errors::in_place(py, e, "F_uv (indices into the rows of uv)")
            })?;
            if tex_faces.len() != input.mesh.num_faces() {
                return Err(bad_input(format!(
                    "F_uv has {} rows, F {}: one row of uv indices per face is needed",
                    tex_faces.len(),
                    input.mesh.num_faces()
                )));
            }
            let corner = conformap_io::CornerUv {
                texcoords,
                faces: tex_faces,
            };
            py.detach(|| conformap_io::write_mesh_with_corner_uv(&path, &input.mesh, &corner))
        }
    };
    written.map_err(|e| to_py(Failure::from(e)))
}
