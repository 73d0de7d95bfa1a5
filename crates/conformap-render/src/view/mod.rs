//! The pictures: the shaded surface ([`surface`]), the flat map ([`map`]), the histogram
//! ([`histogram`]), and the colour bar they share ([`colorbar`]).

pub(crate) mod colorbar;
pub(crate) mod histogram;
pub(crate) mod map;
pub(crate) mod surface;

use conformap_mesh::TriMesh;
use conformap_operators::vec3;
use rayon::prelude::*;

use crate::param::{Domain, MapCoords};
use crate::textures::sphere_texcoords;

/// How map coordinates become texture coordinates (in cells).
#[derive(Debug, Clone, Copy)]
pub(crate) enum TexMap {
    /// Planar: `(p − center) · scale`.
    Plane {
        /// Centre of the map's bounding box (a cell corner).
        center: [f64; 2],
        /// Cells per map unit.
        scale: f64,
    },
    /// Sphere: Mercator coordinates, `cells` around the equator.
    Sphere {
        /// Cells around the equator.
        cells: f64,
    },
}

impl TexMap {
    /// The texture mapping of `coords` with `cells` cells across the larger side of a
    /// planar map's bounding box (around the equator of a sphere map).
    pub(crate) fn new(mesh: &TriMesh, coords: &MapCoords<'_>, cells: f64) -> Self {
        match coords.domain() {
            Domain::Sphere => Self::Sphere { cells },
            Domain::Plane => {
                let (x0, x1, y0, y1) = (0..mesh.num_faces())
                    .into_par_iter()
                    .map(|f| {
                        let q = coords.face(mesh, f);
                        let xs = [q[0][0], q[1][0], q[2][0]];
                        let ys = [q[0][1], q[1][1], q[2][1]];
                        (
                            xs.iter().copied().fold(f64::INFINITY, f64::min),
                            xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                            ys.iter().copied().fold(f64::INFINITY, f64::min),
                            ys.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                        )
                    })
                    .reduce(
                        || {
                            (
                                f64::INFINITY,
                                f64::NEG_INFINITY,
                                f64::INFINITY,
                                f64::NEG_INFINITY,
                            )
                        },
                        |a, b| (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3)),
                    );
                let extent = (x1 - x0).max(y1 - y0);
                let scale = if extent > 0.0 { cells / extent } else { 1.0 };
                Self::Plane {
                    center: [0.5 * (x0 + x1), 0.5 * (y0 + y1)],
                    scale,
                }
            }
        }
    }

    /// Texture coordinates of the map point `p` (planar `[u, v, 0]` or a sphere point,
    /// which need not be normalized).
    #[inline]
    pub(crate) fn at(&self, p: [f64; 3]) -> (f64, f64) {
        match *self {
            Self::Plane { center, scale } => {
                ((p[0] - center[0]) * scale, (p[1] - center[1]) * scale)
            }
            Self::Sphere { cells } => sphere_texcoords(vec3::normalize(p), cells),
        }
    }
}

impl TexMap {
    /// The texture coordinates over the face with the map corners `corners`, as a function
    /// of the barycentric coordinates: for planar maps (an affine texture mapping) the
    /// corners' texture coordinates are computed once and interpolated; sphere maps
    /// interpolate the sphere point and project it at every sample.
    #[inline]
    pub(crate) fn face(&self, corners: [[f64; 3]; 3]) -> FaceTex {
        match self {
            Self::Plane { .. } => FaceTex::Affine(corners.map(|c| self.at(c))),
            Self::Sphere { .. } => FaceTex::Projected(*self, corners),
        }
    }
}

/// [`TexMap::face`]: the texture coordinates over one face.
#[derive(Debug, Clone, Copy)]
pub(crate) enum FaceTex {
    /// Affine in the barycentric coordinates: the corners' texture coordinates.
    Affine([(f64, f64); 3]),
    /// Through the map point: the mapping and the corners' map points.
    Projected(TexMap, [[f64; 3]; 3]),
}

impl Default for FaceTex {
    fn default() -> Self {
        Self::Affine([(0.0, 0.0); 3])
    }
}

impl FaceTex {
    /// The texture coordinates at the barycentric coordinates `b`.
    #[inline]
    pub(crate) fn at(&self, b: [f64; 3]) -> (f64, f64) {
        match self {
            Self::Affine(st) => (
                b[0] * st[0].0 + b[1] * st[1].0 + b[2] * st[2].0,
                b[0] * st[0].1 + b[1] * st[1].1 + b[2] * st[2].1,
            ),
            Self::Projected(tex, corners) => tex.at(interpolate(b, *corners)),
        }
    }
}

/// The pixel geometry both views share: supersampling, the supersampled side, whether a
/// quantity (with its colour bar) is drawn rather than a texture, and the bar's width.
pub(crate) struct Canvas {
    /// Supersampling factor.
    pub ss: usize,
    /// Side of the supersampled image, pixels.
    pub side: usize,
    /// Whether the colour is a quantity (a colour bar is drawn).
    pub quantity: bool,
    /// Width of the colour bar, supersampled pixels (0 without one).
    pub bar: f64,
}

impl Canvas {
    pub(crate) fn new(options: &crate::RenderOptions) -> Self {
        let ss = options.supersample as usize;
        let quantity = !options.color.is_texture();
        Self {
            ss,
            side: options.size as usize * ss,
            quantity,
            bar: if quantity {
                colorbar::width(options.size) as f64 * ss as f64
            } else {
                0.0
            },
        }
    }
}

/// `Σ b_k x_k` for three points.
#[inline]
pub(crate) fn interpolate(b: [f64; 3], x: [[f64; 3]; 3]) -> [f64; 3] {
    [
        b[0] * x[0][0] + b[1] * x[1][0] + b[2] * x[2][0],
        b[0] * x[0][1] + b[1] * x[1][1] + b[2] * x[2][1],
        b[0] * x[0][2] + b[1] * x[1][2] + b[2] * x[2][2],
    ]
}

/// Barycentric coordinates clamped into the triangle (a sample on an edge can fall a
/// rounding error outside), renormalized.
#[inline]
pub(crate) fn clamp_barycentric(b: [f64; 3]) -> [f64; 3] {
    if b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0 {
        return b;
    }
    let c = b.map(|x| x.max(0.0));
    let s = c[0] + c[1] + c[2];
    if s > 0.0 {
        c.map(|x| x / s)
    } else {
        [1.0 / 3.0; 3]
    }
}
