//! The conjugate forms `*ω_i` of a harmonic basis: Gu and Yau's wedge-product system, or
//! its nearest exact complex structure.
//!
//! Writing `*ω_i = Σ_j Λ_ji ω_j` and pairing with `ω_k` gives `W Λ = H` with the wedge
//! matrix `W_kj = ∫ ω_k ∧ ω_j` (antisymmetric, the intersection form) and the Gram matrix
//! `H_ki = ∫ ω_k ∧ *ω_i` (symmetric positive definite): `Λ = W⁻¹ H` (Gu and Yau 2003, the
//! holomorphic basis of Jin et al. 2004 §3.1). The discrete `Λ` is only approximately a
//! complex structure: `Λ² + I = O(h²)`. The nearest exact one keeps `H` as the metric:
//! `M = H^{½} Λ H^{-½}` is antisymmetric, its polar factor `U = M (MᵀM)^{-½}` is
//! antisymmetric and orthogonal, so `Λ_J = H^{-½} U H^{½}` satisfies `Λ_J² = −I` exactly and
//! is an isometry of `H`.

use serde::{Deserialize, Serialize};

use rayon::prelude::*;

use crate::forms::cohomology::{Cochain, SparseCochain};
use crate::forms::dense::{frobenius, inverse, mat_mul, symmetric_function, transpose};

use crate::GlobalError;

/// Which conjugate the holomorphic basis uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum ConjugateMethod {
    /// `Λ = W⁻¹ H` as solved (Gu–Yau): `Λ² + I = O(h²)`, so the `2g` forms
    /// `ω_k + i *ω_k` span slightly more than a `g`-dimensional complex space and the
    /// moduli from different forms differ by `O(h²)`.
    GuYau,
    /// The nearest exact complex structure `Λ_J` (polar factor, see the module docs): the
    /// forms `ω_k + i *ω_k` span exactly a `g`-dimensional complex space, every form of a
    /// genus-1 surface gives the same τ, and Riemann's bilinear relations hold to rounding.
    /// The default (measured in the crate README: the same second-order τ error on tori
    /// of revolution as the plain solve, and one answer instead of `2g`).
    #[default]
    NearestComplexStructure,
}

impl ConjugateMethod {
    /// The name used in reports.
    pub fn name(&self) -> &'static str {
        match self {
            Self::GuYau => "gu-yau",
            Self::NearestComplexStructure => "nearest-complex-structure",
        }
    }
}

/// The conjugation matrices of a harmonic basis.
#[derive(Debug, Clone, PartialEq)]
pub struct Conjugation {
    /// `2g`.
    pub n: usize,
    /// `W_kj = ∫ ω_k ∧ ω_j`, row-major (an integer matrix up to rounding: the intersection
    /// numbers of the dual generators).
    pub wedge: Vec<f64>,
    /// `H_ki = ∫ ω_k ∧ *ω_i`, row-major.
    pub gram: Vec<f64>,
    /// The plain Gu–Yau solve `Λ = W⁻¹ H` (column `i` holds the coefficients of `*ω_i`).
    pub gu_yau: Vec<f64>,
    /// Its nearest exact complex structure `Λ_J`.
    pub exact: Vec<f64>,
    /// `‖Λ² + I‖_F / √(2g)` of the plain solve: how far it is from a complex structure.
    pub complex_structure_defect: f64,
    /// `‖Λ_J − Λ‖_F / ‖Λ‖_F`.
    pub projection_change: f64,
}

impl Conjugation {
    /// The matrix of `method`.
    pub fn matrix(&self, method: ConjugateMethod) -> &[f64] {
        match method {
            ConjugateMethod::GuYau => &self.gu_yau,
            ConjugateMethod::NearestComplexStructure => &self.exact,
        }
    }
}

