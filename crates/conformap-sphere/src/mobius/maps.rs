//! Möbius transformations of the Riemann sphere, `μ(z) = (az + b)/(cz + d)` with
//! `ad − bc = 1`, and of the unit disk, `μ(z) = (az + b)/(b̄z + ā)` with `|a|² − |b|² = 1`
//! (Jin et al. 2004, §3.4), acting on sphere points through stereographic projection.

use num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::stereo::{from_homogeneous, to_homogeneous, Homogeneous};
use crate::SphereError;
use conformap_operators::vec3::{dot, norm};

/// Relative size of `|ad − bc|` (against the largest `|entry|²`) below which a matrix is
/// rejected as singular: `1e-14`, a little above f64 round-off of the products (~1e-16
/// relative), so only numerically rank-one matrices are refused.
pub const MOBIUS_SINGULAR_REL: f64 = 1e-14;

const ZERO: Complex64 = Complex64::new(0.0, 0.0);
const ONE: Complex64 = Complex64::new(1.0, 0.0);

/// A Möbius transformation `μ(z) = (az + b)/(cz + d)`, normalized to `ad − bc = 1`, of the
/// extended plane — and, through the stereographic projection τ of [`crate::stereographic`],
/// the conformal automorphism `τ⁻¹ ∘ μ ∘ τ` of the unit sphere.
///
/// # Examples
/// ```
/// use conformap_sphere::Mobius;
/// use num_complex::Complex64;
/// let c = |re, im| Complex64::new(re, im);
/// let m = Mobius::try_new(c(1.0, 1.0), c(0.5, 0.0), c(0.2, -0.3), c(2.0, 0.0))?;
/// let z = c(0.3, -0.4);
/// // a Möbius map composed with its inverse is the identity
/// assert!((m.inverse().apply(m.apply(z)) - z).norm() < 1e-14);
/// // and it moves sphere points along the sphere
/// let p = m.apply_sphere([0.6, 0.0, 0.8]);
/// assert!(((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < 1e-15);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mobius {
    /// Coefficient `a`.
    pub a: Complex64,
    /// Coefficient `b`.
    pub b: Complex64,
    /// Coefficient `c`.
    pub c: Complex64,
    /// Coefficient `d`.
    pub d: Complex64,
}

impl Mobius {
    /// The identity `z ↦ z`.
    pub const IDENTITY: Self = Self {
        a: ONE,
        b: ZERO,
        c: ZERO,
        d: ONE,
    };

    /// `(az + b)/(cz + d)`, rescaled so that `ad − bc = 1` (the sign of the square root is
    /// immaterial: `±` give the same map).
    ///
    /// # Errors
    /// [`SphereError::SingularMobius`] if a coefficient is not finite or
    /// `|ad − bc| ≤` [`MOBIUS_SINGULAR_REL`] `· max |entry|²`.
    pub fn try_new(
        a: Complex64,
        b: Complex64,
        c: Complex64,
        d: Complex64,
    ) -> Result<Self, SphereError> {
        let det = a * d - b * c;
        let scale = [a, b, c, d]
            .iter()
            .map(|z| z.norm_sqr())
            .fold(0.0, f64::max);
        let finite = [a, b, c, d]
            .iter()
            .all(|z| z.re.is_finite() && z.im.is_finite());
        if !finite || !(det.norm() > MOBIUS_SINGULAR_REL * scale) {
            return Err(SphereError::SingularMobius { det: det.norm() });
        }
        let s = det.sqrt();
        Ok(Self {
            a: a / s,
            b: b / s,
            c: c / s,
            d: d / s,
        })
    }

    /// `μ(z)`. The pole `z = −d/c` maps to a non-finite value; use [`Self::apply_sphere`]
    /// where `∞` may occur.
    #[inline]
    pub fn apply(&self, z: Complex64) -> Complex64 {
        (self.a * z + self.b) / (self.c * z + self.d)
    }

