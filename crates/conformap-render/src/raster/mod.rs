//! The software rasterizer: a z-buffer of face ids at the supersampled resolution
//! ([`visibility`]), then per-sample shading averaged into pixels ([`resolve`]).

mod resolve;
mod visibility;

pub(crate) use resolve::resolve;
pub(crate) use visibility::rasterize;

/// Barycentric coordinates of the point `(x, y)` in the screen triangle `t` (only `x`, `y`
/// of each corner used); `None` for a triangle of zero screen area.
#[inline]
pub(crate) fn barycentric(t: [[f64; 3]; 3], x: f64, y: f64) -> Option<[f64; 3]> {
    let area2 =
        (t[1][0] - t[0][0]) * (t[2][1] - t[0][1]) - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]);
    if area2 == 0.0 {
        return None;
    }
    let w0 = (t[2][0] - t[1][0]) * (y - t[1][1]) - (t[2][1] - t[1][1]) * (x - t[1][0]);
    let w1 = (t[0][0] - t[2][0]) * (y - t[2][1]) - (t[0][1] - t[2][1]) * (x - t[2][0]);
    let b0 = w0 / area2;
    let b1 = w1 / area2;
    Some([b0, b1, 1.0 - b0 - b1])
}