/// `H_ki = ∫ ω_k ∧ *h_i = Σ_e w_e ω_k(e) h_i(e)` (row-major, symmetrized), summed over the
/// support of each cohomology basis form `closed[k]` (a few hundred edges, see
/// [`SparseCochain`]) against the harmonic forms `h`.
///
/// This is the Gram matrix `∫ h_k ∧ *h_i` of the harmonic forms: `h_k = ω_k + d f_k` and
/// `Σ_e w_e (d f_k)(e) h_i(e) = −Σ_v f_k(v) (δ h_i)(v)`, which the harmonic projection makes
/// zero (to its codifferential residual, `GlobalMap::harmonic_residual`). The two triangles
/// differ by that residual; their mean is returned.
pub fn gram_matrix(weights: &[f64], closed: &[SparseCochain], h: &[Cochain]) -> Vec<f64> {
    let n = h.len();
    let rows: Vec<Vec<f64>> = closed
        .par_iter()
        .map(|support| {
            h.iter()
                .map(|form| {
                    support
                        .iter()
                        .map(|&(e, x)| weights[e as usize] * x * form[e as usize])
                        .sum()
                })
                .collect()
        })
        .collect();
    let mut g = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            let v = 0.5 * (rows[i][j] + rows[j][i]);
            g[i * n + j] = v;
            g[j * n + i] = v;
        }
    }
    g
}

/// Solves the wedge-product system `W Λ = H` of the harmonic forms `h` — the wedge matrix
/// `w` of their cohomology classes ([`crate::forms::cohomology::wedge_matrix`]), the Gram
/// matrix from the sparse basis `closed` they project ([`gram_matrix`], cotangent `weights`
/// per edge) — and projects it onto the nearest complex structure.
///
/// # Errors
/// [`GlobalError::DegenerateFormBasis`] if `W` or `H` is numerically singular.
pub fn conjugation(
    w: Vec<f64>,
    weights: &[f64],
    closed: &[SparseCochain],
    h: &[Cochain],
) -> Result<Conjugation, GlobalError> {
    let n = h.len();
    let g = gram_matrix(weights, closed, h);
    let w_inv = inverse(&w, n).ok_or(GlobalError::DegenerateFormBasis {
        reason: "the wedge matrix of the harmonic basis is singular",
    })?;
    let lambda = mat_mul(&w_inv, &g, n);
    let mut sq = mat_mul(&lambda, &lambda, n);
    for i in 0..n {
        sq[i * n + i] += 1.0;
    }
    let complex_structure_defect = frobenius(&sq) / (n as f64).sqrt();
    let (eig, _) = crate::forms::dense::symmetric_eigen(&g, n);
    if !eig.iter().all(|&x| x > 0.0) {
        return Err(GlobalError::DegenerateFormBasis {
            reason: "the Gram matrix of the harmonic basis is not positive definite",
        });
    }
    let h_half = symmetric_function(&g, n, f64::sqrt);
    let h_mhalf = symmetric_function(&g, n, |x| 1.0 / x.sqrt());
    let m = mat_mul(&mat_mul(&h_half, &lambda, n), &h_mhalf, n);
    // antisymmetric up to rounding; take the antisymmetric part
    let mt = transpose(&m, n);
    let m: Vec<f64> = m.iter().zip(&mt).map(|(a, b)| 0.5 * (a - b)).collect();
    let mtm = mat_mul(&transpose(&m, n), &m, n);
    let u = mat_mul(&m, &symmetric_function(&mtm, n, |x| 1.0 / x.sqrt()), n);
    let exact = mat_mul(&mat_mul(&h_mhalf, &u, n), &h_half, n);
    let diff: Vec<f64> = exact.iter().zip(&lambda).map(|(a, b)| a - b).collect();
    let projection_change = frobenius(&diff) / frobenius(&lambda);
    Ok(Conjugation {
        n,
        wedge: w,
        gram: g,
        gu_yau: lambda,
        exact,
        complex_structure_defect,
        projection_change,
    })
}
