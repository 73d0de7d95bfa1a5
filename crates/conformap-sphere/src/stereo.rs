//! Stereographic projection between the unit sphere and the extended complex plane, and
//! the oriented volume `det3` of the inverted-face tests (the plain 3-vector arithmetic is
//! `conformap_operators::vec3`'s).
//!
//! Convention (Jin et al. 2004, §3.4): `τ(x, y, z) = (x + i y) / (1 − z)`, projecting from
//! the north pole `(0, 0, 1)`, which goes to `∞`; the south pole goes to `0` and the
//! equator to the unit circle. Its companion chart `σ = 1/τ = (x − i y) / (1 + z)` projects
//! from the south pole with the same orientation (a holomorphic change of chart), so a
//! conformal map looks conformal in both.

use conformap_operators::vec3::{cross, dot, normalize, sub};
use num_complex::Complex64;

/// A point of the extended complex plane in homogeneous coordinates `[z1 : z2]`
/// (`z = z1 / z2`, `z2 = 0` is `∞`). Möbius maps act on it by a 2 × 2 matrix, with no
/// special case at `∞`.
pub(crate) type Homogeneous = [Complex64; 2];

/// `τ(p) = (x + iy)/(1 − z)`: stereographic projection from the north pole (which maps to a
/// non-finite value; near it use [`stereographic_south`], `σ = 1/τ`). Seen from outside the
/// sphere, `τ` reverses orientation: a counter-clockwise triangle maps clockwise.
#[inline]
pub fn stereographic(p: [f64; 3]) -> Complex64 {
    Complex64::new(p[0], p[1]) / (1.0 - p[2])
}

/// `σ(p) = 1/τ(p) = (x − iy)/(1 + z)`: the chart for the northern hemisphere (projection from
/// the south pole, composed with a reflection so that it has τ's orientation).
#[inline]
pub fn stereographic_south(p: [f64; 3]) -> Complex64 {
    Complex64::new(p[0], -p[1]) / (1.0 + p[2])
}

/// `τ⁻¹(w) = (2 Re w, 2 Im w, |w|² − 1) / (|w|² + 1)`: inverse stereographic projection
/// (Jin et al. 2004, §3.4), on the unit sphere to rounding.
#[inline]
pub fn inverse_stereographic(w: Complex64) -> [f64; 3] {
    from_homogeneous([w, Complex64::new(1.0, 0.0)])
}

/// `σ⁻¹(w)`: the point whose southern-chart coordinate is `w` (`w = 0` is the north pole).
#[inline]
pub fn inverse_stereographic_south(w: Complex64) -> [f64; 3] {
    from_homogeneous([Complex64::new(1.0, 0.0), w])
}

/// Texture coordinates of a unit-sphere point by the equirectangular (longitude/latitude)
/// projection: `u = (atan2(y, x) + π) / 2π`, `v = (asin z + π/2) / π`, both in `[0, 1]`
/// (`v = 0` at the south pole). Faces that straddle the meridian `u = 0 ≡ 1` wrap around
/// the texture (per-vertex coordinates cannot express the seam).
///
/// # Examples
/// ```
/// let uv = conformap_sphere::equirectangular_uv([0.0, 1.0, 0.0]);
/// assert!((uv[0] - 0.75).abs() < 1e-15 && (uv[1] - 0.5).abs() < 1e-15);
/// ```
pub fn equirectangular_uv(p: [f64; 3]) -> [f64; 2] {
    let u = (p[1].atan2(p[0]) + std::f64::consts::PI) / std::f64::consts::TAU;
    let v = (p[2].clamp(-1.0, 1.0).asin() + std::f64::consts::FRAC_PI_2) / std::f64::consts::PI;
    [u, v]
}

/// The inverse of [`equirectangular_uv`]: the unit-sphere point of texture coordinates
/// `(u, v)`.
///
/// # Examples
/// ```
/// use conformap_sphere::{equirectangular_uv, from_equirectangular_uv};
/// let p = [0.48, -0.6, 0.64];
/// let q = from_equirectangular_uv(equirectangular_uv(p));
/// assert!((0..3).all(|k| (p[k] - q[k]).abs() < 1e-15));
/// ```
pub fn from_equirectangular_uv(uv: [f64; 2]) -> [f64; 3] {
    let lon = std::f64::consts::TAU * uv[0] - std::f64::consts::PI;
    let lat = std::f64::consts::PI * uv[1] - std::f64::consts::FRAC_PI_2;
    [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()]
}

