//! Per-face geometry: areas, corner angles and cotangents.

use conformap_mesh::TriMesh;
use rayon::prelude::*;

use crate::vec3::{dot, sub};

/// `|a × b|`, fused (no intermediate array): the corner cotangents of this module are its
/// only users.
#[inline]
fn cross_norm(a: [f64; 3], b: [f64; 3]) -> f64 {
    let x = a[1] * b[2] - a[2] * b[1];
    let y = a[2] * b[0] - a[0] * b[2];
    let z = a[0] * b[1] - a[1] * b[0];
    (x * x + y * y + z * z).sqrt()
}

/// Cotangents of the three corner angles of triangle `(p0, p1, p2)`: entry `k` is the
/// cotangent of the angle at `p_k`, i.e. of the angle opposite the edge `(p_{k+1}, p_{k+2})`.
///
/// Computed as `cot θ = (u·v) / |u × v|`, exact for obtuse angles (negative cotangent).
#[inline]
pub fn triangle_cotangents(p: [[f64; 3]; 3]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for k in 0..3 {
        let u = sub(p[(k + 1) % 3], p[k]);
        let v = sub(p[(k + 2) % 3], p[k]);
        c[k] = dot(u, v) / cross_norm(u, v);
    }
    c
}

/// Corner angles (radians) of triangle `(p0, p1, p2)`; entry `k` is the angle at `p_k`.
#[inline]
pub fn triangle_angles(p: [[f64; 3]; 3]) -> [f64; 3] {
    let mut a = [0.0; 3];
    for k in 0..3 {
        let u = sub(p[(k + 1) % 3], p[k]);
        let v = sub(p[(k + 2) % 3], p[k]);
        a[k] = cross_norm(u, v).atan2(dot(u, v));
    }
    a
}

/// The three corner positions of face `f`.
#[inline]
pub fn face_points(mesh: &TriMesh, f: usize) -> [[f64; 3]; 3] {
    let t = mesh.faces()[f];
    let p = mesh.positions();
    [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]]
}

/// Cotangents of every corner, face by face (see [`triangle_cotangents`]).
pub fn corner_cotangents(mesh: &TriMesh) -> Vec<[f64; 3]> {
    first_corner_cotangents(mesh, mesh.num_faces())
}

/// Faces per parallel task of [`first_corner_cotangents`]: `4096` (a few µs of work each).
const COTANGENT_BLOCK: usize = 4096;

/// Cotangents of every corner of the first `faces` faces (in parallel blocks; the same
/// values as face by face).
pub(crate) fn first_corner_cotangents(mesh: &TriMesh, faces: usize) -> Vec<[f64; 3]> {
    (0..faces)
        .into_par_iter()
        .with_min_len(COTANGENT_BLOCK)
        .map(|f| triangle_cotangents(face_points(mesh, f)))
        .collect()
}

/// Corner angles (radians) of every face (see [`triangle_angles`]).
pub fn corner_angles(mesh: &TriMesh) -> Vec<[f64; 3]> {
    (0..mesh.num_faces())
        .map(|f| triangle_angles(face_points(mesh, f)))
        .collect()
}

/// Area of every face.
pub fn face_areas(mesh: &TriMesh) -> Vec<f64> {
    (0..mesh.num_faces())
        .map(|f| {
            let p = face_points(mesh, f);
            0.5 * cross_norm(sub(p[1], p[0]), sub(p[2], p[0]))
        })
        .collect()
}

/// Total surface area.
pub fn surface_area(mesh: &TriMesh) -> f64 {
    face_areas(mesh).iter().sum()
}
