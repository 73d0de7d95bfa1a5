//! Textures through the map, evaluated per sample: checkerboard, disks, grid lines.

use crate::options::ColorBy;

/// The light tone of every texture (near white).
pub const TONE_LIGHT: [f32; 3] = [0.96, 0.96, 0.94];
/// The dark tone of every texture (a deep blue, distinct from the flag and colour maps).
pub const TONE_DARK: [f32; 3] = [0.13, 0.33, 0.63];

/// Radius of the disks of [`ColorBy::Circles`], as a fraction of the cell side: 0.35 (disks
/// well apart, so their roundness shows).
const CIRCLE_RADIUS: f64 = 0.35;
/// Half width of the lines of [`ColorBy::Grid`], as a fraction of the cell side: 0.06.
const GRID_HALF_WIDTH: f64 = 0.06;

/// The texture colour at texture coordinates `(s, t)` measured in cells (one cell per unit);
/// `color` must be a texture ([`ColorBy::is_texture`]), anything else reads as the checker.
#[inline]
pub(crate) fn texture(color: ColorBy, s: f64, t: f64) -> [f32; 3] {
    let dark = match color {
        ColorBy::Circles => {
            let (fs, ft) = (s - floor_i64(s) as f64 - 0.5, t - floor_i64(t) as f64 - 0.5);
            fs * fs + ft * ft < CIRCLE_RADIUS * CIRCLE_RADIUS
        }
        ColorBy::Grid => {
            // s − round(s), ties (irrelevant here) rounded up
            let (fs, ft) = (s - floor_i64(s + 0.5) as f64, t - floor_i64(t + 0.5) as f64);
            fs.abs() < GRID_HALF_WIDTH || ft.abs() < GRID_HALF_WIDTH
        }
        // the parity of ⌊s⌋ + ⌊t⌋ (two's complement: also for negative cells)
        _ => (floor_i64(s) ^ floor_i64(t)) & 1 == 1,
    };
    if dark {
        TONE_DARK
    } else {
        TONE_LIGHT
    }
}

/// `⌊x⌋` as an integer, without the `libm` call that `f64::floor` is on the x86-64
/// baseline (no SSE4.1), which made a tenth of a textured picture's time: exact for
/// `|x| < 2⁶³`, saturating beyond, 0 for NaN.
#[inline]
pub(crate) fn floor_i64(x: f64) -> i64 {
    // branch-free: a truncated negative non-integer is one too high
    let i = x as i64;
    i - ((i as f64 > x) & (i != i64::MIN)) as i64
}

/// Texture coordinates (in cells) of a point of the unit sphere: Mercator coordinates
/// `(longitude, atanh z)`, conformal like the map, so the cells stay square (they shrink
/// towards the poles), scaled to `cells` cells around the equator (rounded to an even
/// number so the checker closes up across the date line).
#[inline]
pub(crate) fn sphere_texcoords(p: [f64; 3], cells: f64) -> (f64, f64) {
    /// Largest `|z|` used for Mercator's `atanh z` (which is infinite at the poles).
    const POLE_CLAMP: f64 = 1.0 - 1e-12;
    let even = (cells / 2.0).round().max(1.0) * 2.0;
    let k = even / std::f64::consts::TAU;
    let lon = p[1].atan2(p[0]);
    let merc = p[2].clamp(-POLE_CLAMP, POLE_CLAMP).atanh();
    (k * lon, k * merc)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates() {
        let a = texture(ColorBy::Checker, 0.5, 0.5);
        let b = texture(ColorBy::Checker, 1.5, 0.5);
        let c = texture(ColorBy::Checker, 1.5, -0.5);
        assert_ne!(a, b);
        assert_eq!(a, c);
    }

    #[test]
    fn floor_i64_is_floor() {
        for x in [
            -2.5,
            -2.0,
            -1e-300,
            -0.0,
            0.0,
            0.3,
            1.0,
            7.999,
            1e15 + 0.5,
            -1e15 - 0.5,
        ] {
            assert_eq!(floor_i64(x), x.floor() as i64, "{x}");
        }
        assert_eq!(floor_i64(f64::NAN), 0);
        assert_eq!(floor_i64(-1e300), i64::MIN);
        assert_eq!(floor_i64(1e300), i64::MAX);
    }

    #[test]
    fn circles_and_grid() {
        assert_eq!(texture(ColorBy::Circles, 3.5, 7.5), TONE_DARK);
        assert_eq!(texture(ColorBy::Circles, 3.0, 7.0), TONE_LIGHT);
        assert_eq!(texture(ColorBy::Grid, 3.01, 7.5), TONE_DARK);
        assert_eq!(texture(ColorBy::Grid, 3.5, 7.5), TONE_LIGHT);
    }

    #[test]
    fn mercator_cells_close_at_the_date_line() {
        let (s0, _) = sphere_texcoords([-1.0, 1e-9, 0.0], 20.0);
        let (s1, _) = sphere_texcoords([-1.0, -1e-9, 0.0], 20.0);
        // π and −π: 10 cells apart, an even number, so the same tone
        assert!((s0 - s1 - 20.0).abs() < 1e-6);
    }
}
