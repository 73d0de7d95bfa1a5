//! The conformal energy as a function of the boundary angles (CCEM Eq. 3.17), its gradient
//! (Eq. 4.1) and the coefficients of its quadratic model along a direction (Eq. 4.5).
//!
//! With `f = p + i q = e^{iθ}` on the boundary and the interior harmonic (Eq. 3.14a),
//! `E_C(θ) = ½ pᵀAp + ½ qᵀAq − ½ pᵀCq = ½ fᴴ A f − Area(θ)`, where `Area(θ) =
//! ½ Σ_j sin(θ_{j+1} − θ_j)` is the signed area of the inscribed polygon (Eq. 3.11): `C`
//! has `+1` above and `−1` below the diagonal (cyclically), so `½ pᵀCq` is the area of a
//! counter-clockwise polygon, the orientation of our boundary loops. This is CEM Eq. 7–8
//! with the same sign: `E_C = E_D − A`.

use num_complex::Complex64;

use crate::ccem::schur::Schur;

/// The energy and gradient at one point `θ`, with the products needed again later.
#[derive(Debug, Clone)]
pub(crate) struct Eval {
    /// The angles.
    pub theta: Vec<f64>,
    /// `E_C(θ)` (Eq. 3.17).
    pub energy: f64,
    /// `∇E_C(θ)` (the negative of Eq. 4.1).
    pub grad: Vec<f64>,
    /// Boundary values `e^{iθ}`.
    pub f: Vec<Complex64>,
    /// `A f`.
    pub af: Vec<Complex64>,
    /// Size of the two terms, `½ fᴴAf + |Area|`: the scale of the rounding error of
    /// `energy`, which is their difference.
    pub scale: f64,
}

/// Signed polygon area `½ Σ sin(θ_{j+1} − θ_j)` (Eq. 3.11), cyclic.
fn area(theta: &[f64]) -> f64 {
    let n = theta.len();
    (0..n)
        .map(|j| (theta[(j + 1) % n] - theta[j]).sin())
        .sum::<f64>()
        * 0.5
}

/// Evaluates `E_C`, its gradient and `A f` at `θ` (one product with `A`).
///
/// Gradient (Eq. 3.20 / 4.1, complex form): `∂E/∂θ_j = Im(conj(f_j) (Af)_j)
/// + ½ cos(θ_{j+1} − θ_j) − ½ cos(θ_j − θ_{j−1})`.
pub(crate) fn evaluate(schur: &Schur<'_, '_>, theta: Vec<f64>) -> Eval {
    let n = theta.len();
    let f: Vec<Complex64> = theta
        .iter()
        .map(|&t| Complex64::from_polar(1.0, t))
        .collect();
    let af = schur.apply(&f);
    let dirichlet = 0.5
        * f.iter()
            .zip(&af)
            .map(|(z, w)| (z.conj() * w).re)
            .sum::<f64>();
    let a = area(&theta);
    let cos_gap: Vec<f64> = (0..n)
        .map(|j| (theta[(j + 1) % n] - theta[j]).cos())
        .collect();
    let grad = (0..n)
        .map(|j| {
            let prev = cos_gap[(j + n - 1) % n];
            (f[j].conj() * af[j]).im + 0.5 * cos_gap[j] - 0.5 * prev
        })
        .collect();
    Eval {
        theta,
        energy: dirichlet - a,
        grad,
        f,
        af,
        scale: dirichlet.abs() + a.abs(),
    }
}

/// The angles `θ + α d`.
pub(crate) fn step(theta: &[f64], d: &[f64], alpha: f64) -> Vec<f64> {
    theta.iter().zip(d).map(|(t, s)| t + alpha * s).collect()
}

/// Dot product.
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The coefficients `(c₁, c₂)` of `E_C(θ + α d) = E_C(θ) + α c₁ + α² c₂ + O(α³)`
/// (Eq. 4.5), computed as `c₁ = ∇E·d` and `c₂ = ½ d²E/dα²` (one more product with `A`):
/// `d²E/dα² = (d·f)ᴴ A (d·f) − Σ d_j² Re(conj(f_j)(Af)_j) + ½ Σ (d_{j+1} − d_j)²
/// sin(θ_{j+1} − θ_j)`. The quadratic step of Eq. 4.6 is `α = −c₁ / (2 c₂)`.
pub(crate) fn quadratic_coefficients(schur: &Schur<'_, '_>, at: &Eval, d: &[f64]) -> (f64, f64) {
    let n = d.len();
    let c1 = dot(&at.grad, d);
    let df: Vec<Complex64> = at.f.iter().zip(d).map(|(z, s)| z * s).collect();
    let adf = schur.apply(&df);
    let quad = df
        .iter()
        .zip(&adf)
        .map(|(z, w)| (z.conj() * w).re)
        .sum::<f64>();
    let curv = (0..n)
        .map(|j| d[j] * d[j] * (at.f[j].conj() * at.af[j]).re)
        .sum::<f64>();
    let area2 = (0..n)
        .map(|j| {
            let k = (j + 1) % n;
            (d[k] - d[j]).powi(2) * (at.theta[k] - at.theta[j]).sin()
        })
        .sum::<f64>();
    (c1, 0.5 * (quad - curv + 0.5 * area2))
}
