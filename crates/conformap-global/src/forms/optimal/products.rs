//! The per-face `2g × 2g` quadratic forms of the layout area, in a whitened coefficient
//! basis.
//!
//! A form `φ = Σ_k λ_k φ_k` (real `λ`, holomorphic basis `φ_k`) lays face `f` out with the
//! signed area `a_f(λ) = ½ Im(conj(φ(v0→v1)) φ(v0→v2)) = λᵀ Q_f λ`. The total over the
//! user's faces, `C = Σ_f Q_f`, is positive definite (a holomorphic form vanishing on an
//! open set vanishes everywhere). The optimizers work in the coordinates `μ = C^{1/2} λ`, in
//! which the total area is `|μ|²` and the per-face forms are `Q̃_f = W Q_f W`, `W = C^{-1/2}`:
//! the unit sphere of `μ` is exactly the area constraint of Eq. 6 (up to the scale, which no
//! scale-free objective sees), and multiplying the form by `e^{iθ}` is a rotation of `μ`.

use conformap_mesh::{EdgeIndex, TriMesh};
use num_complex::Complex64;

use crate::forms::dense::{symmetric_eigen, symmetric_function};
use crate::forms::periods::ComplexCochain;
use crate::GlobalError;

/// Smallest eigenvalue of the area form `C`, relative to its largest, accepted as positive
/// definite. Default `1e-12`: a discrete holomorphic basis of a valid mesh has a condition
/// number far below `1e12`; below that the basis is degenerate.
pub const AREA_FORM_MIN_RELATIVE_EIGENVALUE: f64 = 1e-12;

/// The whitened per-face area forms of the first `faces` faces.
#[derive(Debug, Clone)]
pub struct AreaProducts {
    /// `2g`.
    pub n: usize,
    /// `Q̃_f`, row-major `n × n` per face, face after face.
    pub q: Vec<f64>,
    /// Surface area share `S_f / ΣS` of each face.
    pub s: Vec<f64>,
    /// `W = C^{-1/2}` (row-major): `λ = W μ`.
    pub w: Vec<f64>,
}

impl AreaProducts {
    /// `Q̃_f`.
    pub fn face(&self, f: usize) -> &[f64] {
        let nn = self.n * self.n;
        &self.q[f * nn..(f + 1) * nn]
    }

    /// Number of faces.
    pub fn faces(&self) -> usize {
        self.s.len()
    }

    /// Basis coefficients `λ = W μ`.
    pub fn coefficients(&self, mu: &[f64]) -> Vec<f64> {
        let n = self.n;
        (0..n)
            .map(|i| (0..n).map(|j| self.w[i * n + j] * mu[j]).sum())
            .collect()
    }

    /// Whitened coordinates `μ = C^{1/2} λ` of basis coefficients (`W⁻¹ λ`), by solving
    /// with the eigen decomposition of `W`.
    pub fn whiten(&self, lambda: &[f64]) -> Vec<f64> {
        let n = self.n;
        let inv = symmetric_function(&self.w, n, |x| 1.0 / x);
        (0..n)
            .map(|i| (0..n).map(|j| inv[i * n + j] * lambda[j]).sum())
            .collect()
    }

    /// `Σ_{f ∈ faces} Q̃_f`.
    pub fn sum_over(&self, faces: impl Iterator<Item = usize>) -> Vec<f64> {
        let mut out = vec![0.0; self.n * self.n];
        for f in faces {
            for (o, q) in out.iter_mut().zip(self.face(f)) {
                *o += q;
            }
        }
        out
    }

    /// The whitened basis `φ̃_k = Σ_j W_jk φ_j` on edge `e`.
    pub fn whitened_edge(&self, forms: &[ComplexCochain], e: usize) -> Vec<Complex64> {
        let n = self.n;
        (0..n)
            .map(|k| (0..n).map(|j| forms[j][e] * self.w[j * n + k]).sum())
            .collect()
    }
}

/// The area forms of the first `faces` faces of `mesh` under the holomorphic basis
/// `forms` (one complex value per edge of `edges`).
///
/// # Errors
/// [`GlobalError::DegenerateFormBasis`] if `C` is not positive definite.
pub fn area_products(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    forms: &[ComplexCochain],
    faces: usize,
) -> Result<AreaProducts, GlobalError> {
    let n = forms.len();
    let nn = n * n;
    let val = |k: usize, h: usize| edges.sign(h) * forms[k][edges.edge_of[h] as usize];
    let mut raw = vec![0.0; faces * nn];
    let mut c = vec![0.0; nn];
    let (mut a, mut b) = (vec![Complex64::default(); n], vec![Complex64::default(); n]);
    for f in 0..faces {
        for k in 0..n {
            a[k] = val(k, 3 * f);
            b[k] = -val(k, 3 * f + 2);
        }
        let q = &mut raw[f * nn..(f + 1) * nn];
        fill_area_form(&a, &b, q);
        for (ci, qi) in c.iter_mut().zip(q.iter()) {
            *ci += qi;
        }
    }
    let (eig, _) = symmetric_eigen(&c, n);
    let (lo, hi) = eig
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
    if !(lo > AREA_FORM_MIN_RELATIVE_EIGENVALUE * hi) {
        return Err(GlobalError::DegenerateFormBasis {
            reason: "the layout area is not a positive definite form of the coefficients",
        });
    }
    let w = symmetric_function(&c, n, |x| 1.0 / x.sqrt());
    let mut q = vec![0.0; faces * nn];
    let mut tmp = vec![0.0; nn];
    for f in 0..faces {
        let src = &raw[f * nn..(f + 1) * nn];
        // tmp = Q W, then Q̃ = W tmp
        for i in 0..n {
            for j in 0..n {
                tmp[i * n + j] = (0..n).map(|k| src[i * n + k] * w[k * n + j]).sum();
            }
        }
        let dst = &mut q[f * nn..(f + 1) * nn];
        for i in 0..n {
            for j in 0..n {
                dst[i * n + j] = (0..n).map(|k| w[i * n + k] * tmp[k * n + j]).sum();
            }
        }
    }
    let areas = conformap_operators::face_areas(mesh);
    let surface_area: f64 = areas[..faces].iter().sum();
    let s = areas[..faces].iter().map(|x| x / surface_area).collect();
    Ok(AreaProducts { n, q, s, w })
}

/// `Q` with `λᵀ Q λ = ½ Im(conj(Σ λ_k a_k) Σ λ_j b_j)`, symmetrized.
fn fill_area_form(a: &[Complex64], b: &[Complex64], q: &mut [f64]) {
    let n = a.len();
    for k in 0..n {
        for j in 0..n {
            let m_kj = (a[k].conj() * b[j]).im;
            let m_jk = (a[j].conj() * b[k]).im;
            q[k * n + j] = 0.25 * (m_kj + m_jk);
        }
    }
}

/// `μᵀ M μ` for a row-major `n × n` matrix.
pub fn quadratic(m: &[f64], mu: &[f64]) -> f64 {
    let n = mu.len();
    (0..n)
        .map(|i| mu[i] * (0..n).map(|j| m[i * n + j] * mu[j]).sum::<f64>())
        .sum()
}