    /// `τ⁻¹ ∘ μ ∘ τ` on a unit-sphere point (`τ` = [`crate::stereographic`]), computed in
    /// homogeneous coordinates, so the north pole (`∞`) and `μ`'s pole need no special case.
    /// The result has unit length to rounding.
    #[inline]
    pub fn apply_sphere(&self, p: [f64; 3]) -> [f64; 3] {
        from_homogeneous(self.apply_homogeneous(to_homogeneous(p)))
    }

    #[inline]
    fn apply_homogeneous(&self, h: Homogeneous) -> Homogeneous {
        [self.a * h[0] + self.b * h[1], self.c * h[0] + self.d * h[1]]
    }

    /// `self ∘ other`: first `other`, then `self`.
    pub fn compose(&self, other: &Self) -> Self {
        Self {
            a: self.a * other.a + self.b * other.c,
            b: self.a * other.b + self.b * other.d,
            c: self.c * other.a + self.d * other.c,
            d: self.c * other.b + self.d * other.d,
        }
    }

    /// The inverse `(dz − b)/(−cz + a)`.
    pub fn inverse(&self) -> Self {
        Self {
            a: self.d,
            b: -self.b,
            c: -self.c,
            d: self.a,
        }
    }

    /// The hyperbolic Möbius map ("boost") of translation length `t = |u|` along the axis
    /// through `±u/|u|`: on the sphere it fixes `n = u/|u|` and `−n`, stretches by `eᵗ` at `n`
    /// (areas near `n` grow by `e²ᵗ`) and by `e⁻ᵗ` at `−n`. Every Möbius map of the sphere is
    /// a rotation followed by a boost, and rotations change no area, so the area energies of
    /// [`crate::optimize_sphere_mobius`] are optimized over `u ∈ ℝ³` only.
    ///
    /// On points it equals [`boost_sphere_point`], the unit-ball form used by the optimizer.
    pub fn boost(u: [f64; 3]) -> Self {
        let t = norm(u);
        if !(t > 0.0) || !t.is_finite() {
            return Self::IDENTITY;
        }
        let n = [u[0] / t, u[1] / t, u[2] / t];
        // T = (z − q)/(z − p) sends the attracting point q = τ(−n) to 0 and the repelling
        // point p = τ(n) to ∞; the boost is T⁻¹ ∘ (z ↦ e⁻ᵗ z) ∘ T.
        let p = to_homogeneous(n);
        let q = to_homogeneous([-n[0], -n[1], -n[2]]);
        let tm = Self {
            a: q[1],
            b: -q[0],
            c: p[1],
            d: -p[0],
        };
        let k = (-0.5 * t).exp();
        let dil = Self {
            a: Complex64::new(k, 0.0),
            b: ZERO,
            c: ZERO,
            d: Complex64::new(1.0 / k, 0.0),
        };
        let inv = Self {
            a: -p[0],
            b: q[0],
            c: -p[1],
            d: q[1],
        };
        let m = inv.compose(&dil).compose(&tm);
        // T is well conditioned (p, q antipodal), so this cannot be singular
        Self::try_new(m.a, m.b, m.c, m.d).unwrap_or(Self::IDENTITY)
    }

    /// The coefficients as `[re, im]` pairs, for reports.
    pub fn to_report(&self) -> MobiusCoefficients {
        let c = |z: Complex64| [z.re, z.im];
        MobiusCoefficients {
            a: c(self.a),
            b: c(self.b),
            c: c(self.c),
            d: c(self.d),
        }
    }
}

/// The coefficients of a Möbius map as `[re, im]` pairs (a serde-friendly [`Mobius`]);
/// for a disk automorphism `c = b̄` and `d = ā`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct MobiusCoefficients {
    /// `a` as `[re, im]`.
    pub a: [f64; 2],
    /// `b` as `[re, im]`.
    pub b: [f64; 2],
    /// `c` as `[re, im]`.
    pub c: [f64; 2],
    /// `d` as `[re, im]`.
    pub d: [f64; 2],
}

