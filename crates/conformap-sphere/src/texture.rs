//! Sphere textures: the equirectangular (longitude/latitude) texture coordinates of a sphere
//! map, one per face corner, split along the seam meridian and with the poles treated, so
//! that every face is a contiguous triangle of the texture.
//!
//! Conventions (what a texture user with `REPEAT` wrapping expects, as glTF and OpenGL
//! default to): `u` is continuous within each face; a face that crosses the seam meridian
//! (`u = 0 ≡ 1`) keeps its corners together, so some of its `u` lie in `(1, 1.25)` and
//! the texture repeats there; every face's smallest `u` lies in `[0, 1)`. A vertex on a
//! crossing face therefore carries two texture coordinates (`u` and `u + 1`). Near a pole
//! longitude means nothing: a corner closer to the polar axis than the face is long (a
//! pole vertex, or one next to it) takes the mean `u` of the face's other corners, so the
//! faces around a pole fan out from it like the rows of a latitude-longitude texture; a
//! face that contains a pole takes one `u` for all its corners (it pinches to a segment of
//! the top or bottom row, as the texture does at the pole).

use std::collections::HashMap;

use conformap_mesh::TriMesh;
use conformap_operators::vec3::{norm, sub};

use crate::stereo::{equirectangular_uv, from_equirectangular_uv};
use crate::SphereError;

/// A corner is treated as polar when its distance from the polar axis is at most this
/// multiple of its face's longest edge (chord): 1. Two other corners then subtend at most
/// 60° of longitude, so no face spans more than 1/6 of the texture in `u`.
pub const SPHERE_POLE_REL: f64 = 1.0;

/// How far apart (chord) the sphere points of one vertex's texture coordinates may be for
/// [`sphere_points_from_corner_uv`] to read them as one sphere map: 1e-6 (texture
/// coordinates stored as f32 round to about 1e-7).
pub const SPHERE_UV_AGREE_TOL: f64 = 1e-6;

/// Texture coordinates per face corner: corner `k` of face `f` has
/// `texcoords[faces[f][k]]` (OBJ `vt` convention: origin bottom-left, `v = 0` at the south
/// pole).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct SphereTexture {
    /// The distinct texture coordinates, numbered by first use in face order.
    pub texcoords: Vec<[f64; 2]>,
    /// For each face of the mesh, the texture coordinate of each of its corners.
    pub faces: Vec<[u32; 3]>,
}

/// The equirectangular texture of a sphere map (`points[v]` = image of vertex `v`), one
/// texture coordinate per face corner, seam and poles treated as the module docs say:
/// `u = (atan2(y, x) + π) / 2π` (plus 1 on the far side of a seam crossing), `v = (asin z
/// + π/2) / π`. Deterministic; corners of one vertex with equal values share one entry.
///
/// # Errors
/// [`SphereError::MapLength`] or [`SphereError::NonFiniteMap`].
///
/// # Examples
/// ```
/// use conformap_sphere::equirectangular_corner_uv;
/// // the octahedron on the unit sphere: four faces around each pole, and the seam
/// // (u = 0 ≡ 1, the direction −x) through vertex 1
/// let p = vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
///              [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
/// let faces = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
///                  [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
/// let mesh = conformap_mesh::TriMesh::try_new(p.clone(), faces)?;
/// let tex = equirectangular_corner_uv(&mesh, &p)?;
/// for t in &tex.faces {
///     let u = t.map(|i| tex.texcoords[i as usize][0]);
///     let span = u.iter().cloned().fold(f64::MIN, f64::max) - u.iter().cloned().fold(f64::MAX, f64::min);
///     assert!(span <= 0.25 + 1e-12); // no face spans the texture
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn equirectangular_corner_uv(
    mesh: &TriMesh,
    points: &[[f64; 3]],
) -> Result<SphereTexture, SphereError> {
    check_points(mesh, points)?;
    let mut index: HashMap<(u32, [u64; 2]), u32> = HashMap::with_capacity(points.len());
    let mut out = SphereTexture {
        texcoords: Vec::with_capacity(points.len() + points.len() / 16),
        faces: Vec::with_capacity(mesh.num_faces()),
    };
    for t in mesh.faces() {
        let uv = face_uv(t.map(|v| points[v as usize]));
        let ids = std::array::from_fn(|k| {
            let key = (t[k], uv[k].map(f64::to_bits));
            *index.entry(key).or_insert_with(|| {
                out.texcoords.push(uv[k]);
                (out.texcoords.len() - 1) as u32
            })
        });
        out.faces.push(ids);
    }
    Ok(out)
}

/// The sphere map whose texture is given per corner (`texcoords`, `tex_faces`, as
/// [`equirectangular_corner_uv`] writes them, or one per vertex): the point of each
/// vertex, or `None` if it is not a sphere texture (a planar atlas) or an index is out of
/// range. The corners of a vertex must name one latitude (within [`SPHERE_UV_AGREE_TOL`])
/// and, unless the vertex lies within [`SPHERE_POLAR_READ`] of the polar axis, one point;
/// near a pole, where the texture gives polar corners the mean `u` of their face, the
/// longitude named by most corners is taken (exact for the corners that were not polar;
/// otherwise off by less than the faces' size). For an exact map use the unit-sphere
/// points (`--flat`).
pub fn sphere_points_from_corner_uv(
    mesh: &TriMesh,
    texcoords: &[[f64; 2]],
    tex_faces: &[[u32; 3]],
) -> Option<Vec<[f64; 3]>> {
    if tex_faces.len() != mesh.num_faces() {
        return None;
    }
    let mut corners: Vec<Vec<[f64; 3]>> = vec![Vec::new(); mesh.num_vertices()];
    for (f, t) in mesh.faces().iter().zip(tex_faces) {
        for k in 0..3 {
            let uv = *texcoords.get(t[k] as usize)?;
            if !(uv[0].is_finite() && uv[1].is_finite()) {
                return None;
            }
            corners[f[k] as usize].push(from_equirectangular_uv(uv));
        }
    }
    corners.iter().map(|c| vertex_point(c)).collect()
}

