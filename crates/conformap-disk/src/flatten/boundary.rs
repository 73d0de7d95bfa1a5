//! Curvatures and the two boundary conversions of boundary first flattening (Sawhney &
//! Crane 2017, §4): Dirichlet → Neumann (boundary scale factors `u` to the target boundary
//! curvature `κ̃`) and Neumann → Dirichlet (`κ̃` to `u`).
//!
//! Conventions. `L` is the positive semi-definite cotangent Laplacian of the problem
//! (`L_ii = Σ w_ij`, `L_ij = −w_ij`). Integrated curvatures: the angle defect
//! `K_i = 2π − Σ θ` at an interior vertex and the geodesic curvature `κ_i = π − Σ θ` at a
//! boundary vertex (the exterior turning angle of a flat boundary). Scaling the metric by
//! `e^{2u}` changes them, to first order and exactly in the discrete setting of the paper,
//! by `(L u)_i`: `K̃ = K + (L u)_I` inside and `κ̃ = κ + (L u)_B` on the boundary (the
//! paper's Eq. 9–10 with its Laplacian of the opposite sign). A flat map has `K̃ = 0`.
//! The sums are kept: `Σ (L u) = 0`, so `Σ κ̃ = Σ K + Σ κ = 2π χ` (discrete Gauss–Bonnet).

use conformap_mesh::TriMesh;
use conformap_operators::{corner_angles, Cholesky, CholeskyOptions, LaplacianBlocks, Partition};
use sprs::CsMat;

use crate::{DiskError, DiskProblem};

/// Angle defects of the interior vertices (interior order) and geodesic curvatures of the
/// boundary vertices (boundary order), from the mesh's corner angles.
#[derive(Debug, Clone)]
pub(crate) struct Curvatures {
    /// `K_I = 2π − Σ θ`.
    pub interior: Vec<f64>,
    /// `κ_B = π − Σ θ`.
    pub boundary: Vec<f64>,
}

/// The sum of the corner angles at every vertex.
pub(crate) fn angle_sums(mesh: &TriMesh) -> Vec<f64> {
    let mut sums = vec![0.0; mesh.num_vertices()];
    for (t, a) in mesh.faces().iter().zip(corner_angles(mesh)) {
        for k in 0..3 {
            sums[t[k] as usize] += a[k];
        }
    }
    sums
}

impl Curvatures {
    /// The curvatures for the problem's partition from the [`angle_sums`] of its mesh.
    pub(crate) fn new(sums: &[f64], partition: &Partition) -> Self {
        let tau = std::f64::consts::TAU;
        let pi = std::f64::consts::PI;
        Self {
            interior: partition
                .interior
                .iter()
                .map(|&v| tau - sums[v as usize])
                .collect(),
            boundary: partition
                .boundary
                .iter()
                .map(|&v| pi - sums[v as usize])
                .collect(),
        }
    }
}

/// `y += L_IB x` (interior rows, boundary columns).
fn ib_mul_add(ib: &CsMat<f64>, x: &[f64], y: &mut [f64]) {
    for (j, col) in ib.outer_iterator().enumerate() {
        for (i, &v) in col.iter() {
            y[i] += v * x[j];
        }
    }
}

/// `L_BI y + L_BB x` for interior values `y` and boundary values `x`.
fn boundary_rows(blocks: &LaplacianBlocks, y: &[f64], x: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = blocks
        .ib
        .outer_iterator()
        .map(|col| col.iter().map(|(i, &v)| v * y[i]).sum())
        .collect();
    for (j, col) in blocks.bb.outer_iterator().enumerate() {
        for (i, &v) in col.iter() {
            out[i] += v * x[j];
        }
    }
    out
}

/// Dirichlet → Neumann: the interior scale factors of the flat metric with boundary scale
/// factors `u_b` (`L_II u_I = −K_I − L_IB u_B`, one solve with the problem's factor of
/// `L_II`) and the boundary curvature it gives, `κ̃ = κ + L_BI u_I + L_BB u_B`.
///
/// Returns `(u_I, κ̃)`.
pub(crate) fn dirichlet_to_neumann(
    problem: &DiskProblem<'_>,
    curv: &Curvatures,
    u_b: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let blocks = problem.blocks();
    let mut rhs: Vec<f64> = curv.interior.iter().map(|k| -k).collect();
    let mut lu = vec![0.0; rhs.len()];
    ib_mul_add(&blocks.ib, u_b, &mut lu);
    for (r, l) in rhs.iter_mut().zip(&lu) {
        *r -= l;
    }
    problem.interior_factor().solve_in_place(&mut rhs, 1);
    let lb = boundary_rows(blocks, &rhs, u_b);
    let kappa = curv.boundary.iter().zip(&lb).map(|(k, l)| k + l).collect();
    (rhs, kappa)
}

/// The Laplacian with one vertex's row and column removed, factored once: the Neumann
/// problems `L x = b` (with `Σ b = 0`) of the whole mesh are solved with it.
#[derive(Debug)]
pub(crate) struct PinnedLaplacian {
    partition: Partition,
    factor: Cholesky,
}

impl PinnedLaplacian {
    /// Analyses and factors `L` without the row and column of `pin`.
    pub(crate) fn new(problem: &DiskProblem<'_>, pin: u32) -> Result<Self, DiskError> {
        let n = problem.mesh().num_vertices();
        let partition = Partition::new(n, &[pin]);
        let reduced = LaplacianBlocks::new(problem.laplacian(), &partition).ii;
        let factor = Cholesky::factor_with(&reduced, &CholeskyOptions::DEFAULT)?;
        Ok(Self { partition, factor })
    }

    /// The solution of `L x = b` (vertex order) with `x = 0` at the pinned vertex; `b` must
    /// sum to zero (the pinned row then holds too).
    pub(crate) fn solve(&self, b: &[f64]) -> Vec<f64> {
        let mut reduced = self.partition.interior_values(b);
        self.factor.solve_in_place(&mut reduced, 1);
        self.partition.assemble(&reduced, &[0.0])
    }
}

/// Neumann → Dirichlet: the scale factors (vertex order) of the flat metric whose boundary
/// curvature is `kappa_target` (boundary order; its sum must be `2π` up to rounding):
/// `L u = K̃ − K` with `K̃ = 0` inside. Determined up to a constant (0 at the pinned vertex).
pub(crate) fn neumann_to_dirichlet(
    problem: &DiskProblem<'_>,
    pinned: &PinnedLaplacian,
    curv: &Curvatures,
    kappa_target: &[f64],
) -> Vec<f64> {
    let partition = problem.partition();
    let interior: Vec<f64> = curv.interior.iter().map(|k| -k).collect();
    let boundary: Vec<f64> = kappa_target
        .iter()
        .zip(&curv.boundary)
        .map(|(t, k)| t - k)
        .collect();
    pinned.solve(&partition.assemble(&interior, &boundary))
}
