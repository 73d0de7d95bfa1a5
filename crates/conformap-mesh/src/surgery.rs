//! Mesh surgery: closing boundary loops with centroid fans (the patches P_i of CEM §3.3).

use crate::{MeshError, TriMesh};

/// A mesh whose chosen boundary loops were closed by centroid fans.
///
/// The original vertices keep their indices `0..original_vertices`; vertex
/// `original_vertices + j` is the centroid added for `filled_loops[j]`; the original faces
/// come first, in order, so "opening the holes" is taking the first `original_faces` faces
/// and the first `original_vertices` map values.
#[derive(Debug, Clone)]
pub struct FilledMesh {
    /// The closed-up mesh.
    pub mesh: TriMesh,
    /// Number of vertices of the input mesh.
    pub original_vertices: usize,
    /// Number of faces of the input mesh.
    pub original_faces: usize,
    /// Indices (into the input's `boundary_loops()`) of the loops that were filled.
    pub filled_loops: Vec<usize>,
}

/// Fills the boundary loops listed in `loops` (indices into `mesh.boundary_loops()`) with a
/// fan around the centroid of each loop's vertices.
///
/// # Errors
/// [`MeshError`] if the filled mesh is invalid (e.g. a fan triangle is degenerate because
/// the loop is flat and its centroid lies on one of its edges).
pub fn fill_holes(mesh: &TriMesh, loops: &[usize]) -> Result<FilledMesh, MeshError> {
    let mut positions = mesh.positions().to_vec();
    let mut faces = mesh.faces().to_vec();
    let mut filled = Vec::with_capacity(loops.len());
    for &li in loops {
        let lp = &mesh.boundary_loops()[li];
        let mut c = [0.0; 3];
        for &v in lp {
            let p = mesh.positions()[v as usize];
            for k in 0..3 {
                c[k] += p[k];
            }
        }
        let m = lp.len() as f64;
        let centre = positions.len() as u32;
        positions.push([c[0] / m, c[1] / m, c[2] / m]);
        // the loop runs with the surface on its left; the patch must run the other way
        for i in 0..lp.len() {
            let a = lp[i];
            let b = lp[(i + 1) % lp.len()];
            faces.push([b, a, centre]);
        }
        filled.push(li);
    }
    Ok(FilledMesh {
        mesh: TriMesh::try_new(positions, faces)?,
        original_vertices: mesh.num_vertices(),
        original_faces: mesh.num_faces(),
        filled_loops: filled,
    })
}
