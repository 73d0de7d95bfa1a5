//! `global_map`: the `global` job on arrays. The region is given in memory
//! ([`conformap::jobs::global::GlobalJob::region_faces`]) instead of a `--region` file;
//! everything else is [`conformap::run_in_memory`]'s.
//!
//! The seamed layout comes back as libigl / trimesh keep seamed texture coordinates: `uv`
//! `(k, 2)`, one row per corner class (a vertex, split where a seam passes through it),
//! and `F_uv` `(m, 3)`, per face the row of each corner.

use conformap::failure::Failure;
use conformap::pipeline::TexCoords;
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use crate::arrays::{faces_array, mesh_input, to_array};
use crate::errors::to_py;
use crate::keywords;
use crate::maps::{report_dict, run};
use crate::options;

/// Global conformal parameterization of a surface with handles by a holomorphic 1-form, as
/// `conformap global`: returns `(uv, F_uv, report)`, the seamed layout (`uv` (k, 2) one
/// row per corner class, `F_uv` (m, 3) per face the row of each corner); with
/// `return_mesh=True` also the mesh it belongs to (the full documentation is in
/// `conformap.pyi`).
///
/// Example: `uv, F_uv, report = conformap.global_map(V, F, "zeros", zeros=[10])`
#[pyfunction]
#[pyo3(signature = (V, F, objective = "uniform", *, form = None, region = None, zeros = None,
    starts = None, conjugate = "nearest", root = None, topology_opt = false,
    return_mesh = false, strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments, non_snake_case)] // `V`, `F` as the stubs spell them
pub fn global_map<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    objective: &str,
    form: Option<&Bound<'py, PyAny>>,
    region: Option<&Bound<'py, PyAny>>,
    zeros: Option<&Bound<'py, PyAny>>,
    starts: Option<&Bound<'py, PyAny>>,
    conjugate: &str,
    root: Option<&Bound<'py, PyAny>>,
    topology_opt: bool,
    return_mesh: bool,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyTuple>> {
    let job = keywords::global_job(
        objective,
        form,
        region,
        zeros,
        starts,
        conjugate,
        root,
        topology_opt,
        strict,
    )?;
    let max_memory = options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
    let job = keywords::global_region(job, region, input.mesh.num_faces())?;
    let (solved, report) = run(py, &job, &input, max_memory, strict)?;
    // a per-vertex layout (`topology_opt` on a genus-0 surface): `F_uv` is `F`
    let per_vertex_faces = input.mesh.faces().to_vec();
    let uv: Vec<[f64; 2]> = solved.flat.0.iter().map(|p| [p[0], p[1]]).collect();
    // `topology_opt` on a genus-0 surface may return the starting sphere map: unit vectors
    let sphere = matches!(solved.uv, TexCoords::PerVertex(_))
        && solved.flat.0.iter().any(|p| p[2].abs() > 0.0);
    let (laid_out, tex_faces) = match &solved.uv {
        TexCoords::PerCorner(c) => (&input.mesh, &c.faces),
        TexCoords::Refined { mesh, uv } => (mesh, &uv.faces),
        TexCoords::PerVertex(_) => (&input.mesh, &per_vertex_faces),
    };
    if !return_mesh && laid_out.num_faces() != input.mesh.num_faces() {
        return Err(to_py(Failure::BadInput(
            format!(
                "the double covering split boundary chords: the layout belongs to a refined \
                 mesh of {} faces, not F's {}",
                laid_out.num_faces(),
                input.mesh.num_faces()
            ),
            Some("pass return_mesh=True to get that mesh with the layout".to_string()),
        )));
    }
    let layout = if sphere {
        to_array(py, &solved.flat.0)?
    } else {
        to_array(py, &uv)?
    };
    let mut items: Vec<Bound<'py, PyAny>> = vec![
        layout.into_any(),
        faces_array(py, tex_faces)?.into_any(),
        report_dict(py, &report)?,
    ];
    if return_mesh {
        items.push(to_array(py, laid_out.positions())?.into_any());
        items.push(faces_array(py, laid_out.faces())?.into_any());
    }
    PyTuple::new(py, items)
}
