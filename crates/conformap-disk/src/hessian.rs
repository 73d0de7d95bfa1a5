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

use conformap_operators::DenseModifiedLblt;

use crate::angles::gaps;
use crate::energy::Eval;

/// Floor on the absolute eigenvalues of the blocks of `D` in the modified factorization,
/// relative to the largest diagonal entry of the Hessian: only guards against zero (the
/// measured runs modify one eigenvalue of the Hessian of a 1M-face square, none on most
/// class-a meshes, and the floor from 1e-12 to 1e-6 changes no iteration count).
pub(crate) const HESSIAN_EIGEN_FLOOR: f64 = 1e-12;

/// Multiple of the identity added to the Hessian, relative to its largest diagonal entry: a
/// touch of Levenberg–Marquardt damping. Measured on the generated squares (250k, 500k,
/// 1M faces): 55, 75, 108 iterations undamped; 49–53, 52–68, 50–67 with 1e-8 to 3e-7; no
/// change on the class-a meshes.
pub(crate) const HESSIAN_DAMPING: f64 = 1e-7;

/// The factored Hessian and what it cost.
#[derive(Debug)]
pub(crate) struct Preconditioner {
    factor: DenseModifiedLblt,
    /// Eigenvalues of `D`'s blocks that were negative (or below the floor) and flipped.
    pub modified: usize,
    /// Milliseconds spent forming and factoring.
    pub ms: f64,
}

impl Preconditioner {
    /// The Hessian of `E_C` at `at` for the dense Schur complement `a` (column-major
    /// `n_B × n_B`), lifted as in the module docs, damped by [`HESSIAN_DAMPING`] and factored with the modified
    /// Bunch–Kaufman factorization; `None` only for input of the wrong size.
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
        for j in 0..n {
            h[j * n + j] += HESSIAN_DAMPING * dmax;
        }
        let factor = DenseModifiedLblt::factor(h, n, 0, HESSIAN_EIGEN_FLOOR * dmax).ok()?;
        Some(Self {
            modified: factor.modified,
            factor,
            ms: t0.elapsed().as_secs_f64() * 1e3,
        })
    }

    /// `M⁻¹ x` in place, `M` the modified Hessian.
    pub fn apply_inverse(&self, x: &mut [f64]) {
        self.factor.solve_in_place(x);
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
