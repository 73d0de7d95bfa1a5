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
//! mean diagonal is added (giving that direction the eigenvalue `μ`; directions are made
//! mean-free anyway), plus a damping of 1e-7 of the largest diagonal entry. Factored by the
//! dense Cholesky when that is positive definite (the usual case from the aligned
//! harmonic-measure start), else by the modified Bunch–Kaufman `LBLᵀ`, which flips
//! negative curvatures. From [`crate::CcemOptions::banded_hessian_min_nb`] boundary
//! vertices on, only the Hessian's cyclic band is factored ([`Preconditioner::banded`]).

use conformap_operators::{Cholesky, CholeskyOptions, DenseCholesky, DenseModifiedLblt, Ordering};
use sprs::CsMat;

use crate::angles::gaps;
use crate::ccem::energy::Eval;

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

/// Half-width of the banded Hessian (entries `(j, k)` with cyclic `|j − k| ≤ b` kept).
/// Measured from the harmonic-measure start on the 250k-face square: half-widths 2, 8,
/// 32, 128 need 31, 17, 8, 4 iterations (the whole Hessian: 3); the band's factorization
/// costs `n_B b²` ≈ 50 Mflop at `n_B = 2,828`.
pub(crate) const HESSIAN_BAND: usize = 128;

/// The factored Hessian and what it cost.
#[derive(Debug)]
pub(crate) struct Preconditioner {
    factor: Factor,
    /// Eigenvalues of `D`'s blocks that were negative (or below the floor) and flipped
    /// (dense), or diagonal shifts the banded Cholesky needed (banded).
    pub modified: usize,
    /// Half-width of the band, when banded.
    pub band: Option<usize>,
}

impl Preconditioner {
    /// The Hessian of `E_C` at `at` for the dense Schur complement `a` (column-major
    /// `n_B × n_B`), lifted as in the module docs, damped by [`HESSIAN_DAMPING`] and factored with the modified
    /// Bunch–Kaufman factorization; `None` only for input of the wrong size.
    pub fn at(a: &[f64], at: &Eval) -> Option<Self> {
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
        // positive definite (the usual case from the aligned harmonic-measure start): the
        // plain Cholesky, about twice as fast as the modified Bunch–Kaufman (896: 2.9
        // against 6.3 ms; 1,416: 20 against 30; 1,990: 35 against 64), which stays the
        // fallback for an indefinite Hessian
        if let Ok(c) = DenseCholesky::factor(h.clone(), n, 0) {
            return Some(Self {
                modified: 0,
                band: None,
                factor: Factor::Cholesky(c),
            });
        }
        let factor = DenseModifiedLblt::factor(h, n, 0, HESSIAN_EIGEN_FLOOR * dmax).ok()?;
        Some(Self {
            modified: factor.modified,
            band: None,
            factor: Factor::Dense(factor),
        })
    }

    /// The cyclic band (half-width `b`) of the Hessian at `at`, damped as the dense one,
    /// factored by the sparse Cholesky (directions are made mean-free anyway, so the
    /// rotation's null direction needs no lift); where the band is not positive definite, `10⁻⁶, 10⁻⁴, …` of the largest
    /// diagonal entry is added until it is (each try counted in `modified`). `None` when no
    /// shift up to the largest diagonal entry works (then the caller uses the dense one).
    pub fn banded(a: &[f64], at: &Eval, b: usize) -> Option<Self> {
        let n = at.theta.len();
        if n < 3 || a.len() != n * n {
            return None;
        }
        let b = b.min((n - 1) / 2);
        let h = hessian_band(a, at, b);
        let dmax = (0..n).fold(0.0f64, |m, j| m.max(h[j][b].abs()));
        // no lift of the rotation's null direction on the diagonal: a shift of the whole
        // spectrum damps the two soft Möbius directions too, and the descent then stops
        // at the rounding level 2e-8 above the minimum (a bumpy 80 × 80 square); the band
        // drops the far couplings but keeps the full row sums on its diagonal, so it is
        // nonsingular as it is
        let base = HESSIAN_DAMPING * dmax;
        for (modified, shift) in [0.0, 1e-6, 1e-4, 1e-2, 1.0].into_iter().enumerate() {
            let m = band_matrix(&h, b, base + shift * dmax);
            // natural order: a cyclic band fills only the last `2b` rows (no ordering to
            // compute)
            let natural = CholeskyOptions::DEFAULT.with_ordering(Ordering::Identity);
            if let Ok(c) = Cholesky::factor_with(&m, &natural) {
                return Some(Self {
                    modified,
                    band: Some(b),
                    factor: Factor::Banded(Box::new(c)),
                });
            }
        }
        None
    }

