//! Harmonic projection of the cohomology basis: `h_i = ω_i + d f_i` with `δ h_i = 0`, i.e.
//! `L f_i = div ω_i` for the cotangent Laplacian `L`, one vertex pinned. One symbolic
//! analysis and one numeric factorization serve all `2g` right-hand sides (one blocked
//! solve).

use std::time::Instant;

use conformap_mesh::{HomologyBasis, TriMesh};
use conformap_operators::{
    cotan_laplacian, Cholesky, CholeskyOptions, FactorStats, LaplacianBlocks, Partition,
};

use crate::forms::cohomology::Cochain;
use crate::GlobalError;

/// What the harmonic projection did and cost.
#[derive(Debug, Clone)]
pub struct HarmonicSolve {
    /// The harmonic forms, one per cohomology form, same order.
    pub forms: Vec<Cochain>,
    /// Largest `‖δ h_i‖∞ / ‖div ω_i‖∞` after the projection (rounding level when the
    /// solve is accurate).
    pub codifferential_residual: f64,
    /// The factorization's sizes and timings.
    pub factor: FactorStats,
    /// Milliseconds assembling `L` and its reduced block.
    pub assemble_ms: f64,
    /// Milliseconds for the blocked solve and the update of the forms.
    pub solve_ms: f64,
}

/// `(div ω)_v = Σ_{edges v → u} w_vu ω(v → u)`.
fn divergence(mesh: &TriMesh, basis: &HomologyBasis, weights: &[f64], w: &[f64]) -> Vec<f64> {
    let mut div = vec![0.0; mesh.num_vertices()];
    for (e, &h) in basis.edges.halfedge.iter().enumerate() {
        let (a, b) = mesh.halfedge_vertices(h as usize);
        let flux = weights[e] * w[e];
        div[a as usize] += flux;
        div[b as usize] -= flux;
    }
    div
}

/// The reduced cotangent Laplacian of a closed surface (one vertex pinned), assembled and
/// factored once. It depends on the surface alone, not on its homology, so
/// [`crate::global_map`] factors it while the tree–cotree and the cut run on the other core.
pub struct HarmonicFactor {
    part: Partition,
    chol: Cholesky,
    /// Milliseconds assembling `L` and its reduced block.
    pub assemble_ms: f64,
}

impl HarmonicFactor {
    /// Assembles and factors the cotangent Laplacian of `mesh` with vertex `pinned` fixed.
    ///
    /// # Errors
    /// [`GlobalError::Operator`] when the reduced Laplacian is not positive definite
    /// (strongly negative cotangent weights).
    pub fn new(
        mesh: &TriMesh,
        pinned: u32,
        options: &CholeskyOptions,
    ) -> Result<Self, GlobalError> {
        let t0 = Instant::now();
        let l = cotan_laplacian(mesh);
        let part = Partition::new(mesh.num_vertices(), &[pinned]);
        let blocks = LaplacianBlocks::new(&l, &part);
        let assemble_ms = ms(t0);
        let chol = Cholesky::factor_with(&blocks.ii, options)?;
        Ok(Self {
            part,
            chol,
            assemble_ms,
        })
    }

    /// Projects each closed form of `closed` onto its harmonic representative (same
    /// cohomology class: `h − ω = d f` is exact, so every period is kept). `basis` must be a
    /// homology basis of the factored mesh rooted at the pinned vertex.
    ///
    /// # Errors
    /// [`GlobalError::NonFinite`] if a solve produces a non-finite value.
    pub fn project(
        &self,
        mesh: &TriMesh,
        basis: &HomologyBasis,
        weights: &[f64],
        closed: &[Cochain],
    ) -> Result<HarmonicSolve, GlobalError> {
        let t1 = Instant::now();
        let part = &self.part;
        let ni = part.interior.len();
        let k = closed.len();
        let divs: Vec<Vec<f64>> = closed
            .iter()
            .map(|w| divergence(mesh, basis, weights, w))
            .collect();
        let mut rhs = Vec::with_capacity(ni * k);
        for d in &divs {
            rhs.extend(part.interior.iter().map(|&v| d[v as usize]));
        }
        self.chol.solve_in_place(&mut rhs, k);
        let mut forms = Vec::with_capacity(k);
        let mut codifferential_residual = 0.0f64;
        for (i, w) in closed.iter().enumerate() {
            let f = part.assemble(&rhs[i * ni..(i + 1) * ni], &[0.0]);
            if let Some(v) = f.iter().position(|x| !x.is_finite()) {
                return Err(GlobalError::NonFinite {
                    vertex: v,
                    stage: "harmonic projection",
                });
            }
            let h: Cochain = basis
                .edges
                .halfedge
                .iter()
                .zip(w)
                .map(|(&he, &x)| {
                    let (a, b) = mesh.halfedge_vertices(he as usize);
                    x + f[b as usize] - f[a as usize]
                })
                .collect();
            let scale = divs[i].iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let after = divergence(mesh, basis, weights, &h);
            let res = after.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if scale > 0.0 {
                codifferential_residual = codifferential_residual.max(res / scale);
            }
            forms.push(h);
        }
        Ok(HarmonicSolve {
            forms,
            codifferential_residual,
            factor: self.chol.stats().clone(),
            assemble_ms: self.assemble_ms,
            solve_ms: ms(t1),
        })
    }
}

/// Milliseconds since `t`.
pub(crate) fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
