//! [`RenderOptions`]: what to draw and how, with documented defaults.

use crate::error::RenderError;

/// Which picture to make.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum View {
    /// The 3D surface, shaded, coloured through its map (default).
    #[default]
    Surface,
    /// The flat map (disk, holes, 1-form layout; a sphere map as an orthographic view of the
    /// unit sphere) with its mesh edges where they are resolvable and a colour bar.
    Map,
    /// The histogram of the corner angle distortion in degrees.
    Histogram,
}

/// What colours the faces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorBy {
    /// A checkerboard in the map's coordinates, computed per pixel (default).
    #[default]
    Checker,
    /// A grid of disks in the map's coordinates (a conformal map keeps them round).
    Circles,
    /// Grid lines in the map's coordinates.
    Grid,
    /// Per-face mean angle distortion in degrees (sequential colours from 0).
    Angle,
    /// Per-face Beltrami coefficient `|μ|` (sequential colours from 0).
    Beltrami,
    /// Per-face log area ratio (diverging colours, symmetric around 0).
    Area,
    /// One colour per chart of a seamed map (faces joined across every edge whose two
    /// ends have the same images on both sides), neighbouring charts in different colours
    /// ([`crate::chart_labels`]); no colour bar.
    Chart,
}

impl ColorBy {
    /// Whether this is a texture through the map (rather than a per-face quantity).
    pub fn is_texture(self) -> bool {
        matches!(self, Self::Checker | Self::Circles | Self::Grid)
    }
}

/// Options of [`crate::render`]. `#[non_exhaustive]`: build from [`RenderOptions::DEFAULT`]
/// with the `with_*` methods.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RenderOptions {
    /// Width and height of the picture in pixels. Default: 1024.
    pub size: u32,
    /// Supersampling factor per axis (`s²` samples per pixel, averaged): the anti-aliasing
    /// of edges and texture. Default: 3 (9 samples), enough to make checker edges smooth
    /// while a 1M-face picture stays well under a second.
    pub supersample: u32,
    /// Which picture. Default: [`View::Surface`].
    pub view: View,
    /// What colours the faces. Default: [`ColorBy::Checker`].
    pub color: ColorBy,
    /// Turn of the camera around the picture's up axis, degrees (positive turns the camera
    /// to its right around the object). Default: 0 (the surface view looks along the
    /// smallest principal axis; the sphere map view along −z).
    pub azimuth_deg: f64,
    /// Tilt of the camera over the object, degrees (positive looks down on it). Default: 0.
    pub elevation_deg: f64,
    /// Texture cells across the larger side of the map's bounding box (planar maps), or
    /// cells around the equator (sphere maps, in Mercator coordinates so the cells stay
    /// square). Default: 20.
    pub texture_cells: f64,
    /// Histogram bins between 0 and the (rounded-up) largest angle distortion. Default: 40.
    pub histogram_bins: usize,
    /// Background colour. Default: white.
    pub background: [u8; 3],
}

impl RenderOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        size: 1024,
        supersample: 3,
        view: View::Surface,
        color: ColorBy::Checker,
        azimuth_deg: 0.0,
        elevation_deg: 0.0,
        texture_cells: 20.0,
        histogram_bins: 40,
        background: [255, 255, 255],
    };

    /// Largest [`Self::size`]: 16384 pixels.
    pub const MAX_SIZE: u32 = 16384;
    /// Largest [`Self::supersample`]: 8 (64 samples per pixel).
    pub const MAX_SUPERSAMPLE: u32 = 8;

    /// Sets [`Self::size`].
    #[must_use]
    pub fn with_size(mut self, size: u32) -> Self {
        self.size = size;
        self
    }

    /// Sets [`Self::supersample`].
    #[must_use]
    pub fn with_supersample(mut self, supersample: u32) -> Self {
        self.supersample = supersample;
        self
    }

    /// Sets [`Self::view`].
    #[must_use]
    pub fn with_view(mut self, view: View) -> Self {
        self.view = view;
        self
    }

    /// Sets [`Self::color`].
    #[must_use]
    pub fn with_color(mut self, color: ColorBy) -> Self {
        self.color = color;
        self
    }

    /// Sets [`Self::azimuth_deg`].
    #[must_use]
    pub fn with_azimuth_deg(mut self, azimuth_deg: f64) -> Self {
        self.azimuth_deg = azimuth_deg;
        self
    }

    /// Sets [`Self::elevation_deg`].
    #[must_use]
    pub fn with_elevation_deg(mut self, elevation_deg: f64) -> Self {
        self.elevation_deg = elevation_deg;
        self
    }

    /// Sets [`Self::texture_cells`].
    #[must_use]
    pub fn with_texture_cells(mut self, texture_cells: f64) -> Self {
        self.texture_cells = texture_cells;
        self
    }

    /// Sets [`Self::histogram_bins`].
    #[must_use]
    pub fn with_histogram_bins(mut self, histogram_bins: usize) -> Self {
        self.histogram_bins = histogram_bins;
        self
    }

    /// Sets [`Self::background`].
    #[must_use]
    pub fn with_background(mut self, background: [u8; 3]) -> Self {
        self.background = background;
        self
    }

    /// Checks every field's range.
    ///
    /// # Errors
    /// [`RenderError::InvalidOption`] naming the field.
    pub fn validate(&self) -> Result<(), RenderError> {
        if !(16..=Self::MAX_SIZE).contains(&self.size) {
            return Err(RenderError::InvalidOption {
                name: "size",
                reason: "must be between 16 and 16384 pixels",
            });
        }
        if !(1..=Self::MAX_SUPERSAMPLE).contains(&self.supersample) {
            return Err(RenderError::InvalidOption {
                name: "supersample",
                reason: "must be between 1 and 8",
            });
        }
        if !(self.azimuth_deg.is_finite() && self.elevation_deg.is_finite()) {
            return Err(RenderError::InvalidOption {
                name: "azimuth_deg/elevation_deg",
                reason: "must be finite angles in degrees",
            });
        }
        if !(self.texture_cells > 0.0 && self.texture_cells <= 1e4) {
            return Err(RenderError::InvalidOption {
                name: "texture_cells",
                reason: "must be in (0, 10000]",
            });
        }
        if !(1..=10_000).contains(&self.histogram_bins) {
            return Err(RenderError::InvalidOption {
                name: "histogram_bins",
                reason: "must be between 1 and 10000",
            });
        }
        Ok(())
    }
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