/// Homogeneous coordinates of `τ(p)`: `[x + iy : 1 − z]` in the southern hemisphere and the
/// equal `[1 + z : x − iy]` in the northern one, so neither coordinate pair is tiny.
#[inline]
pub(crate) fn to_homogeneous(p: [f64; 3]) -> Homogeneous {
    if p[2] <= 0.0 {
        [Complex64::new(p[0], p[1]), Complex64::new(1.0 - p[2], 0.0)]
    } else {
        [Complex64::new(1.0 + p[2], 0.0), Complex64::new(p[0], -p[1])]
    }
}

/// The unit-sphere point of the homogeneous `[z1 : z2]`:
/// `(2 Re(z1 z̄2), 2 Im(z1 z̄2), |z1|² − |z2|²) / (|z1|² + |z2|²)`, renormalized to unit
/// length (exact to the last bit or two).
#[inline]
pub(crate) fn from_homogeneous(h: Homogeneous) -> [f64; 3] {
    let s = h[0] * h[1].conj();
    let (a, b) = (h[0].norm_sqr(), h[1].norm_sqr());
    normalize([2.0 * s.re, 2.0 * s.im, a - b])
}

/// `det[a, b, c] = a · (b × c)`, evaluated as `a · ((b − a) × (c − a))` (equal, and free of
/// the cancellation the plain form suffers for a tiny triangle far from the origin). Kept
/// here rather than in `conformap_operators::vec3`: it is not the plain triple product, and
/// the inverted-face tests of the sphere map depend on this rounding.
#[inline]
pub(crate) fn det3(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    dot(a, cross(sub(b, a), sub(c, a)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use conformap_operators::vec3::norm;

    #[test]
    fn projections_invert_each_other() {
        for w in [
            Complex64::new(0.0, 0.0),
            Complex64::new(0.3, -0.7),
            Complex64::new(-5.0, 2.0),
            Complex64::new(1e6, 3e5),
        ] {
            let p = inverse_stereographic(w);
            assert!((norm(p) - 1.0).abs() < 1e-15);
            if w.norm() < 1e3 {
                assert!((stereographic(p) - w).norm() <= 1e-12 * (1.0 + w.norm()));
            } else {
                // near the north pole τ cancels; the southern chart does not
                assert!((stereographic_south(p) - w.inv()).norm() <= 1e-12 * w.inv().norm());
            }
            let q = inverse_stereographic_south(w);
            if w.norm() < 1e3 {
                assert!((stereographic_south(q) - w).norm() <= 1e-12 * (1.0 + w.norm()));
            } else {
                assert!((stereographic(q) - w.inv()).norm() <= 1e-12 * w.inv().norm());
            }
            // the two charts are related by w ↦ 1/w
            if w.norm() > 0.0 {
                let pq = inverse_stereographic(w.inv());
                assert!(norm(sub(pq, q)) < 1e-12);
            }
        }
        // poles and equator
        let south = inverse_stereographic(Complex64::new(0.0, 0.0));
        assert!(norm(sub(south, [0.0, 0.0, -1.0])) < 1e-15);
        let e = inverse_stereographic(Complex64::new(0.0, 1.0));
        assert!(norm(sub(e, [0.0, 1.0, 0.0])) < 1e-15);
    }

    #[test]
    fn homogeneous_round_trip_everywhere() {
        for p in [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            normalize([0.3, -0.2, 0.9]),
            normalize([0.3, -0.2, -0.9]),
        ] {
            let q = from_homogeneous(to_homogeneous(p));
            assert!(norm(sub(p, q)) < 1e-15, "{p:?} -> {q:?}");
        }
    }

    #[test]
    fn det3_is_the_triple_product() {
        let (a, b, c) = ([0.1, 0.2, 0.9], [0.5, -0.1, 0.3], [-0.2, 0.7, 0.4]);
        let plain = dot(a, cross(b, c));
        assert!((det3(a, b, c) - plain).abs() < 1e-15);
    }
}