/// The boost of [`Mobius::boost`] applied to a unit vector `x`, in the unit-ball form
/// `φ_α(x) = (1 − |α|²)(x − α)/|x − α|² − α` with `α = tanh(|u|/2) u/|u|` (the Möbius map
/// of the ball moving `α` to the centre). Smooth in `u`, including `u = 0` (identity).
#[inline]
pub fn boost_sphere_point(u: [f64; 3], x: [f64; 3]) -> [f64; 3] {
    let g = half_tanh_ratio(norm(u));
    let al = [g * u[0], g * u[1], g * u[2]];
    let r = 1.0 - dot(al, al);
    let d = [x[0] - al[0], x[1] - al[1], x[2] - al[2]];
    let q = dot(d, d);
    [
        r * d[0] / q - al[0],
        r * d[1] / q - al[1],
        r * d[2] / q - al[2],
    ]
}

/// `g(t) = tanh(t/2)/t` (and its limit ½ at 0): the ball point of a boost is `g(|u|) u`.
#[inline]
pub(crate) fn half_tanh_ratio(t: f64) -> f64 {
    if t < 1e-4 {
        // tanh(t/2)/t = ½ − t²/24 + t⁴/240 − …; the t⁴ term is < 1e-18 here
        0.5 - t * t / 24.0
    } else {
        (0.5 * t).tanh() / t
    }
}

/// `g'(t)/t` for `g` = [`half_tanh_ratio`] (limit `−1/12` at 0), so that
/// `∂(g(|u|) u)/∂u = g I + (g'/|u|) u uᵀ`.
#[inline]
pub(crate) fn half_tanh_ratio_dt_over_t(t: f64) -> f64 {
    if t < 1e-3 {
        // g' = −t/12 + t³/60 − …, so g'/t = −1/12 + t²/60; the next term is < 1e-12 · t⁰
        -1.0 / 12.0 + t * t / 60.0
    } else {
        let th = (0.5 * t).tanh();
        let dg = 0.5 * (1.0 - th * th) / t - th / (t * t);
        dg / t
    }
}

/// A conformal automorphism of the unit disk, `μ(z) = (az + b)/(b̄z + ā)` with
/// `|a|² − |b|² = 1` (Jin et al. 2004, §3.4, "topological disk"): the Möbius maps that
/// commute with the reflection in the unit circle.
///
/// # Examples
/// ```
/// use conformap_sphere::DiskAutomorphism;
/// use num_complex::Complex64;
/// let m = DiskAutomorphism::from_vector([0.8, -0.3]).compose(&DiskAutomorphism::rotation(0.4));
/// for k in 0..8 {
///     let z = Complex64::from_polar(1.0, k as f64);
///     assert!((m.apply(z).norm() - 1.0).abs() < 1e-14); // the circle is kept
/// }
/// assert!(m.apply(Complex64::new(0.2, 0.1)).norm() < 1.0); // and so is the disk
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiskAutomorphism {
    /// Coefficient `a`.
    pub a: Complex64,
    /// Coefficient `b`.
    pub b: Complex64,
}

impl DiskAutomorphism {
    /// The identity.
    pub const IDENTITY: Self = Self { a: ONE, b: ZERO };

    /// `(az + b)/(b̄z + ā)` rescaled to `|a|² − |b|² = 1`.
    ///
    /// # Errors
    /// [`SphereError::SingularMobius`] unless `|a|² − |b|² > 0` (relative to
    /// [`MOBIUS_SINGULAR_REL`]) and both are finite: with `|b| ≥ |a|` the map does not keep
    /// the disk.
    pub fn try_new(a: Complex64, b: Complex64) -> Result<Self, SphereError> {
        let det = a.norm_sqr() - b.norm_sqr();
        let scale = a.norm_sqr().max(b.norm_sqr());
        let finite = [a, b].iter().all(|z| z.re.is_finite() && z.im.is_finite());
        if !finite || !(det > MOBIUS_SINGULAR_REL * scale) {
            return Err(SphereError::SingularMobius { det });
        }
        let s = det.sqrt();
        Ok(Self { a: a / s, b: b / s })
    }

    /// The rotation `z ↦ e^{iθ} z`.
    pub fn rotation(theta: f64) -> Self {
        Self {
            a: Complex64::from_polar(1.0, 0.5 * theta),
            b: ZERO,
        }
    }

