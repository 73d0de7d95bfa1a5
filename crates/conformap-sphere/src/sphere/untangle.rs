//! The last step of the sphere map's flip-free guard: local untangling of inverted faces.
//! Each round moves the vertices of the inverted faces and their neighbours to the
//! normalized weighted mean of their neighbours under a Laplacian without negative weights
//! (the intrinsic Delaunay one), a discrete harmonic step on the sphere that pulls a
//! folded vertex back inside its ring; everything farther away is left as it is.

use conformap_mesh::TriMesh;
use sprs::CsMat;

use crate::stereo::det3;
use conformap_operators::vec3::norm;

/// Untangling rounds at most: 60 (each costs a pass over the faces; a planted fold of the
/// tests untangles in 1–5).
pub const SPHERE_UNTANGLE_MAX_ROUNDS: usize = 60;

/// Rounds after which the moved region grows by one more ring: 10. A fold whose ring is
/// not star-shaped around the folded vertex cannot be undone by moving the ring alone; a
/// wider region lets the neighbourhood relax (up to 6 rings).
const SPHERE_UNTANGLE_ROUNDS_PER_RING: usize = 10;

/// Faces whose chord triangle is not counter-clockwise seen from outside.
pub(crate) fn inverted_faces(mesh: &TriMesh, points: &[[f64; 3]]) -> Vec<usize> {
    mesh.faces()
        .iter()
        .enumerate()
        .filter(|(_, t)| {
            det3(
                points[t[0] as usize],
                points[t[1] as usize],
                points[t[2] as usize],
            ) <= 0.0
        })
        .map(|(f, _)| f)
        .collect()
}

/// Untangles `points` in place (see the module docs) with the weights `−l_uv` of `l`
/// (negative ones are taken as 0), or with weight 1 on every edge of `l` (Tutte's) when
/// `uniform`; returns the inverted faces left.
pub(crate) fn untangle(
    mesh: &TriMesh,
    l: &CsMat<f64>,
    uniform: bool,
    points: &mut [[f64; 3]],
) -> usize {
    let n = points.len();
    for round in 0..SPHERE_UNTANGLE_MAX_ROUNDS {
        let bad = inverted_faces(mesh, points);
        if bad.is_empty() {
            return 0;
        }
        let mut moved = vec![false; n];
        for &f in &bad {
            for &v in &mesh.faces()[f] {
                moved[v as usize] = true;
            }
        }
        for _ in 0..1 + round / SPHERE_UNTANGLE_ROUNDS_PER_RING {
            let ring: Vec<usize> = (0..n).filter(|&v| moved[v]).collect();
            for v in ring {
                if let Some(col) = l.outer_view(v) {
                    for (u, _) in col.iter() {
                        moved[u] = true;
                    }
                }
            }
        }
        for v in (0..n).filter(|&v| moved[v]) {
            let Some(col) = l.outer_view(v) else { continue };
            let mut s = [0.0; 3];
            for (u, &w) in col.iter().filter(|&(u, _)| u != v) {
                let w = if uniform { 1.0 } else { (-w).max(0.0) };
                for k in 0..3 {
                    s[k] += w * points[u][k];
                }
            }
            let r = norm(s);
            if r > 0.0 && r.is_finite() {
                points[v] = [s[0] / r, s[1] / r, s[2] / r];
            }
        }
    }
    inverted_faces(mesh, points).len()
}