/// Distance from the polar axis within which the corners of a vertex may name different
/// longitudes in [`sphere_points_from_corner_uv`]: 0.5 (30° from a pole).
pub const SPHERE_POLAR_READ: f64 = 0.5;

/// The point of a vertex from its corners' points (see [`sphere_points_from_corner_uv`]).
fn vertex_point(c: &[[f64; 3]]) -> Option<[f64; 3]> {
    let first = *c.first()?;
    if c.iter()
        .any(|q| (q[2] - first[2]).abs() > SPHERE_UV_AGREE_TOL)
    {
        return None;
    }
    let agree = |a: [f64; 3], b: [f64; 3]| norm(sub(a, b)) <= SPHERE_UV_AGREE_TOL;
    if c.iter().all(|&q| agree(q, first)) {
        return Some(first);
    }
    if first[0].hypot(first[1]) > SPHERE_POLAR_READ {
        return None;
    }
    c.iter()
        .copied()
        .max_by_key(|&q| c.iter().filter(|&&r| agree(q, r)).count())
}

fn check_points(mesh: &TriMesh, points: &[[f64; 3]]) -> Result<(), SphereError> {
    if points.len() != mesh.num_vertices() {
        return Err(SphereError::MapLength {
            expected: mesh.num_vertices(),
            found: points.len(),
        });
    }
    match points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        Some(vertex) => Err(SphereError::NonFiniteMap { vertex }),
        None => Ok(()),
    }
}

/// The texture coordinates of one face's corners (points `q`).
fn face_uv(q: [[f64; 3]; 3]) -> [[f64; 2]; 3] {
    let base = q.map(equirectangular_uv);
    let h = (0..3)
        .map(|k| norm(sub(q[k], q[(k + 1) % 3])))
        .fold(0.0, f64::max);
    let axis = q.map(|p| p[0].hypot(p[1]));
    let mut polar: [bool; 3] = std::array::from_fn(|k| axis[k] <= SPHERE_POLE_REL * h);
    if winds_around_pole(&base) {
        polar = [true; 3];
    }
    // integer offsets keep the value of a vertex bit-identical across its faces
    let mut u: [f64; 3] = base.map(|t| t[0]);
    match (0..3).find(|&k| !polar[k]) {
        Some(r) => {
            for k in (0..3).filter(|&k| !polar[k]) {
                u[k] = base[k][0] + (base[r][0] - base[k][0]).round();
            }
            let free: Vec<f64> = (0..3).filter(|&k| !polar[k]).map(|k| u[k]).collect();
            let mean = free.iter().sum::<f64>() / free.len() as f64;
            for k in (0..3).filter(|&k| polar[k]) {
                u[k] = mean;
            }
        }
        None => {
            // a face around the pole: the longitude of its centroid, for every corner
            let c = [0, 1].map(|i| q.iter().map(|p| p[i]).sum::<f64>());
            let lon = if c[0] == 0.0 && c[1] == 0.0 {
                0.5
            } else {
                equirectangular_uv([c[0], c[1], 0.0])[0]
            };
            u = [lon; 3];
        }
    }
    let shift = u.iter().cloned().fold(f64::INFINITY, f64::min).floor();
    std::array::from_fn(|k| [u[k] - shift, base[k][1]])
}

/// Whether the face's longitudes wind once around the polar axis (the face contains a
/// pole).
fn winds_around_pole(base: &[[f64; 2]; 3]) -> bool {
    let turn: f64 = (0..3)
        .map(|k| {
            let d = base[(k + 1) % 3][0] - base[k][0];
            d - d.round()
        })
        .sum();
    turn.abs() > 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_face_across_the_seam_is_contiguous() {
        // longitudes just either side of the seam (atan2 = ±π)
        let a = |lon: f64, z: f64| {
            let r = (1.0 - z * z).sqrt();
            [r * lon.cos(), r * lon.sin(), z]
        };
        let pi = std::f64::consts::PI;
        let uv = face_uv([a(pi - 0.05, 0.0), a(-pi + 0.05, 0.0), a(pi, 0.1)]);
        let u = uv.map(|t| t[0]);
        let (lo, hi) = (
            u.iter().cloned().fold(9.0, f64::min),
            u.iter().cloned().fold(-9.0, f64::max),
        );
        assert!(hi - lo < 0.02, "{u:?}");
        assert!((0.0..1.0).contains(&lo) && hi > 1.0, "{u:?}");
    }

    #[test]
    fn a_face_around_the_pole_pinches() {
        let r = 0.01f64;
        let z = (1.0 - r * r).sqrt();
        let q = [0.0, 2.1, 4.2].map(|t: f64| [r * t.cos(), r * t.sin(), z]);
        let uv = face_uv(q);
        assert!(winds_around_pole(&q.map(equirectangular_uv)));
        assert!(uv.iter().all(|t| t[0] == uv[0][0] && t[1] > 0.99), "{uv:?}");
    }
}
