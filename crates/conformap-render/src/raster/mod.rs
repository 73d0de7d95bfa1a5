//! The software rasterizer, band by band: the triangles are binned into bands of sample
//! rows ([`visibility::Bins`]); every band, in parallel, is drawn into a z-buffer of face
//! ids small enough to stay in the cache and resolved at once into its rows of pixels
//! ([`resolve`]: the samples of a pixel grouped by face, each group shaded in one call).
//! The full supersampled buffer never exists.

mod resolve;
mod visibility;

use rayon::prelude::*;

use crate::image::Image;
use visibility::Bins;

/// Sample rows per band, at least (rounded up to whole pixel rows): 16. A band's depth and
/// id rows (16 × 3072 × 12 bytes, 590 KiB at 1024 pixels and 3² samples) stay in the L2
/// cache between drawing and resolving, and a 1024-pixel picture still has 170 bands to
/// share among the threads.
const BAND_SAMPLE_ROWS: usize = 16;

/// Draws the triangles `tri(t)` (`t < n_tris`, indices into `screen`) into a picture of
/// `size` × `size` pixels at `ss × ss` samples per pixel. `screen` holds the corners' sample
/// positions (`x`, `y`, `y` down) and depths (smaller nearer). Shading is in two steps:
/// `prepare(face)` does the work of a face once (kept in a [`FaceCache`] while the face's
/// pixels are resolved), and `shade(prepared, points)` gives the sum of the face's colours
/// at the sample points `points` (all in one pixel, see [`resolve::resolve_band`]);
/// uncovered samples take `background`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw<F: Copy + Default + Send>(
    size: usize,
    ss: usize,
    screen: &[[f64; 3]],
    n_tris: usize,
    tri: impl Fn(usize) -> [u32; 3] + Sync,
    background: [u8; 3],
    prepare: impl Fn(u32) -> F + Sync,
    shade: impl Fn(&F, &[[f64; 2]]) -> [f32; 3] + Sync,
) -> Image {
    let ss = ss.clamp(1, 8);
    let side = size * ss;
    let band_pixels = BAND_SAMPLE_ROWS.div_ceil(ss);
    let bins = Bins::new(side, side, band_pixels * ss, screen, n_tris, &tri);
    debug_assert_eq!(bins.bands(), size.div_ceil(band_pixels));
    let bg = background.map(|c| c as f32 / 255.0);
    let mut rgb = vec![0u8; 3 * size * size];
    rgb.par_chunks_mut(3 * size * band_pixels)
        .enumerate()
        .for_each_init(
            || (Vec::new(), Vec::new(), FaceCache::new()),
            |(depth, ids, cache), (b, out)| {
                bins.draw_band(b, screen, &tri, depth, ids);
                let (y0, _) = bins.rows(b);
                let mut shade_face =
                    |f: u32, points: &[[f64; 2]]| shade(cache.get(f, &prepare), points);
                resolve::resolve_band(ids, side, ss, y0, out, bg, &mut shade_face);
            },
        );
    Image::from_rgb(size as u32, size as u32, rgb)
        .unwrap_or_else(|| Image::filled(1, 1, background))
}

/// Entries of a [`FaceCache`]: 2048 (a power of two). A face of a mesh with about as many
/// faces as pixels is met in ~3 pixels, the last of them up to a pixel row later (~1500
/// faces at 1024 pixels); 2048 entries of at most ~200 bytes stay in the L2 cache beside a
/// band.
const FACE_CACHE: usize = 2048;

/// The prepared data of the faces met last, direct-mapped by face id (one per worker).
pub(crate) struct FaceCache<F> {
    ids: Vec<u32>,
    prepared: Vec<F>,
}

impl<F: Copy + Default> FaceCache<F> {
    fn new() -> Self {
        Self {
            ids: vec![visibility::NO_FACE; FACE_CACHE],
            prepared: vec![F::default(); FACE_CACHE],
        }
    }

    /// The prepared data of face `f`, from the cache or from `prepare`.
    #[inline]
    fn get(&mut self, f: u32, prepare: &impl Fn(u32) -> F) -> &F {
        let slot = f as usize & (FACE_CACHE - 1);
        if self.ids[slot] != f {
            self.prepared[slot] = prepare(f);
            self.ids[slot] = f;
        }
        &self.prepared[slot]
    }
}

