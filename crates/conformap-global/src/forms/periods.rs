//! The holomorphic basis `φ_k = ω_k + i *ω_k`, its period matrix over the generators,
//! Riemann's bilinear relations as a residual, and the conformal modulus τ of a torus.

use conformap_mesh::HomologyBasis;
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
use num_complex::Complex64;

use crate::forms::cohomology::Cochain;

/// A complex 1-form: one value per edge.
pub type ComplexCochain = Vec<Complex64>;

/// The cochains `h` as the columns of an `edges × n` matrix.
pub(crate) fn cochain_matrix(h: &[Cochain]) -> Mat<f64> {
    let rows = h.first().map_or(0, Vec::len);
    Mat::from_fn(rows, h.len(), |e, k| h[k][e])
}

/// `φ_k = ω_k + i Σ_j Λ_jk ω_j` for every `k` (the `2g` holomorphic basis forms; only `g` of
/// them are complex-linearly independent): the imaginary parts are one matrix product
/// `H Λ` (`H` the harmonic forms as columns).
pub fn holomorphic_basis(h: &[Cochain], lambda: &[f64]) -> Vec<ComplexCochain> {
    let n = h.len();
    let hm = cochain_matrix(h);
    let lm = Mat::<f64>::from_fn(n, n, |j, k| lambda[j * n + k]);
    let mut im = Mat::<f64>::zeros(hm.nrows(), n);
    matmul(
        im.as_mut(),
        Accum::Replace,
        hm.as_ref(),
        lm.as_ref(),
        1.0,
        Par::rayon(0),
    );
    (0..n)
        .map(|k| {
            h[k].iter()
                .zip(im.col_as_slice(k))
                .map(|(&re, &im)| Complex64::new(re, im))
                .collect()
        })
        .collect()
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
