//! `info`, `metrics`, `read_mesh`, `write_mesh`, `repair`: the CLI's `info --json` and
//! `metrics --json` dicts on arrays, conformap-io's readers and writers, and the CLI's
//! `--repair` on arrays.

use conformap::failure::Failure;
use conformap::jobs::info::{available_repairs, describe};
use conformap::jobs::metrics::metrics_report;
use conformap::jobs::param::PlanarMap;
use num_complex::Complex64;
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{faces, faces_array, mesh_input, points, to_array, to_py_json};
use crate::errors::{bad_input, bad_input_hint, to_py};

/// Topology and validity of a mesh, as `conformap info --json`. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (V, F))]
#[allow(non_snake_case)] // `V`, `F` as the stubs (and libigl) spell them
pub fn info<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let input = mesh_input(V, F)?;
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
#[pyo3(signature = (V, F, param))]
#[allow(non_snake_case)] // `V`, `F` as the stubs (and libigl) spell them
pub fn metrics<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    param: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let input = mesh_input(V, F)?;
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

/// Reads an OBJ / glTF / GLB mesh as `(V, F)`: float64 (n, 3) and int64 (m, 3); with
/// `repair=True` applies the CLI's `--repair` first (the vertices kept are in file order).
#[pyfunction]
#[pyo3(signature = (path, repair = false))]
pub fn read_mesh<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    repair: bool,
) -> PyResult<MeshArrays<'py>> {
    let input = py
        .detach(|| conformap::pipeline::read_input(&path, repair))
        .map_err(to_py)?;
    let mesh = &input.mesh;
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
#[pyo3(signature = (path, V, F, uv = None, F_uv = None))]
#[allow(non_snake_case)] // the keyword arguments are spelled as libigl users write them
pub fn write_mesh(
    py: Python<'_>,
    path: std::path::PathBuf,
    V: &Bound<'_, PyAny>,
    F: &Bound<'_, PyAny>,
    uv: Option<&Bound<'_, PyAny>>,
    F_uv: Option<&Bound<'_, PyAny>>,
) -> PyResult<()> {
    let written = match (uv, F_uv) {
        (None, Some(_)) => return Err(bad_input("F_uv needs uv, the rows it indexes")),
        (None, None) => {
            let flat = points(V, "V", 3)?;
            let pts: Vec<[f64; 3]> = flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
            let faces = faces(F, "F", pts.len())?;
            if faces.is_empty() {
                return Err(bad_input_hint(
                    "F has no rows: a mesh without faces cannot be written (read_mesh would \
                     refuse the file)",
                    "pass at least one face",
                ));
            }
            py.detach(|| conformap_io::write_flat(&path, &pts, &faces))
        }
        (Some(uv), None) => {
            let input = mesh_input(V, F)?;
            let flat = points(uv, "uv", 2)?;
            finite_rows(&flat, "uv")?;
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
            let input = mesh_input(V, F)?;
            let flat = points(uv, "uv", 2)?;
            finite_rows(&flat, "uv")?;
            let texcoords: Vec<[f64; 2]> = flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
            let tex_faces = faces(f_uv, "F_uv (indices into the rows of uv)", texcoords.len())?;
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

/// Refuses a NaN or infinite value in `flat` (rows of 2), naming its row.
fn finite_rows(flat: &[f64], name: &str) -> PyResult<()> {
    match flat.iter().position(|x| !x.is_finite()) {
        Some(k) => Err(bad_input_hint(
            format!(
                "{name} row {}: ({}, {}) is not finite; a texture coordinate must be a number",
                k / 2,
                flat[k - k % 2],
                flat[k - k % 2 + 1]
            ),
            format!("replace the NaN or infinite rows of {name} (numpy.isfinite({name}).all(1) finds them)"),
        )),
        None => Ok(()),
    }
}

/// `(V, F, vertex_map)` of a repair: float64 (k, 3), int64 (m, 3), int64 (k,).
pub type Repaired<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, numpy::PyArray1<i64>>,
);

/// The CLI's `--repair` on arrays: coincident vertices welded, then the repairs of
/// `conformap_mesh::repair` (duplicate faces and unreferenced vertices dropped, the largest
/// component kept, faces oriented consistently). Returns `(V, F, vertex_map)`,
/// `vertex_map[k]` the row of the input `V` that vertex `k` comes from.
#[pyfunction]
#[pyo3(signature = (V, F))]
#[allow(non_snake_case)] // `V`, `F` as the stubs (and libigl) spell them
pub fn repair<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
) -> PyResult<Repaired<'py>> {
    let flat = points(V, "V", 3)?;
    let positions: Vec<[f64; 3]> = flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect();
    let faces = faces(F, "F", positions.len())?;
    let (mesh, origin) = py
        .detach(|| repair_arrays(&positions, &faces))
        .map_err(to_py)?;
    let origin: Vec<i64> = origin.iter().map(|&i| i as i64).collect();
    Ok((
        to_array(py, mesh.positions())?,
        faces_array(py, mesh.faces())?,
        numpy::PyArray1::from_vec(py, origin),
    ))
}

/// Welds coincident vertices, repairs and validates; the mesh and the input row of each
/// of its vertices.
fn repair_arrays(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> Result<(conformap_mesh::TriMesh, Vec<usize>), Failure> {
    let at = |e: conformap_mesh::MeshError| {
        let hint = conformap::failure::mesh_hint(&e).map(str::to_string);
        Failure::BadInput(format!("{}: {e}", crate::arrays::MEMORY_PATH), hint)
    };
    // the CLI's --repair, by the same code
    let fixed = conformap::pipeline::input::weld_and_repair(positions, faces).map_err(at)?;
    let log = fixed.log;
    let origin = log.vertex_to_input.iter().map(|&c| c as usize).collect();
    let mesh = conformap_mesh::TriMesh::try_new(fixed.positions, fixed.faces)
        .map_err(|e| at(log.to_input_error(e)))?;
    Ok((mesh, origin))
}
