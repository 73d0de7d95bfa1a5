//! [`Image`]: an RGB8 picture, written as PNG.

use std::io::Write;
use std::path::Path;

use crate::error::RenderError;

/// The PNG compression of [`Image::write_png`]: `png::Compression::Fast` (the `fdeflate`
/// encoder, adaptive row filters). Measured on 1024² pictures: 6–18 ms instead of
/// 160–310 ms for `Balanced` (zlib level 6) on the 1M-face surface and map views, for
/// files 1.1–1.6× as large (surface 698 KiB instead of 447; map 716 KiB instead of 641;
/// hand, spot: 1.15–1.5×). Encoding is serial, so at `Balanced` it cost as much as the
/// whole parallel render; a smaller file is one `oxipng` away.
pub(crate) const PNG_COMPRESSION: png::Compression = png::Compression::Fast;

/// An 8-bit sRGB picture, rows top to bottom, 3 bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    width: u32,
    height: u32,
    rgb: Vec<u8>,
}

impl Image {
    /// A `width × height` picture filled with `color`.
    pub fn filled(width: u32, height: u32, color: [u8; 3]) -> Self {
        let n = width as usize * height as usize;
        let mut rgb = Vec::with_capacity(3 * n);
        for _ in 0..n {
            rgb.extend_from_slice(&color);
        }
        Self { width, height, rgb }
    }

    /// Wraps `rgb` (`3·width·height` bytes, rows top to bottom); `None` if the length is
    /// wrong.
    pub fn from_rgb(width: u32, height: u32, rgb: Vec<u8>) -> Option<Self> {
        (rgb.len() == 3 * width as usize * height as usize).then_some(Self { width, height, rgb })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixels, 3 bytes each, rows top to bottom.
    pub fn rgb(&self) -> &[u8] {
        &self.rgb
    }

    /// Mutable pixels, 3 bytes each, rows top to bottom.
    pub fn rgb_mut(&mut self) -> &mut [u8] {
        &mut self.rgb
    }

    /// The pixel at column `x`, row `y` (`None` outside).
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        Some([self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]])
    }

    /// Sets the pixel at `(x, y)`; ignored outside the picture.
    #[inline]
    pub fn set(&mut self, x: i64, y: i64, color: [u8; 3]) {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            return;
        }
        let i = 3 * (y as usize * self.width as usize + x as usize);
        self.rgb[i..i + 3].copy_from_slice(&color);
    }

    /// Fills the rectangle `[x0, x1) × [y0, y1)` (clipped to the picture).
    pub fn fill_rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, color: [u8; 3]) {
        for y in y0.max(0)..y1.min(self.height as i64) {
            for x in x0.max(0)..x1.min(self.width as i64) {
                self.set(x, y, color);
            }
        }
    }

    /// Iterates over all pixels.
    pub fn pixels(&self) -> impl Iterator<Item = [u8; 3]> + '_ {
        self.rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]])
    }

    /// Encodes the picture as PNG into `w` (8-bit RGB, sRGB, fast compression: the
    /// `fdeflate` encoder with adaptive row filters, ten times faster than zlib level 6 for
    /// files 1.1–1.6× as large).
    ///
    /// # Errors
    /// [`RenderError::Png`] when encoding or writing fails.
    pub fn write_png<W: Write>(&self, w: W) -> Result<(), RenderError> {
        let mut encoder = png::Encoder::new(w, self.width, self.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        encoder.set_compression(PNG_COMPRESSION);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&self.rgb)?;
        writer.finish()?;
        Ok(())
    }

    /// The PNG bytes of the picture.
    ///
    /// # Errors
    /// [`RenderError::Png`] when encoding fails.
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        let mut out = Vec::new();
        self.write_png(&mut out)?;
        Ok(out)
    }

    /// Writes the picture as a PNG file.
    ///
    /// # Errors
    /// [`RenderError::Io`] when the file cannot be created, [`RenderError::Png`] when
    /// encoding fails.
    pub fn save_png(&self, path: &Path) -> Result<(), RenderError> {
        let file = std::fs::File::create(path).map_err(|source| RenderError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        self.write_png(std::io::BufWriter::new(file))
    }
}
