//! The [`SolverSummary`] of each sphere solver, built from its own report (the solver
//! decides whether it converged), and the peak-memory estimates of the sphere solvers.

use conformap_mesh::TriMesh;
use conformap_operators::{PeakMemory, SolverSummary};

use crate::{DoubleCoverReport, MobiusReport, SphereReport, SPHERE_SOLVE_RESIDUAL_TOL};

impl SphereReport {
    /// A direct method: one "iteration" per stage after Angenent's map, the mean
    /// chord-angle distortion (degrees) after each stage as the history, Angenent's
    /// residual; converged when that solve is accurate (residual at most
    /// [`SPHERE_SOLVE_RESIDUAL_TOL`]).
    pub fn summary(&self) -> SolverSummary {
        SolverSummary::new(
            self.stages.len().saturating_sub(1),
            self.residual <= SPHERE_SOLVE_RESIDUAL_TOL,
            self.stages
                .iter()
                .map(|s| s.mean_angle_distortion_deg)
                .collect(),
            self.residual,
        )
    }

    /// [`Self::summary`] of a sphere map normalized by a Möbius optimization afterwards:
    /// converged only if that optimization converged too.
    pub fn summary_with_mobius(&self, mobius: Option<&MobiusReport>) -> SolverSummary {
        let mut s = self.summary();
        s.converged &= mobius.is_none_or(|m| m.converged);
        s
    }
}

impl DoubleCoverReport {
    /// The summary of the covering's sphere map ([`SphereReport::summary`]).
    pub fn summary(&self) -> SolverSummary {
        self.sphere.summary()
    }
}

impl MobiusReport {
    /// Newton iterations of the best start, whether it converged, the objective at the
    /// optimum of every start as the history, and the gradient norm at the optimum.
    pub fn summary(&self) -> SolverSummary {
        let iterations = self.starts.get(self.best_start).map_or(0, |s| s.iterations);
        SolverSummary::new(
            iterations,
            self.converged,
            self.starts.iter().map(|s| s.energy).collect(),
            self.gradient_norm,
        )
    }
}

/// Estimated peak resident memory (bytes) of [`crate::sphere_map`] on `mesh`: Angenent's
/// solve and the corrections factor (nearly) every vertex.
pub fn sphere_peak_bytes(mesh: &TriMesh) -> u64 {
    let v = mesh.num_vertices();
    PeakMemory::laplacian(v, mesh.num_edges(), v).bytes()
}

/// Estimated peak resident memory (bytes) of [`crate::double_cover_disk_map`] on `mesh`:
/// the covering has twice the vertices and edges, every vertex factored.
pub fn double_cover_peak_bytes(mesh: &TriMesh) -> u64 {
    let (v, e) = (2 * mesh.num_vertices(), 2 * mesh.num_edges());
    PeakMemory::laplacian(v, e, v).bytes()
}

/// Estimated peak resident memory (bytes) of a Möbius optimization
/// ([`crate::optimize_sphere_mobius`], [`crate::optimize_disk_mobius`]) on `mesh`: no
/// factorization, the mesh, the map and per-face areas.
pub fn mobius_peak_bytes(mesh: &TriMesh) -> u64 {
    PeakMemory::laplacian(mesh.num_vertices(), mesh.num_edges(), 2).bytes()
}
