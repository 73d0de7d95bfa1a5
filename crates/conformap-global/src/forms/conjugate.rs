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

use crate::forms::blocked::inner_products;
use crate::forms::cohomology::Cochain;
use crate::forms::dense::{frobenius, inverse, mat_mul, symmetric_function, transpose};
use conformap_mesh::HomologyBasis;

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

/// `W_kj = ∫ ω_k ∧ ω_j` over the first `faces` faces and `H_kj = ∫ ω_k ∧ *ω_j` (row-major),
/// as matrix products over the faces and edges (the face sums of `cohomology::wedge` and
/// `cohomology::inner_product` for all pairs at once): with `A₁[f][k] = ω_k(v0 → v1)`,
/// `A₂[f][k] = ω_k(v0 → v2)`, `W = ½ (A₁ᵀA₂ − A₂ᵀA₁)`; `H = Hᵀ diag(w) H` with the forms as
/// the columns of `H`. Both are summed block by block (`blocked.rs`: the `faces × n` and
/// `edges × n` factors are never stored whole). Exactly antisymmetric and symmetric (the
/// upper triangles mirrored).
pub fn wedge_and_gram(
    basis: &HomologyBasis,
    weights: &[f64],
    h: &[Cochain],
    faces: usize,
) -> (Vec<f64>, Vec<f64>) {
    let n = h.len();
    let e = &basis.edges;
    let x = inner_products(faces, n, |start, len, mut a1, mut a2| {
        // each face's two edges and orientations, looked up once for all forms
        let at: Vec<[(usize, f64); 2]> = (start..start + len)
            .map(|f| [3 * f, 3 * f + 2].map(|he| (e.edge_of[he] as usize, e.sign(he))))
            .collect();
        for (k, form) in h.iter().enumerate() {
            for (r, &[(e1, s1), (e2, s2)]) in at.iter().enumerate() {
                a1[(r, k)] = s1 * form[e1];
                a2[(r, k)] = -(s2 * form[e2]);
            }
        }
    });
    let rows = h.first().map_or(0, Vec::len);
    let gm = inner_products(rows, n, |start, len, mut weighted, mut plain| {
        for (k, form) in h.iter().enumerate() {
            for (r, (&value, &w)) in form[start..start + len]
                .iter()
                .zip(&weights[start..start + len])
                .enumerate()
            {
                weighted[(r, k)] = w * value;
                plain[(r, k)] = value;
            }
        }
    });
    let mut w = vec![0.0; n * n];
    let mut g = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            if j > i {
                let v = 0.5 * (x[(i, j)] - x[(j, i)]);
                w[i * n + j] = v;
                w[j * n + i] = -v;
            }
            g[i * n + j] = gm[(i, j)];
            g[j * n + i] = gm[(i, j)];
        }
    }
    (w, g)
}

/// Solves the wedge-product system for the harmonic forms `h` (cotangent `weights` per
/// edge) and projects it onto the nearest complex structure.
///
/// # Errors
/// [`GlobalError::DegenerateFormBasis`] if `W` or `H` is numerically singular.
pub fn conjugation(
    basis: &HomologyBasis,
    weights: &[f64],
    h: &[Cochain],
    faces: usize,
) -> Result<Conjugation, GlobalError> {
    let n = h.len();
    let (w, g) = wedge_and_gram(basis, weights, h, faces);
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
