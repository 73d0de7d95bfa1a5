//! The resolve pass: shades every sample of the visibility buffer and averages the
//! `s × s` samples of each pixel, in parallel over pixel rows.

use rayon::prelude::*;

use super::visibility::{VisBuffer, NO_FACE};
use crate::image::Image;

/// Shades the visibility buffer `vis` (of `ss` samples per pixel and axis) into a picture:
/// `shade(face, x, y)` gives the linear-ish RGB in `[0, 1]` of a covered sample at the
/// sample-space point `(x, y)` (its centre); uncovered samples take `background`.
pub(crate) fn resolve(
    vis: &VisBuffer,
    ss: usize,
    background: [u8; 3],
    shade: impl Fn(u32, f64, f64) -> [f32; 3] + Sync,
) -> Image {
    let (w, h) = (vis.width / ss, vis.height / ss);
    let bg = background.map(|c| c as f32 / 255.0);
    let inv = 1.0 / (ss * ss) as f32;
    let mut rgb = vec![0u8; 3 * w * h];
    rgb.par_chunks_mut(3 * w).enumerate().for_each(|(py, row)| {
        for px in 0..w {
            let mut acc = [0.0f32; 3];
            for sy in 0..ss {
                let y = py * ss + sy;
                let base = y * vis.width + px * ss;
                for sx in 0..ss {
                    let f = vis.face[base + sx];
                    let c = if f == NO_FACE {
                        bg
                    } else {
                        shade(f, (px * ss + sx) as f64 + 0.5, y as f64 + 0.5)
                    };
                    acc[0] += c[0];
                    acc[1] += c[1];
                    acc[2] += c[2];
                }
            }
            for k in 0..3 {
                row[3 * px + k] = (acc[k] * inv * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
            }
        }
    });
    Image::from_rgb(w as u32, h as u32, rgb).unwrap_or_else(|| Image::filled(1, 1, background))
}
