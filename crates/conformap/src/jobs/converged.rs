//! Whether a solver converged, decided from its own result in one named function per
//! solver (the iterative disk solvers and Koebe's iteration decide it themselves and report
//! `converged`; these are the direct methods, which report a residual or nothing).

use conformap_global::{GlobalMap, TopologyOpt};
use conformap_sphere::{SphereReport, SPHERE_SOLVE_RESIDUAL_TOL};

/// A sphere map (Angenent's direct solve and its stages): converged when the final
/// linear solve is accurate, its residual at most the library's
/// [`SPHERE_SOLVE_RESIDUAL_TOL`].
pub fn sphere_map_converged(report: &SphereReport) -> bool {
    report.residual <= SPHERE_SOLVE_RESIDUAL_TOL
}

/// A global map by a holomorphic 1-form: linear solves and a closed-form choice of the
/// form, with no iteration to stop early; the library returns it only when every solve
/// succeeded (an error otherwise), so a returned map has converged. Its accuracy is the
/// report's `residual` (Riemann's bilinear relations).
pub fn global_map_converged(_map: &GlobalMap) -> bool {
    true
}

/// The topological optimization: a greedy loop that stops by its own rule (no slit
/// improves the uniformity, or the slit budget is spent) and returns the best layout seen,
/// so a returned result has converged.
pub fn topology_opt_converged(_result: &TopologyOpt) -> bool {
    true
}