/// The barycentric coordinates of a screen triangle as affine functions of the sample
/// position, relative to its first corner (where they are `(1, 0, 0)`).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Barycentric {
    origin: [f64; 2],
    /// `∂b0/∂x, ∂b0/∂y, ∂b1/∂x, ∂b1/∂y`.
    grad: [f64; 4],
    area2: f64,
}

impl Barycentric {
    /// The frame of the screen triangle `t` (only `x`, `y` of each corner used); `None`
    /// for a triangle of zero (or non-finite) screen area.
    #[inline]
    pub(crate) fn new(t: [[f64; 3]; 3]) -> Option<Self> {
        let area2 =
            (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]);
        if !(area2 != 0.0 && area2.is_finite()) {
            return None;
        }
        let inv = 1.0 / area2;
        // b0 ∝ (t2 − t1) × (p − t1), b1 ∝ (t0 − t2) × (p − t2)
        let e0 = [t[2][0] - t[1][0], t[2][1] - t[1][1]];
        let e1 = [t[0][0] - t[2][0], t[0][1] - t[2][1]];
        Some(Self {
            origin: [t[0][0], t[0][1]],
            grad: [-e0[1] * inv, e0[0] * inv, -e1[1] * inv, e1[0] * inv],
            area2: area2.abs(),
        })
    }

    /// Twice the triangle's area, in samples² (positive).
    #[inline]
    pub(crate) fn area2(&self) -> f64 {
        self.area2
    }

    /// Barycentric coordinates of the point `(x, y)` (they sum to 1; outside the triangle
    /// some are negative).
    #[inline]
    pub(crate) fn at(&self, x: f64, y: f64) -> [f64; 3] {
        let (dx, dy) = (x - self.origin[0], y - self.origin[1]);
        let g = &self.grad;
        let b0 = 1.0 + g[0] * dx + g[1] * dy;
        let b1 = g[2] * dx + g[3] * dy;
        [b0, b1, 1.0 - b0 - b1]
    }
}

/// The mean of the points `p` (the origin for none).
#[inline]
pub(crate) fn centroid(p: &[[f64; 2]]) -> [f64; 2] {
    if p.is_empty() {
        return [0.0; 2];
    }
    let (mut x, mut y) = (0.0, 0.0);
    for q in p {
        x += q[0];
        y += q[1];
    }
    let n = p.len() as f64;
    [x / n, y / n]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentric_coordinates_reproduce_the_corners() {
        let t = [[1.0, 2.0, 0.0], [7.0, 3.0, 0.0], [2.0, 9.0, 0.0]];
        let b = Barycentric::new(t).expect("area");
        assert_eq!(b.area2(), 41.0);
        for (k, c) in t.iter().enumerate() {
            let w = b.at(c[0], c[1]);
            for (j, x) in w.iter().enumerate() {
                let expected = if j == k { 1.0 } else { 0.0 };
                assert!((x - expected).abs() < 1e-12, "{w:?} at corner {k}");
            }
        }
        assert!(Barycentric::new([[0.0; 3], [1.0, 1.0, 0.0], [2.0, 2.0, 0.0]]).is_none());
        assert_eq!(centroid(&[[1.0, 2.0], [3.0, 6.0]]), [2.0, 4.0]);
    }

    #[test]
    fn a_square_fills_its_pixels_and_leaves_the_rest_background() {
        // the square [8, 24]² of samples at 2² samples per pixel: pixels 4..12 of 16
        let screen = [
            [8.0, 8.0, 0.0],
            [24.0, 8.0, 0.0],
            [24.0, 24.0, 0.0],
            [8.0, 24.0, 0.0],
        ];
        let tris = [[0u32, 1, 2], [0, 2, 3]];
        let image = draw(
            16,
            2,
            &screen,
            2,
            |t| tris[t],
            [255, 255, 255],
            |f| f,
            |_, p| [0.0, 0.0, p.len() as f32],
        );
        assert_eq!(image.pixel(4, 4), Some([0, 0, 255]));
        assert_eq!(image.pixel(11, 11), Some([0, 0, 255]));
        assert_eq!(image.pixel(3, 4), Some([255, 255, 255]));
        assert_eq!(image.pixel(12, 12), Some([255, 255, 255]));
        let blue = image.pixels().filter(|p| *p == [0, 0, 255]).count();
        assert_eq!(blue, 8 * 8);
    }
}
