//! The [`SolverSummary`] of the genus-g solvers, built from their own results (the solver
//! decides whether it converged), and their peak-memory estimates.

use conformap_mesh::TriMesh;
use conformap_operators::{PeakMemory, SolverSummary};

use crate::{GlobalMap, TopologyOpt};

impl GlobalMap {
    /// Linear solves and a closed-form choice of the form, with no iteration to stop
    /// early: [`crate::global_map`] returns a map only when every solve succeeded (an error
    /// otherwise), so a returned map has converged. Its residual is Riemann's bilinear
    /// relations of the period matrix (relative).
    pub fn summary(&self) -> SolverSummary {
        SolverSummary::direct(true, self.bilinear_residual)
    }
}

impl TopologyOpt {
    /// A greedy loop that stops by its own rule (no slit improves the uniformity, or the
    /// slit budget is spent) and returns the best layout seen, so a returned result has
    /// converged: one iteration per step after the start, the uniformity energy of every
    /// step (step 0 the starting map) as the history, no residual (0).
    pub fn summary(&self) -> SolverSummary {
        SolverSummary::new(
            self.steps.len().saturating_sub(1),
            true,
            self.steps.iter().map(|s| s.energy).collect(),
            0.0,
        )
    }
}

/// Estimated peak resident memory (bytes) of [`crate::global_map`] on `mesh`: one
/// factorization of the Laplacian of the surface the forms live on, the input (closed) or
/// its double covering (with boundary: twice the vertices and edges).
pub fn global_map_peak_bytes(mesh: &TriMesh) -> u64 {
    let copies = if mesh.boundary_loops().is_empty() {
        1
    } else {
        2
    };
    laplacian_bytes(mesh, copies)
}

/// Estimated peak resident memory (bytes) of [`crate::topology_opt`] on `mesh`: the
/// factorization of a double covering (of the slit surface, as large as the input's).
pub fn topology_opt_peak_bytes(mesh: &TriMesh) -> u64 {
    laplacian_bytes(mesh, 2)
}

fn laplacian_bytes(mesh: &TriMesh, copies: usize) -> u64 {
    let (v, e) = (copies * mesh.num_vertices(), copies * mesh.num_edges());
    PeakMemory::laplacian(v, e, v).bytes()
}
