//! [`MapCoords`]: the map to draw, per vertex or per corner, planar or spherical.

use conformap_mesh::TriMesh;
use conformap_operators::vec3;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::error::RenderError;

/// How far a sphere map point may be from the unit sphere: `1e-3` relative. Sphere maps
/// are unit to rounding (`1e-15`); a looser bound accepts points read back from a file with
/// few digits, and anything beyond it is not a sphere map.
pub const SPHERE_RADIUS_TOL: f64 = 1e-3;

/// Planar values of a map: one per vertex, or one per face corner (for maps cut along
/// seams, where a vertex has several images: 1-form layouts, texture atlases).
#[derive(Debug, Clone, Copy)]
pub enum UvValues<'a> {
    /// `values[v]` is the image of vertex `v`.
    PerVertex(&'a [Complex64]),
    /// `values[f][k]` is the image of corner `k` of face `f` (the vertex `faces()[f][k]`).
    PerCorner(&'a [[Complex64; 3]]),
}

/// A map of a mesh, as [`crate::render`] draws it.
#[derive(Debug, Clone, Copy)]
pub enum MapCoords<'a> {
    /// A planar map `u + iv`: disk, disk with holes, 1-form layout, any tool's `vt`.
    Planar(UvValues<'a>),
    /// A sphere map as equirectangular texture coordinates `(u, v)` in `[0, 1]²`
    /// (`u = (atan2(y, x) + π) / 2π`, `v = (asin z + π/2) / π`, as `conformap sphere`
    /// writes them); drawn as the sphere points they stand for.
    Equirectangular(UvValues<'a>),
    /// A sphere map as one unit 3-vector per vertex.
    Sphere(&'a [[f64; 3]]),
}

/// The domain a map lands in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Domain {
    /// The plane: corners are `[u, v, 0]`.
    Plane,
    /// The unit sphere: corners are unit vectors.
    Sphere,
}

/// The point on the unit sphere with equirectangular coordinates `uv`.
#[inline]
pub(crate) fn from_equirectangular(uv: Complex64) -> [f64; 3] {
    let lon = std::f64::consts::TAU * uv.re - std::f64::consts::PI;
    let lat = std::f64::consts::PI * uv.im - std::f64::consts::FRAC_PI_2;
    [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()]
}

impl UvValues<'_> {
    /// The value at corner `k` of face `f`.
    #[inline]
    fn corner(&self, mesh: &TriMesh, f: usize, k: usize) -> Complex64 {
        match self {
            Self::PerVertex(v) => v[mesh.faces()[f][k] as usize],
            Self::PerCorner(c) => c[f][k],
        }
    }

    fn check(&self, mesh: &TriMesh) -> Result<(), RenderError> {
        match self {
            Self::PerVertex(v) => {
                if v.len() != mesh.num_vertices() {
                    return Err(RenderError::LengthMismatch {
                        what: "values",
                        per: "vertex",
                        expected: mesh.num_vertices(),
                        found: v.len(),
                    });
                }
                match v.iter().position(|z| !z.is_finite()) {
                    Some(index) => Err(RenderError::NonFiniteValue {
                        what: "vertex",
                        index,
                    }),
                    None => Ok(()),
                }
            }
            Self::PerCorner(c) => {
                if c.len() != mesh.num_faces() {
                    return Err(RenderError::LengthMismatch {
                        what: "corner triples",
                        per: "face",
                        expected: mesh.num_faces(),
                        found: c.len(),
                    });
                }
                match c.iter().position(|t| t.iter().any(|z| !z.is_finite())) {
                    Some(index) => Err(RenderError::NonFiniteValue {
                        what: "face",
                        index,
                    }),
                    None => Ok(()),
                }
            }
        }
    }
}

impl MapCoords<'_> {
    /// Checks that the map fits `mesh`: lengths, finite values, unit sphere points.
    ///
    /// # Errors
    /// [`RenderError::LengthMismatch`], [`RenderError::NonFiniteValue`],
    /// [`RenderError::NotOnSphere`].
    pub fn check(&self, mesh: &TriMesh) -> Result<(), RenderError> {
        match self {
            Self::Planar(uv) | Self::Equirectangular(uv) => uv.check(mesh),
            Self::Sphere(points) => {
                if points.len() != mesh.num_vertices() {
                    return Err(RenderError::LengthMismatch {
                        what: "points",
                        per: "vertex",
                        expected: mesh.num_vertices(),
                        found: points.len(),
                    });
                }
                for (vertex, p) in points.iter().enumerate() {
                    let length = vec3::norm(*p);
                    if !length.is_finite() {
                        return Err(RenderError::NonFiniteValue {
                            what: "vertex",
                            index: vertex,
                        });
                    }
                    if !((length - 1.0).abs() <= SPHERE_RADIUS_TOL) {
                        return Err(RenderError::NotOnSphere { vertex, length });
                    }
                }
                Ok(())
            }
        }
    }

    /// The domain of the map.
    pub(crate) fn domain(&self) -> Domain {
        match self {
            Self::Planar(_) => Domain::Plane,
            Self::Equirectangular(_) | Self::Sphere(_) => Domain::Sphere,
        }
    }

    /// The image of every vertex (`[u, v, 0]` or the unit vector), when each vertex has
    /// one; `None` for a map given per corner (a seamed map, where a vertex has several).
    pub(crate) fn vertex_points(&self) -> Option<Vec<[f64; 3]>> {
        match self {
            Self::Planar(UvValues::PerVertex(v)) => {
                Some(v.par_iter().map(|z| [z.re, z.im, 0.0]).collect())
            }
            Self::Equirectangular(UvValues::PerVertex(v)) => {
                Some(v.par_iter().map(|&z| from_equirectangular(z)).collect())
            }
            Self::Sphere(points) => Some(points.to_vec()),
            Self::Planar(UvValues::PerCorner(_))
            | Self::Equirectangular(UvValues::PerCorner(_)) => None,
        }
    }

    /// The three corner images of face `f`: `[u, v, 0]` for planar maps, unit vectors for
    /// sphere maps (one dispatch on the kind of map).
    #[inline]
    pub(crate) fn face(&self, mesh: &TriMesh, f: usize) -> [[f64; 3]; 3] {
        let planar = |z: Complex64| [z.re, z.im, 0.0];
        match self {
            Self::Planar(UvValues::PerVertex(v)) => mesh.faces()[f].map(|i| planar(v[i as usize])),
            Self::Planar(UvValues::PerCorner(c)) => c[f].map(planar),
            Self::Equirectangular(uv) => {
                [0, 1, 2].map(|k| from_equirectangular(uv.corner(mesh, f, k)))
            }
            Self::Sphere(points) => mesh.faces()[f].map(|i| points[i as usize]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equirectangular_round_trip() {
        // the inverse of conformap_sphere::equirectangular_uv
        let p = from_equirectangular(Complex64::new(0.75, 0.5));
        assert!((p[1] - 1.0).abs() < 1e-15 && p[0].abs() < 1e-15 && p[2].abs() < 1e-15);
        let north = from_equirectangular(Complex64::new(0.3, 1.0));
        assert!((north[2] - 1.0).abs() < 1e-15);
    }
}
