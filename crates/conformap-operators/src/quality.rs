//! How well a mesh suits the cotangent Laplacian: its extreme corner angles and its
//! non-Delaunay edges (negative cotangent weight), as `conformap info` reports them.

use conformap_mesh::TriMesh;

use crate::geometry::{face_points, triangle_angles};
use crate::laplacian::cotan_laplacian;
use crate::vec3::{cross, dot, norm, sub};

/// Corner angles and cotangent weights of a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MeshQuality {
    /// Smallest corner angle, degrees.
    pub angle_min_deg: f64,
    /// Largest corner angle, degrees.
    pub angle_max_deg: f64,
    /// Edges whose cotangent weight `−L_ij` is negative (non-Delaunay edges: the two
    /// opposite angles sum to more than π; a boundary edge, to an obtuse opposite angle).
    pub negative_cotan_edges: usize,
    /// [`Self::negative_cotan_edges`] over all edges.
    pub negative_cotan_edge_fraction: f64,
    /// Interior edges whose two faces' normals are nearly opposite (cosine below
    /// [`FOLD_NORMAL_COS`]): a geometric fold, such as a scan's folded sliver. A valid mesh
    /// may have them; maps of it need the flip-free guards.
    pub folded_edges: usize,
}

/// Cosine of the angle between adjacent face normals below which [`mesh_quality`] counts a
/// fold: −0.9, normals more than 154° apart (a crease folded back on itself; the sharpest
/// real features of the shared meshes stay above it).
pub const FOLD_NORMAL_COS: f64 = -0.9;

/// The [`MeshQuality`] of `mesh`: one pass over the faces and one over the cotangent
/// Laplacian's upper triangle.
///
/// # Examples
/// ```
/// use conformap_operators::mesh_quality;
/// // a unit square split along a diagonal: right angles and 45°, every weight ≥ 0
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let q = mesh_quality(&mesh);
/// assert!((q.angle_min_deg - 45.0).abs() < 1e-12 && (q.angle_max_deg - 90.0).abs() < 1e-12);
/// assert_eq!(q.negative_cotan_edges, 0);
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn mesh_quality(mesh: &TriMesh) -> MeshQuality {
    let (mut amin, mut amax) = (f64::INFINITY, 0.0f64);
    for f in 0..mesh.num_faces() {
        for a in triangle_angles(face_points(mesh, f)) {
            amin = amin.min(a);
            amax = amax.max(a);
        }
    }
    let l = cotan_laplacian(mesh);
    // an edge's weight is −L_ij: count edges (upper triangle) with L_ij > 0
    let negative = l
        .outer_iterator()
        .enumerate()
        .map(|(j, col)| col.iter().filter(|&(i, &v)| i < j && v > 0.0).count())
        .sum::<usize>();
    let normal = |f: usize| {
        let p = face_points(mesh, f);
        let (u, v) = (sub(p[1], p[0]), sub(p[2], p[0]));
        let n = cross(u, v);
        // not `vec3::normalize`: a degenerate face's normal is NaN here, never folded
        let r = norm(n);
        n.map(|x| x / r)
    };
    let opp = mesh.opposite_halfedges();
    let folded_edges = (0..opp.len())
        .filter(|&h| opp[h] != conformap_mesh::NO_HALFEDGE && (h as u32) < opp[h])
        .filter(|&h| {
            let (a, b) = (normal(h / 3), normal(opp[h] as usize / 3));
            dot(a, b) < FOLD_NORMAL_COS
        })
        .count();
    MeshQuality {
        folded_edges,
        angle_min_deg: amin.to_degrees(),
        angle_max_deg: amax.to_degrees(),
        negative_cotan_edges: negative,
        negative_cotan_edge_fraction: negative as f64 / mesh.num_edges().max(1) as f64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_obtuse_pair_makes_one_negative_edge() {
        // two triangles sharing edge 0–1 whose opposite angles are both ~ 127°
        let mesh = TriMesh::try_new(
            vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [1.0, 0.5, 0.0],
                [1.0, -0.5, 0.0],
            ],
            vec![[0, 1, 2], [1, 0, 3]],
        )
        .expect("valid");
        let q = mesh_quality(&mesh);
        // only the shared edge: its opposite angles sum to ~ 254°; the boundary edges face
        // acute angles
        assert_eq!(q.negative_cotan_edges, 1);
        assert!((q.negative_cotan_edge_fraction - 0.2).abs() < 1e-15);
        let apex = 180.0 - 2.0 * 0.5f64.atan().to_degrees();
        assert!((q.angle_max_deg - apex).abs() < 1e-9, "{}", q.angle_max_deg);
        assert_eq!(q.folded_edges, 0);
        // fold the second triangle back over the first: its apex above the first one
        let folded = TriMesh::try_new(
            vec![
                [0.0, 0.0, 0.0],
                [2.0, 0.0, 0.0],
                [1.0, 0.5, 0.0],
                [1.0, 0.4, 0.05],
            ],
            vec![[0, 1, 2], [1, 0, 3]],
        )
        .expect("valid");
        assert_eq!(mesh_quality(&folded).folded_edges, 1);
    }
}
