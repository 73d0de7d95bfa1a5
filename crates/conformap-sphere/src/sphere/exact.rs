//! Two exact facts the sphere map uses on small and coarse meshes.
//!
//! - **Inscribed meshes.** A mesh whose vertices lie on one sphere and whose radial
//!   projection turns no face over is its own conformal map to the sphere: the radial
//!   projection keeps every length cross-ratio (chords of the sphere are the mesh's edges,
//!   scaled), which is what discrete conformal equivalence asks (Bobenko, Pinkall,
//!   Springborn 2015: an inscribed Delaunay polyhedron is its own uniformization). The
//!   regular solids, geodesic spheres and any convex hull of points on a sphere are such.
//! - **Möbius centring.** A sphere map is defined up to a Möbius map. Coarse meshes have
//!   faces covering a good part of the sphere, and whether such a face's chord triangle is
//!   counter-clockwise depends on that normalization (a face larger than a hemisphere
//!   inverts). Moving the centroid of the vertices to the origin (the Möbius-invariant
//!   "centred" normalization) spreads the faces evenly and removes those inversions.

use conformap_mesh::TriMesh;
use conformap_operators::vec3::{norm, scale, sub};

use crate::stereo::det3;

/// Largest spread of the distances of the vertices from the fitted sphere's centre, relative
/// to their mean, for a mesh to count as inscribed: 1e-9.
pub const SPHERE_INSCRIBED_TOL: f64 = 1e-9;

/// Most centring steps: 100 (each a pass over the vertices; the solids and meshes
/// measured centre to 1e-12 in under 30).
const CENTRING_MAX_STEPS: usize = 100;

/// Centroid norm at which centring stops: 1e-13.
const CENTRING_TOL: f64 = 1e-13;

/// The radial projection of `mesh` from the centre of the sphere through its vertices, if
/// it has one (within [`SPHERE_INSCRIBED_TOL`]) and the projection turns no face over.
pub(crate) fn inscribed_radial(mesh: &TriMesh) -> Option<Vec<[f64; 3]>> {
    let p = mesh.positions();
    let c = fitted_centre(p)?;
    let r: Vec<f64> = p.iter().map(|&q| norm(sub(q, c))).collect();
    let mean = r.iter().sum::<f64>() / r.len() as f64;
    let spread = r.iter().map(|x| (x - mean).abs()).fold(0.0, f64::max);
    if !(mean > 0.0 && spread <= SPHERE_INSCRIBED_TOL * mean) {
        return None;
    }
    let points: Vec<[f64; 3]> = p
        .iter()
        .zip(&r)
        .map(|(&q, &d)| scale(1.0 / d, sub(q, c)))
        .collect();
    let turned = mesh.faces().iter().any(|t| {
        det3(
            points[t[0] as usize],
            points[t[1] as usize],
            points[t[2] as usize],
        ) <= 0.0
    });
    (!turned).then_some(points)
}

/// The centre `c` of the least-squares sphere `|p|² = 2 c·p + k` through the points, or
/// `None` if the 4 × 4 normal equations are singular (coplanar points).
fn fitted_centre(p: &[[f64; 3]]) -> Option<[f64; 3]> {
    // shift to the centroid for conditioning
    let n = p.len() as f64;
    let g = [0, 1, 2].map(|i| p.iter().map(|q| q[i]).sum::<f64>() / n);
    let mut a = [[0.0f64; 5]; 4];
    for q in p {
        let d = sub(*q, g);
        let row = [2.0 * d[0], 2.0 * d[1], 2.0 * d[2], 1.0];
        let rhs = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        for i in 0..4 {
            for j in 0..4 {
                a[i][j] += row[i] * row[j];
            }
            a[i][4] += row[i] * rhs;
        }
    }
    let x = solve4(a)?;
    Some([x[0] + g[0], x[1] + g[1], x[2] + g[2]])
}

/// Gaussian elimination with partial pivoting on an augmented 4 × 5 system.
fn solve4(mut a: [[f64; 5]; 4]) -> Option<[f64; 4]> {
    let size = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for col in 0..4 {
        let piv = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if !(a[piv][col].abs() > 1e-12 * size) {
            return None;
        }
        a.swap(col, piv);
        for row in col + 1..4 {
            let f = a[row][col] / a[col][col];
            for k in col..5 {
                a[row][k] -= f * a[col][k];
            }
        }
    }
    let mut x = [0.0; 4];
    for i in (0..4).rev() {
        let s: f64 = (i + 1..4).map(|k| a[i][k] * x[k]).sum();
        x[i] = (a[i][4] - s) / a[i][i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Moves `points` (on the unit sphere) by the Möbius map that brings their centroid to the
/// origin: repeated hyperbolic steps `x ↦ (1 − |a|²)(x − a)/|x − a|² − a` with `a` the
/// current centroid (damped to `|a| ≤ ½`), until the centroid is below 1e-13 or 100 steps.
/// Returns whether it converged.
pub(crate) fn centre(points: &mut [[f64; 3]]) -> bool {
    let n = points.len() as f64;
    for _ in 0..CENTRING_MAX_STEPS {
        let c = [0, 1, 2].map(|i| points.iter().map(|q| q[i]).sum::<f64>() / n);
        let m = norm(c);
        if m <= CENTRING_TOL {
            return true;
        }
        let a = scale(m.min(0.5) / m, c);
        let r = 1.0 - (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for x in points.iter_mut() {
            let d = sub(*x, a);
            let q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if q > 0.0 {
                let y = [0, 1, 2].map(|i| r * d[i] / q - a[i]);
                let l = norm(y);
                *x = scale(1.0 / l, y);
            }
        }
    }
    false
}
