//! Floater's mean value weights (M. S. Floater, *Mean value coordinates*, CAGD 20, 2003,
//! Eq. 5.1 / Prop. 1): positive on every triangulation, so a map that makes each interior
//! vertex the weighted mean of its neighbours, with the boundary on a convex polygon, is
//! one-to-one on the input triangulation (Floater 2003, *One-to-one piecewise linear
//! mappings over triangulations*, Thm. 6.1). Not symmetric and not a Laplacian of any
//! energy: a last resort where harmonic maps fold.

use conformap_mesh::TriMesh;
use sprs::{CsMat, TriMat};

use crate::vec3::{cross, dot, norm, sub};

/// `tan(θ/2)` of the angle between `u` and `v`, as `|u × v| / (|u||v| + u·v)`: no
/// cancellation for small angles, finite for every angle below `π`.
#[inline]
fn half_angle_tan(u: [f64; 3], v: [f64; 3]) -> f64 {
    norm(cross(u, v)) / (norm(u) * norm(v) + dot(u, v))
}

/// The mean value matrix `M` of `mesh` (CSC, `n × n`, not symmetric): row `i` holds
/// `M_ij = −λ_ij` for every neighbour `j` and `M_ii = Σ_j λ_ij`, with Floater's weights
/// `λ_ij = (tan(α_ij/2) + tan(β_ij/2)) / |v_j − v_i|` (`α_ij`, `β_ij` the corner angles at
/// `v_i` on either side of the edge `ij`, measured in 3D). Rows sum to zero; every
/// off-diagonal entry is negative. Solving `M_II f_I = −M_IB f_B` puts every interior
/// vertex at the λ-weighted mean of its neighbours.
///
/// # Examples
/// ```
/// use conformap_mesh::TriMesh;
/// use conformap_operators::mean_value_matrix;
/// // a centred regular hexagon fan: the centre is the plain mean of its neighbours
/// let mut pos = vec![[0.0, 0.0, 0.0]];
/// for k in 0..6 {
///     let t = k as f64 * std::f64::consts::PI / 3.0;
///     pos.push([t.cos(), t.sin(), 0.0]);
/// }
/// let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
/// let mesh = TriMesh::try_new(pos, faces)?;
/// let m = mean_value_matrix(&mesh);
/// let w = 2.0 * (std::f64::consts::PI / 6.0).tan(); // two half-angles of 30°, |e| = 1
/// assert!((m.get(0, 0).unwrap() - 6.0 * w).abs() < 1e-14);
/// assert!((m.get(0, 3).unwrap() + w).abs() < 1e-14);
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn mean_value_matrix(mesh: &TriMesh) -> CsMat<f64> {
    let n = mesh.num_vertices();
    let p = mesh.positions();
    let mut tri = TriMat::with_capacity((n, n), 12 * mesh.num_faces());
    for t in mesh.faces() {
        for k in 0..3 {
            let i = t[k] as usize;
            let (j, l) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
            let (u, v) = (sub(p[j], p[i]), sub(p[l], p[i]));
            let h = half_angle_tan(u, v);
            // the corner at i lies on one side of edge ij and of edge il
            for (other, e) in [(j, u), (l, v)] {
                let w = h / norm(e);
                tri.add_triplet(i, other, -w);
                tri.add_triplet(i, i, w);
            }
        }
    }
    tri.to_csc()
}
