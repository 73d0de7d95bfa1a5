//! The holomorphic basis `φ_k = ω_k + i *ω_k`, its period matrix over the generators,
//! Riemann's bilinear relations as a residual, and the conformal modulus τ of a torus.

use conformap_mesh::HomologyBasis;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::forms::blocked::{blocks, PRODUCT_BLOCK_ROWS};

use crate::forms::cohomology::Cochain;

/// A complex 1-form: one value per edge.
pub type ComplexCochain = Vec<Complex64>;

/// `φ_k = ω_k + i Σ_j Λ_jk ω_j` for every `k` (the `2g` holomorphic basis forms; only `g` of
/// them are complex-linearly independent): the imaginary parts are the product `H Λ` (`H`
/// the harmonic forms as columns), computed block by block of edges (`blocked.rs`; each
/// block of the `n` forms read once while it is in cache) and written straight into the
/// complex forms.
pub fn holomorphic_basis(h: &[Cochain], lambda: &[f64]) -> Vec<ComplexCochain> {
    let n = h.len();
    let rows = h.first().map_or(0, Vec::len);
    let mut out: Vec<ComplexCochain> = vec![vec![Complex64::new(0.0, 0.0); rows]; n];
    // the block `b` of every output form, to fill the blocks in parallel
    let mut per_block: Vec<Vec<&mut [Complex64]>> =
        blocks(rows).iter().map(|_| Vec::new()).collect();
    for form in &mut out {
        for (b, chunk) in form.chunks_mut(PRODUCT_BLOCK_ROWS).enumerate() {
            per_block[b].push(chunk);
        }
    }
    per_block
        .into_par_iter()
        .enumerate()
        .for_each(|(b, mut columns)| {
            let start = b * PRODUCT_BLOCK_ROWS;
            let mut im = Vec::new();
            for (k, column) in columns.iter_mut().enumerate() {
                let len = column.len();
                im.clear();
                im.resize(len, 0.0);
                for (j, form) in h.iter().enumerate() {
                    let c = lambda[j * n + k];
                    for (acc, x) in im.iter_mut().zip(&form[start..start + len]) {
                        *acc += c * x;
                    }
                }
                for ((z, &re), &y) in column.iter_mut().zip(&h[k][start..start + len]).zip(&im) {
                    *z = Complex64::new(re, y);
                }
            }
        });
    out
}

/// The periods of the real forms `h` along the generator loops (row `j`: generator, column
/// `k`: form), row-major.
pub fn harmonic_periods(basis: &HomologyBasis, h: &[Cochain]) -> Vec<f64> {
    let n = h.len();
    let mut p = vec![0.0; basis.generators.len() * n];
    for (j, g) in basis.generators.iter().enumerate() {
        for (k, w) in h.iter().enumerate() {
            p[j * n + k] = g
                .halfedges
                .iter()
                .map(|&he| basis.edges.on_halfedge(w, he as usize))
                .sum();
        }
    }
    p
}

/// The periods `P_jk = ∮_{γ_j} φ_k` of the holomorphic basis `φ_k = ω_k + i Σ_l Λ_lk ω_l`
/// from the periods `ph` of the harmonic forms ([`harmonic_periods`]): `P = P_h + i P_h Λ`
/// (row-major, generator `j`, form `k`), without building the complex forms. With the
/// dual cohomology basis `P = I + iΛ` up to rounding.
pub fn period_matrix(ph: &[f64], lambda: &[f64], n: usize) -> Vec<Complex64> {
    let rows = ph.len() / n.max(1);
    let mut p = vec![Complex64::new(0.0, 0.0); rows * n];
    for j in 0..rows {
        for k in 0..n {
            let im: f64 = (0..n).map(|l| ph[j * n + l] * lambda[l * n + k]).sum();
            p[j * n + k] = Complex64::new(ph[j * n + k], im);
        }
    }
    p
}

/// Riemann's bilinear relations for the basis: `∫ φ_k ∧ φ_l = 0` for holomorphic forms,
/// evaluated through the periods and the intersection form (`∫ α ∧ β = Σ_ij a_i W_ij b_j`
/// for closed forms with periods `a`, `b` over the generators, `W` the wedge matrix of
/// their dual basis, exact for the discrete wedge). Returns
/// `max_kl |∫ φ_k ∧ φ_l| / √(‖φ_k‖² ‖φ_l‖²)` with `‖φ‖² = i/2 ∫ φ ∧ φ̄` (the area of its
/// layout).
pub fn bilinear_residual(periods: &[Complex64], wedge: &[f64], n: usize) -> f64 {
    let pair = |k: usize, l: usize, conj: bool| -> Complex64 {
        let mut s = Complex64::new(0.0, 0.0);
        for i in 0..n {
            for j in 0..n {
                let b = periods[j * n + l];
                let b = if conj { b.conj() } else { b };
                s += periods[i * n + k] * wedge[i * n + j] * b;
            }
        }
        s
    };
    let norms: Vec<f64> = (0..n)
        .map(|k| (Complex64::new(0.0, 0.5) * pair(k, k, true)).re)
        .collect();
    let mut worst = 0.0f64;
    for k in 0..n {
        for l in 0..n {
            let d = (norms[k] * norms[l]).abs().sqrt();
            if d > 0.0 {
                worst = worst.max(pair(k, l, false).norm() / d);
            }
        }
    }
    worst
}

/// Most reduction steps of [`reduce_modulus`]. Default 64: each inversion at least doubles
/// `Im τ` once `|Re τ| ≤ ½`, so any finite τ reduces in far fewer.
pub const MODULUS_MAX_STEPS: usize = 64;

/// The conformal modulus `τ = p₂ / p₁` of the lattice `ℤp₁ + ℤp₂` of a genus-1 form's two
/// periods, reduced to the fundamental domain `Im τ > 0`, `|Re τ| ≤ ½`, `|τ| ≥ 1` by
/// `τ → −τ`, `τ → τ − round(Re τ)` and `τ → −1/τ`. `None` if a period is zero or the
/// periods are parallel.
///
/// # Examples
/// ```
/// use conformap_global::reduce_modulus;
/// use num_complex::Complex64;
/// // the square lattice in disguise: periods 1 and 1 + i
/// let tau = reduce_modulus(Complex64::new(1.0, 0.0), Complex64::new(1.0, 1.0)).unwrap();
/// assert!((tau - Complex64::new(0.0, 1.0)).norm() < 1e-15);
/// ```
pub fn reduce_modulus(p1: Complex64, p2: Complex64) -> Option<Complex64> {
    if p1.norm() == 0.0 {
        return None;
    }
    let mut tau = p2 / p1;
    if !tau.is_finite() || tau.im.abs() <= 1e-14 * tau.norm() {
        return None;
    }
    if tau.im < 0.0 {
        tau = -tau;
    }
    for _ in 0..MODULUS_MAX_STEPS {
        tau.re -= tau.re.round();
        if tau.norm_sqr() < 1.0 - 1e-15 {
            tau = -tau.inv();
        } else {
            break;
        }
    }
    Some(tau)
}