    /// The hyperbolic translation of length `t = |v|` towards the boundary point
    /// `e^{iθ} = (v₀ + i v₁)/|v|`: `z ↦ (z − β)/(1 − β̄z)` with `β = tanh(t/2) e^{iθ}`, which
    /// sends `β` to 0 and stretches by `eᵗ` at `e^{iθ}` (areas there grow by `e²ᵗ`). Every
    /// disk automorphism is such a translation followed by a rotation; rotations change no
    /// area, so [`crate::optimize_disk_mobius`] optimizes over `v ∈ ℝ²`. This is the boost
    /// of [`Mobius::boost`] with `u = (v₀, v₁, 0)`, seen on the southern hemisphere.
    pub fn from_vector(v: [f64; 2]) -> Self {
        let g = half_tanh_ratio(v[0].hypot(v[1]));
        let beta = Complex64::new(g * v[0], g * v[1]);
        let s = (1.0 - beta.norm_sqr()).sqrt();
        Self {
            a: Complex64::new(1.0 / s, 0.0),
            b: -beta / s,
        }
    }

    /// `μ(z)`.
    #[inline]
    pub fn apply(&self, z: Complex64) -> Complex64 {
        (self.a * z + self.b) / (self.b.conj() * z + self.a.conj())
    }

    /// `self ∘ other` (again a disk automorphism).
    pub fn compose(&self, other: &Self) -> Self {
        Self {
            a: self.a * other.a + self.b * other.b.conj(),
            b: self.a * other.b + self.b * other.a.conj(),
        }
    }

    /// The inverse `(āz − b)/(−b̄z + a)`.
    pub fn inverse(&self) -> Self {
        Self {
            a: self.a.conj(),
            b: -self.b,
        }
    }

