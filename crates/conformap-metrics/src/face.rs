//! Per-face quantities: the isometric chart of a 3D triangle, image corner angles and the
//! Beltrami coefficient of the affine map on one face.

use conformap_operators::vec3;
use num_complex::Complex64;

/// `|μ|` reported for a face whose map is exactly anti-conformal (`f_z = 0`, so `|μ| = ∞`):
/// `1e12`, far above any finite value a real map produces, and finite so the report stays
/// valid JSON. Only flipped faces can reach it.
pub const BELTRAMI_ABS_CAP: f64 = 1e12;

/// An isometric, orientation-preserving chart of a 3D triangle `(p0, p1, p2)`:
/// `p0 ↦ 0`, `p1 ↦ w1 > 0` on the real axis, `p2 ↦ w2` in the upper half-plane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Chart {
    w1: f64,
    w2: Complex64,
}

impl Chart {
    /// The chart of a non-degenerate triangle (as every face of a validated mesh is).
    #[inline]
    pub(crate) fn new(p: [[f64; 3]; 3]) -> Self {
        let (e1, e2) = (vec3::sub(p[1], p[0]), vec3::sub(p[2], p[0]));
        let len1 = vec3::norm(e1);
        let dot = vec3::dot(e1, e2);
        let cross = vec3::norm(vec3::cross(e1, e2));
        Self {
            w1: len1,
            w2: Complex64::new(dot / len1, cross / len1),
        }
    }

    /// The chart image of `p1` (on the positive real axis).
    #[inline]
    pub(crate) fn w1(&self) -> f64 {
        self.w1
    }

    /// The chart image of `p2` (in the upper half-plane).
    #[inline]
    pub(crate) fn w2(&self) -> Complex64 {
        self.w2
    }

    /// `|μ|` of the affine map `w ↦ f` taking the chart triangle to the image `f`.
    ///
    /// Writing the map as `f(w) = f0 + a w + b w̄` and solving on the two edges
    /// `d_k = f_k − f0 = a w_k + b w̄_k` gives `μ = b / a = (w1 d2 − w2 d1) / (w̄2 d1 − w̄1 d2)`
    /// (the chart area cancels). 0 for a similarity, `< 1` for an orientation-preserving
    /// image, `> 1` for a flipped one, [`BELTRAMI_ABS_CAP`] when `f_z = 0`.
    #[inline]
    pub(crate) fn beltrami_abs(&self, f: [Complex64; 3]) -> f64 {
        let (d1, d2) = (f[1] - f[0], f[2] - f[0]);
        let num = d2 * self.w1 - d1 * self.w2;
        let den = d1 * self.w2.conj() - d2 * self.w1;
        let mu = num.norm() / den.norm();
        if mu <= BELTRAMI_ABS_CAP {
            mu
        } else {
            BELTRAMI_ABS_CAP
        }
    }
}

/// Unsigned corner angles (radians, in `[0, π]`) of the image triangle; entry `k` at `f_k`.
/// A flipped triangle has the same angles as its mirror image.
#[inline]
pub(crate) fn image_angles(f: [Complex64; 3]) -> [f64; 3] {
    let mut a = [0.0; 3];
    for k in 0..3 {
        let u = f[(k + 1) % 3] - f[k];
        let v = f[(k + 2) % 3] - f[k];
        let cross = u.re * v.im - u.im * v.re;
        let dot = u.re * v.re + u.im * v.im;
        a[k] = cross.abs().atan2(dot);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    const TRI: [[f64; 3]; 3] = [[0.1, 0.2, 0.3], [1.3, 0.4, -0.2], [0.5, 1.1, 0.9]];

    fn image(chart: &Chart, g: impl Fn(Complex64) -> Complex64) -> [Complex64; 3] {
        [
            g(Complex64::new(0.0, 0.0)),
            g(Complex64::new(chart.w1, 0.0)),
            g(chart.w2),
        ]
    }

    #[test]
    fn chart_is_isometric() {
        let c = Chart::new(TRI);
        let d = |a: [f64; 3], b: [f64; 3]| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        };
        assert!((c.w1 - d(TRI[0], TRI[1])).abs() < 1e-15);
        assert!((c.w2.norm() - d(TRI[0], TRI[2])).abs() < 1e-15);
        assert!(((c.w2 - c.w1).norm() - d(TRI[1], TRI[2])).abs() < 1e-15);
        assert!(c.w2.im > 0.0);
    }

    #[test]
    fn beltrami_of_affine_maps() {
        let c = Chart::new(TRI);
        let (a, b) = (Complex64::new(0.7, -1.2), Complex64::new(0.3, 0.25));
        let similarity = image(&c, |w| a * w + 5.0);
        assert!(c.beltrami_abs(similarity) < 1e-15);
        let affine = image(&c, |w| a * w + b * w.conj());
        assert!((c.beltrami_abs(affine) - b.norm() / a.norm()).abs() < 1e-14);
        let anti = image(&c, |w| a * w.conj());
        assert_eq!(c.beltrami_abs(anti), BELTRAMI_ABS_CAP);
    }

    #[test]
    fn image_angles_sum_to_pi() {
        let f = [
            Complex64::new(0.0, 0.0),
            Complex64::new(1.0, 0.0),
            Complex64::new(0.0, 1.0),
        ];
        let a = image_angles(f);
        assert!((a[0] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!((a.iter().sum::<f64>() - std::f64::consts::PI).abs() < 1e-15);
        let mirrored = f.map(|z| z.conj());
        assert_eq!(image_angles(mirrored), a);
    }
}
