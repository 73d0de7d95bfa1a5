//! The exact Hessian of `E_C(θ)` (CCEM Eq. 3.17) at one point, factored once and used as
//! the initial inverse Hessian `H₀` of BFGS (Algorithm 4.2).
//!
//! Why: the Hessian in the boundary angles scales locally like the squared gaps between
//! neighbouring boundary vertices (`∂²E/∂θ_j² ≈ Σ_k w_jk (θ_k − θ_j)²`), and those gaps span
//! many orders of magnitude where a conformal map crowds the boundary (the corners of a
//! square: gaps from 1e-2 down to 1e-7 rad; thin limbs). BFGS started from `H₀ = γ I` has to
//! learn that spread step by step: 489 iterations on a 250k-face square, 150 on hand.obj.
//! Started from the exact Hessian at the starting boundary it needs 47 and 30, reaching the
//! same minimum (see the crate README). With `A` dense, the Hessian costs `n_B²` to form
//! and `n_B³ / 6` multiply–adds to factor; every direction then costs two triangular
//! solves, about one product with `A`.
//!
//! With `p + i q = f = e^{iθ}`, `E_C = ½ fᴴ A f − ½ Σ_j sin(θ_{j+1} − θ_j)`:
//! - `∂²E/∂θ_j∂θ_k = A_jk cos(θ_k − θ_j) = A_jk (p_j p_k + q_j q_k)` for `j ≠ k`,
//! - `∂²E/∂θ_j² = A_jj − Re(conj(f_j) (Af)_j) + ½ sin(θ_{j+1} − θ_j) + ½ sin(θ_j − θ_{j−1})`,
//! - and the area adds `−½ sin(θ_{j+1} − θ_j)` at `(j, j+1)` and `(j+1, j)`.
//!
//! The constant vector spans its null space (rotations), so `(μ / n_B) 11ᵀ` with `μ` the
//! mean diagonal is added (giving that direction the eigenvalue `μ`) (directions are made mean-free anyway); where the energy is not convex
//! a multiple of the identity is added until the Cholesky factorization succeeds.

use conformap_operators::DenseCholesky;

use crate::angles::gaps;
use crate::energy::Eval;

/// First diagonal shift tried when the Hessian is not positive definite, relative to its
/// largest diagonal entry; each further try multiplies the shift by
/// [`HESSIAN_SHIFT_STEP`].
pub(crate) const HESSIAN_SHIFT_START: f64 = 1e-10;
/// Factor between successive shifts.
pub(crate) const HESSIAN_SHIFT_STEP: f64 = 100.0;
/// Shifts tried before giving up (the last is `1e-10 · 100⁵ = 1` times the diagonal).
pub(crate) const HESSIAN_SHIFT_TRIES: usize = 6;

/// The factored Hessian and what it cost.
#[derive(Debug)]
pub(crate) struct Preconditioner {
    pub factor: DenseCholesky,
    /// The diagonal shift that made it positive definite (0 if none was needed).
    pub shift: f64,
    /// Milliseconds spent forming and factoring.
    pub ms: f64,
}

impl Preconditioner {
    /// The Hessian of `E_C` at `at` for the dense Schur complement `a` (column-major
    /// `n_B × n_B`), lifted and shifted as in the module docs, factored; `None` if no shift
    /// up to the diagonal's size makes it positive definite.
    pub fn at(a: &[f64], at: &Eval) -> Option<Self> {
        let t0 = std::time::Instant::now();
        let n = at.theta.len();
        if n == 0 || a.len() != n * n {
            return None;
        }
        let mut h = hessian(a, at);
        let dmax = (0..n).fold(0.0f64, |m, j| m.max(h[j * n + j].abs()));
        let mu = (0..n).map(|j| h[j * n + j]).sum::<f64>() / n as f64;
        let lift = mu.abs() / n as f64;
        h.iter_mut().for_each(|x| *x += lift);
        let mut shift = 0.0;
        for _ in 0..=HESSIAN_SHIFT_TRIES {
            let mut m = h.clone();
            for j in 0..n {
                m[j * n + j] += shift;
            }
            if let Ok(factor) = DenseCholesky::factor(m, n, 0) {
                return Some(Self {
                    factor,
                    shift,
                    ms: t0.elapsed().as_secs_f64() * 1e3,
                });
            }
            shift = if shift > 0.0 {
                shift * HESSIAN_SHIFT_STEP
            } else {
                HESSIAN_SHIFT_START * dmax.max(f64::MIN_POSITIVE)
            };
        }
        None
    }

    /// `H⁻¹ x` in place (`x` mean-free or not: the lifted null space is harmless).
    pub fn apply_inverse(&self, x: &mut [f64]) {
        self.factor.solve_in_place(x, 1);
    }
}

/// The Hessian of `E_C(θ)` at `at` (module docs), `n_B × n_B` column-major, for the dense
/// Schur complement `a`.
pub(crate) fn hessian(a: &[f64], at: &Eval) -> Vec<f64> {
    let n = at.theta.len();
    let p: Vec<f64> = at.f.iter().map(|z| z.re).collect();
    let q: Vec<f64> = at.f.iter().map(|z| z.im).collect();
    let gp = gaps(&at.theta);
    let mut h = vec![0.0; n * n];
    for k in 0..n {
        let (pk, qk) = (p[k], q[k]);
        let col = &a[k * n..(k + 1) * n];
        let out = &mut h[k * n..(k + 1) * n];
        for (((o, &ajk), &pj), &qj) in out.iter_mut().zip(col).zip(&p).zip(&q) {
            *o = ajk * (pj * pk + qj * qk);
        }
    }
    for j in 0..n {
        let jm = (j + n - 1) % n;
        h[j * n + j] =
            a[j * n + j] - (at.f[j].conj() * at.af[j]).re + 0.5 * (gp[j].sin() + gp[jm].sin());
    }
    for j in 0..n {
        let jp = (j + 1) % n;
        if jp != j {
            let s = 0.5 * gp[j].sin();
            h[jp * n + j] -= s;
            h[j * n + jp] -= s;
        }
    }
    h
}