    /// The same map as a general [`Mobius`] (`c = b̄`, `d = ā`).
    pub fn to_mobius(&self) -> Mobius {
        Mobius {
            a: self.a,
            b: self.b,
            c: self.b.conj(),
            d: self.a.conj(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stereo::{inverse_stereographic, stereographic};
    use conformap_operators::vec3::{dot, normalize, sub};

    fn c(re: f64, im: f64) -> Complex64 {
        Complex64::new(re, im)
    }

    fn sample_points() -> Vec<[f64; 3]> {
        let mut pts = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]];
        for k in 0..40 {
            let t = k as f64 * 0.7;
            pts.push(normalize([
                t.cos(),
                (1.3 * t).sin(),
                (0.37 * t).cos() - 0.2,
            ]));
        }
        pts
    }

    #[test]
    fn mobius_composed_with_inverse_is_identity() {
        let m = Mobius::try_new(c(1.0, 2.0), c(-0.5, 0.3), c(0.7, -0.1), c(0.2, 0.9)).unwrap();
        assert!(((m.a * m.d - m.b * m.c) - ONE).norm() < 1e-14);
        for p in sample_points() {
            let q = m.inverse().apply_sphere(m.apply_sphere(p));
            assert!(norm(sub(p, q)) < 1e-12, "{p:?} -> {q:?}");
            let r = m.compose(&m.inverse()).apply_sphere(p);
            assert!(norm(sub(p, r)) < 1e-12);
        }
        let z = c(0.3, -2.0);
        assert!((m.inverse().apply(m.apply(z)) - z).norm() < 1e-12);
        assert!((m.apply(m.inverse().apply(z)) - z).norm() < 1e-12);
    }

    #[test]
    fn apply_sphere_is_conjugated_apply() {
        let m = Mobius::try_new(c(1.0, 0.5), c(0.2, 0.0), c(-0.3, 0.4), c(1.1, -0.2)).unwrap();
        for w in [c(0.1, 0.2), c(-3.0, 1.0), c(0.0, 0.0)] {
            let p = inverse_stereographic(w);
            let q = m.apply_sphere(p);
            assert!((stereographic(q) - m.apply(w)).norm() < 1e-12 * (1.0 + m.apply(w).norm()));
        }
    }

    #[test]
    fn singular_matrices_are_refused() {
        assert!(Mobius::try_new(ONE, ONE, ONE, ONE).is_err());
        assert!(Mobius::try_new(c(f64::NAN, 0.0), ZERO, ZERO, ONE).is_err());
        assert!(DiskAutomorphism::try_new(ONE, c(0.0, 1.0)).is_err());
    }

    #[test]
    fn boost_matches_the_ball_formula_and_fixes_its_axis() {
        for u in [
            [0.3, -1.2, 0.5],
            [0.0, 0.0, 2.0],
            [0.0, 0.0, -0.7],
            [1e-9, 0.0, 0.0],
        ] {
            let m = Mobius::boost(u);
            for p in sample_points() {
                let a = m.apply_sphere(p);
                let b = boost_sphere_point(u, p);
                assert!(norm(sub(a, b)) < 1e-12, "u {u:?} p {p:?}: {a:?} vs {b:?}");
            }
            let t = norm(u);
            let n = normalize(u);
            assert!(norm(sub(m.apply_sphere(n), n)) < 1e-12);
            // stretch e^t at n: a nearby point moves away from n by that factor
            let eps = 1e-6;
            let tangent = normalize(conformap_operators::vec3::cross(n, [0.3, 0.5, 0.7]));
            let x = normalize([
                n[0] + eps * tangent[0],
                n[1] + eps * tangent[1],
                n[2] + eps * tangent[2],
            ]);
            let d0 = norm(sub(x, n));
            let d1 = norm(sub(boost_sphere_point(u, x), n));
            assert!(
                (d1 / d0 - t.exp()).abs() < 1e-4 * t.exp(),
                "{} vs {}",
                d1 / d0,
                t.exp()
            );
        }
        assert_eq!(Mobius::boost([0.0; 3]), Mobius::IDENTITY);
    }

    #[test]
    fn ball_form_keeps_the_sphere() {
        for p in sample_points() {
            let q = boost_sphere_point([2.0, -1.0, 0.4], p);
            assert!((dot(q, q).sqrt() - 1.0).abs() < 1e-14);
        }
    }

    #[test]
    fn disk_automorphisms_keep_the_circle_and_invert() {
        let m =
            DiskAutomorphism::from_vector([1.5, -0.4]).compose(&DiskAutomorphism::rotation(2.0));
        assert!((m.a.norm_sqr() - m.b.norm_sqr() - 1.0).abs() < 1e-12);
        for k in 0..50 {
            let z = Complex64::from_polar(1.0, 0.13 * k as f64);
            assert!((m.apply(z).norm() - 1.0).abs() < 1e-14);
            let w = 0.9 * z;
            assert!(m.apply(w).norm() < 1.0);
            assert!((m.inverse().apply(m.apply(w)) - w).norm() < 1e-13);
            assert!((m.to_mobius().apply(w) - m.apply(w)).norm() < 1e-13);
        }
        // from_vector(v) is the horizontal sphere boost seen through τ on the southern
        // hemisphere
        let v = [0.6, 0.9];
        let d = DiskAutomorphism::from_vector(v);
        for z in [c(0.1, 0.2), c(-0.5, 0.4), c(0.0, 0.0)] {
            let p = boost_sphere_point([v[0], v[1], 0.0], inverse_stereographic(z));
            assert!((stereographic(p) - d.apply(z)).norm() < 1e-13);
        }
    }

    #[test]
    fn tanh_ratio_series_match() {
        for t in [1e-5f64, 9e-5, 1.1e-4, 5e-4, 2e-3, 0.5, 3.0] {
            let exact = (0.5 * t).tanh() / t;
            assert!((half_tanh_ratio(t) - exact).abs() < 1e-15);
            let h = 1e-4;
            let fd =
                ((0.5 * (t + h)).tanh() / (t + h) - (0.5 * (t - h)).tanh() / (t - h)) / (2.0 * h);
            assert!(
                (half_tanh_ratio_dt_over_t(t) - fd / t).abs() < 1e-6,
                "t {t}"
            );
        }
    }
}
