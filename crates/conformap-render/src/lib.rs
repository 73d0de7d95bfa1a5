//! Pictures of conformal maps without a GPU: the surface with a checkerboard through its
//! map, the flat map coloured by distortion, histograms of angle distortion; PNG and SVG
//! out.
//!
//! Depends on `conformap-mesh` (the validated [`conformap_mesh::TriMesh`]) and
//! `conformap-metrics` (the per-face angle distortion, `|μ|` and areas behind the colours),
//! `conformap-operators` (the 3D vector helpers, `vec3`), plus `png` and `rayon`. Never reads mesh files and never solves anything: it draws a map
//! given as [`MapCoords`], whoever computed it.
//!
//! # Contents
//! - [`render`] → [`Image`] (write it with [`Image::save_png`] / [`Image::write_png`]),
//!   configured by [`RenderOptions`]: [`View::Surface`] (the 3D surface, Lambert-shaded,
//!   with a checkerboard, disks or a grid computed per pixel from the interpolated map, or
//!   a per-face distortion), [`View::Map`] (the flat map, or a sphere map seen from outside,
//!   with mesh edges where resolvable, folded faces flagged and a colour bar),
//!   [`View::Histogram`].
//! - [`angle_histogram`] → [`AngleHistogram`], and [`histogram_svg`] for the SVG version.
//! - [`MapCoords`] / [`UvValues`]: planar maps per vertex or per corner (seamed maps), sphere
//!   maps as unit vectors or equirectangular texture coordinates.
//! - [`Camera`]: the orthographic camera (principal-axis default, azimuth, elevation).
//! - [`RenderError`]: the one error type.
//!
//! Internals: `raster` (bands of sample rows in parallel, each drawn into a z-buffer of
//! face ids at `supersample²` samples per pixel and resolved while in the cache: a pixel's
//! samples grouped by face, each group shaded in one call), `textures`,
//! `colormap`, `font` (a 5×7 bitmap font for the few labels), `faces` (per-face values),
//! `view` (the three pictures and the colour bar).
//!
//! # Example
//! ```
//! use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues, View};
//! use num_complex::Complex64;
//! // a bumpy square grid, mapped by its own (x, y)
//! let n = 20;
//! let mut positions = Vec::new();
//! for j in 0..=n {
//!     for i in 0..=n {
//!         let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
//!         positions.push([x, y, 0.1 * (6.0 * x).sin() * (5.0 * y).cos()]);
//!     }
//! }
//! let mut faces = Vec::new();
//! for j in 0..n as u32 {
//!     for i in 0..n as u32 {
//!         let v = j * (n as u32 + 1) + i;
//!         faces.push([v, v + 1, v + n as u32 + 2]);
//!         faces.push([v, v + n as u32 + 2, v + n as u32 + 1]);
//!     }
//! }
//! let mesh = conformap_mesh::TriMesh::try_new(positions, faces)?;
//! let uv: Vec<Complex64> = mesh.positions().iter().map(|p| Complex64::new(p[0], p[1])).collect();
//! let map = MapCoords::Planar(UvValues::PerVertex(&uv));
//! let options = RenderOptions::DEFAULT.with_size(128).with_supersample(2);
//! let surface = render(&mesh, &map, &options)?;
//! assert_eq!((surface.width(), surface.height()), (128, 128));
//! let flat = render(&mesh, &map, &options.with_view(View::Map).with_color(ColorBy::Angle))?;
//! let png = flat.to_png()?;
//! assert_eq!(&png[1..4], b"PNG");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod camera;
mod colormap;
mod error;
mod faces;
mod font;
mod image;
mod options;
mod param;
mod raster;
mod textures;
mod view;

pub use camera::{principal_axes, Camera, Viewport, FIT_MARGIN};
pub use colormap::FLAG_COLOR;
pub use error::RenderError;
pub use faces::{chart_labels, COLOR_RANGE_QUANTILE};
pub use image::Image;
pub use options::{ColorBy, RenderOptions, View};
pub use param::{MapCoords, UvValues, SPHERE_RADIUS_TOL};
pub use textures::{TONE_DARK, TONE_LIGHT};
pub use view::histogram::{angle_histogram, histogram_svg, AngleHistogram};
pub use view::map::{EDGE_FADE_FULL_PX, EDGE_FADE_START_PX, EDGE_WIDTH_PX};
pub use view::surface::{AMBIENT, BACK_SIDE, DIFFUSE, SMALL_FACE_PX};

use conformap_mesh::TriMesh;

/// Draws the map `coords` of `mesh` as `options` say: the shaded surface, the flat map or
/// the angle-distortion histogram (see [`View`]; the histogram is
/// `size × 5/8·size`, the others `size × size`).
///
/// # Errors
/// - [`RenderError::InvalidOption`]: an option out of range ([`RenderOptions::validate`]).
/// - [`RenderError::LengthMismatch`], [`RenderError::NonFiniteValue`],
///   [`RenderError::NotOnSphere`]: the map does not fit the mesh ([`MapCoords::check`]).
/// - [`RenderError::Collapsed`]: nothing with an extent to draw.
pub fn render(
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    options.validate()?;
    coords.check(mesh)?;
    match options.view {
        View::Surface => view::surface::render_surface(mesh, coords, options),
        View::Map => view::map::render_map(mesh, coords, options),
        View::Histogram => {
            let hist = angle_histogram(mesh, coords, options.histogram_bins)?;
            Ok(view::histogram::histogram_image(&hist, options))
        }
    }
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