    /// `M⁻¹ x` in place, `M` the modified Hessian.
    pub fn apply_inverse(&self, x: &mut [f64]) {
        match &self.factor {
            Factor::Dense(f) => f.solve_in_place(x),
            Factor::Cholesky(c) => c.solve_in_place(x, 1),
            Factor::Banded(c) => c.solve_in_place(x, 1),
        }
    }
}

/// The factorization behind a [`Preconditioner`].
#[derive(Debug)]
enum Factor {
    Dense(DenseModifiedLblt),
    Cholesky(DenseCholesky),
    Banded(Box<Cholesky>),
}

/// Row `j` of the cyclic band of the Hessian: `h[j][b + d]` is `H_{j, j+d}`, `|d| ≤ b`
/// (indices mod `n`), with the formulas of the module docs.
pub(crate) fn hessian_band(a: &[f64], at: &Eval, b: usize) -> Vec<Vec<f64>> {
    let n = at.theta.len();
    let gp = gaps(&at.theta);
    let f = &at.f;
    (0..n)
        .map(|j| {
            let mut row = vec![0.0; 2 * b + 1];
            for (slot, d) in (0..=2 * b).zip(-(b as isize)..=b as isize) {
                if d == 0 {
                    continue;
                }
                let k = (j as isize + d).rem_euclid(n as isize) as usize;
                // A is symmetric: read column j (contiguous) rather than row j
                row[slot] = a[j * n + k] * (f[j].re * f[k].re + f[j].im * f[k].im);
            }
            let jm = (j + n - 1) % n;
            row[b] =
                a[j * n + j] - (f[j].conj() * at.af[j]).re + 0.5 * (gp[j].sin() + gp[jm].sin());
            // the area's coupling of neighbours
            row[b + 1] -= 0.5 * gp[j].sin();
            row[b - 1] -= 0.5 * gp[jm].sin();
            row
        })
        .collect()
}

/// The band as a symmetric CSC matrix (full storage, sorted rows), `shift` added to the
/// diagonal.
fn band_matrix(h: &[Vec<f64>], b: usize, shift: f64) -> CsMat<f64> {
    let n = h.len();
    let mut indptr = Vec::with_capacity(n + 1);
    let mut indices = Vec::with_capacity(n * (2 * b + 1));
    let mut data = Vec::with_capacity(n * (2 * b + 1));
    indptr.push(0);
    let mut col: Vec<(usize, f64)> = Vec::with_capacity(2 * b + 1);
    for (j, row) in h.iter().enumerate() {
        col.clear();
        for (slot, d) in (0..=2 * b).zip(-(b as isize)..=b as isize) {
            let k = (j as isize + d).rem_euclid(n as isize) as usize;
            // symmetrize: the band of A is symmetric, the area term too
            let v = if d == 0 { row[slot] + shift } else { row[slot] };
            col.push((k, v));
        }
        col.sort_unstable_by_key(|e| e.0);
        for &(k, v) in &col {
            indices.push(k);
            data.push(v);
        }
        indptr.push(indices.len());
    }
    CsMat::new_csc((n, n), indptr, indices, data)
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
