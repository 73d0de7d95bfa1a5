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

#[cfg(test)]
use conformap_mesh::{EdgeIndex, TriMesh};
use num_complex::Complex64;

use crate::forms::dense::symmetric_function;
use crate::forms::optimal::faces::FaceForms;
use crate::forms::periods::ComplexCochain;
#[cfg(test)]
use crate::GlobalError;

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
/// `forms` (one complex value per edge of `edges`), expanded from [`FaceForms`].
///
/// # Errors
/// [`GlobalError::DegenerateFormBasis`] if `C` is not positive definite.
#[cfg(test)]
pub fn area_products(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    forms: &[ComplexCochain],
    faces: usize,
) -> Result<AreaProducts, GlobalError> {
    Ok(AreaProducts::from_faces(&FaceForms::new(
        mesh, edges, forms, faces,
    )?))
}

impl AreaProducts {
    /// The `n × n` area forms `Q̃_f` of `faces` (`O(F n²)` memory: only the objectives
    /// that need a form per face build them — the emphasized area and the zero allocation).
    pub fn from_faces(faces: &FaceForms) -> Self {
        let n = faces.n;
        let whitened = faces.whitened();
        let mut q = vec![0.0; faces.faces() * n * n];
        for (f, dst) in q.chunks_mut(n * n).enumerate() {
            for i in 0..n {
                for j in i..n {
                    let x = whitened.area_form_entry(f, i, j);
                    dst[i * n + j] = x;
                    dst[j * n + i] = x;
                }
            }
        }
        Self {
            n,
            q,
            s: faces.s.clone(),
            w: faces.w.clone(),
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
