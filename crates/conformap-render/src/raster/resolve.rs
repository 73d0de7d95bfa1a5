//! The resolve pass: the `s × s` samples of every pixel of a band, grouped by the face they
//! see, each group shaded in one call, averaged into the pixel.

use super::visibility::NO_FACE;

/// Largest number of samples per pixel: `8²` ([`crate::RenderOptions::MAX_SUPERSAMPLE`]
/// squared); the grouping marks samples in a 64-bit mask.
pub(crate) const MAX_SAMPLES: usize = 64;

/// Resolves one band: `ids` holds the nearest face of each sample of `rows` sample rows
/// (`width` samples each, the first being the picture's sample row `y0`), `ss` samples per
/// pixel and axis; `out` receives the band's pixel rows (RGB8, `width / ss` pixels each).
/// `shade(face, points)` gives the *sum* of the colours (RGB in `[0, 1]`) of the face at
/// the sample-space points `points` (sample centres; all in one pixel); uncovered samples
/// take `background`.
pub(crate) fn resolve_band(
    ids: &[u32],
    width: usize,
    ss: usize,
    y0: usize,
    out: &mut [u8],
    background: [f32; 3],
    shade: &mut impl FnMut(u32, &[[f64; 2]]) -> [f32; 3],
) {
    let n = ss * ss;
    if n == 0 || n > MAX_SAMPLES {
        return;
    }
    let w = width / ss;
    let inv = 1.0 / n as f32;
    let mut face = [NO_FACE; MAX_SAMPLES];
    let mut points = [[0.0f64; 2]; MAX_SAMPLES];
    for (py, row) in out.chunks_exact_mut(3 * w).enumerate() {
        let sy0 = py * ss;
        for (px, pixel) in row.chunks_exact_mut(3).enumerate() {
            let sx0 = px * ss;
            let mut k = 0;
            for sy in 0..ss {
                let base = (sy0 + sy) * width + sx0;
                for (f, &id) in face[k..k + ss].iter_mut().zip(&ids[base..base + ss]) {
                    *f = id;
                }
                k += ss;
            }
            let at = |j: usize| {
                [
                    (sx0 + j % ss) as f64 + 0.5,
                    (y0 + sy0 + j / ss) as f64 + 0.5,
                ]
            };
            let first = face[0];
            let acc = if face[1..n].iter().all(|&f| f == first) {
                // one face (or none) in the whole pixel: the common case
                if first == NO_FACE {
                    background.map(|c| c * n as f32)
                } else {
                    for (j, p) in points[..n].iter_mut().enumerate() {
                        *p = at(j);
                    }
                    shade(first, &points[..n])
                }
            } else {
                let mut acc = [0.0f32; 3];
                let mut done = 0u64;
                for i in 0..n {
                    if done & (1 << i) != 0 {
                        continue;
                    }
                    let f = face[i];
                    let mut m = 0;
                    for j in i..n {
                        if done & (1 << j) == 0 && face[j] == f {
                            done |= 1 << j;
                            points[m] = at(j);
                            m += 1;
                        }
                    }
                    let c = if f == NO_FACE {
                        background.map(|c| c * m as f32)
                    } else {
                        shade(f, &points[..m])
                    };
                    acc = [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]];
                }
                acc
            };
            for k in 0..3 {
                pixel[k] = (acc[k] * inv * 255.0 + 0.5).clamp(0.0, 255.0) as u8;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_are_shaded_once_with_their_samples() {
        // a 2 × 1 pixel band at 2 × 2 samples: pixel 0 all face 7, pixel 1 split between
        // face 3 (two samples), no face (one) and face 7 (one)
        let ids = [7, 7, 3, NO_FACE, 7, 7, 3, 7];
        let mut calls = Vec::new();
        let mut shade = |f: u32, p: &[[f64; 2]]| {
            calls.push((f, p.to_vec()));
            let v = if f == 7 { 1.0 } else { 0.5 };
            [v * p.len() as f32, 0.0, 0.0]
        };
        let mut out = [0u8; 6];
        resolve_band(&ids, 4, 2, 10, &mut out, [0.0, 0.0, 1.0], &mut shade);
        assert_eq!(calls.len(), 3);
        assert_eq!(
            calls[0],
            (7, vec![[0.5, 10.5], [1.5, 10.5], [0.5, 11.5], [1.5, 11.5]])
        );
        assert_eq!(calls[1], (3, vec![[2.5, 10.5], [2.5, 11.5]]));
        assert_eq!(calls[2], (7, vec![[3.5, 11.5]]));
        assert_eq!(&out[..3], &[255, 0, 0]);
        // (2 · 0.5 + 1) / 4 red, 1/4 blue
        assert_eq!(&out[3..], &[128, 0, 64]);
    }
}
