//! What [`crate::koebe`] returns: the map, the circles of its loops, and the account of the
//! iteration.

use conformap_operators::LoopCircle;
use num_complex::Complex64;
use serde::Serialize;

use crate::SolverReport;

/// One Koebe step (one map of a filled planar mesh with one loop open).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct KoebeStepRecord {
    /// Sweep number, from 1.
    pub sweep: usize,
    /// The loop that was open (mapped onto the unit circle).
    pub open_loop: usize,
    /// Newton iterations of the boundary minimization.
    pub newton_iterations: usize,
    /// Whether the Newton iteration met its step tolerance.
    pub newton_converged: bool,
    /// Conformal energy of the step's map of the filled planar mesh, with that mesh's own
    /// weights (0 for a domain that is already circular).
    pub energy: f64,
    /// Worst circle residual over all loops after the step.
    pub residual_max: f64,
    /// Whether `L_II` was refactored numerically on the symbolic analysis of an earlier
    /// step with the same open loop (`false`: a full factorization).
    pub refactored: bool,
}

/// The circle-domain energy minimization that ends [`crate::koebe`].
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct PolishReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Whether the Newton step fell below the tolerance (or to the rounding floor).
    pub converged: bool,
    /// Conformal energy `E_C` (CEM Eq. 7, the mesh's own cotangent weights, as the metrics
    /// judge it) of the start and after every iteration.
    pub energy_history: Vec<f64>,
    /// Faces of the polished map with non-positive signed area.
    pub flipped_faces: usize,
    /// Boundary vertices held at their angle because a gap next to them shrank to its floor
    /// (`1e-3` of its starting length): where the discrete energy would collapse a boundary
    /// edge (coarse loops with staircase corners).
    pub held_vertices: usize,
    /// Boundary vertices (every loop's), the size of the dense problem.
    pub boundary_vertices: usize,
    /// Milliseconds, factorization and Schur complement included.
    pub time_ms: f64,
}

/// Wall-clock time per stage of [`crate::koebe`], milliseconds.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct KoebeTimings {
    /// The first disk map (CEM on the surface with the holes filled), all of it.
    pub first_map: f64,
    /// Assembling the planar Laplacians and their blocks.
    pub assemble: f64,
    /// Sparse factorizations and refactorizations of the planar steps.
    pub factor: f64,
    /// Forming the dense Schur complements.
    pub schur: f64,
    /// Newton minimizations, harmonic extensions, inversions and circle fits.
    pub solve: f64,
    /// The circle-domain polish.
    pub polish: f64,
    /// Total time inside [`crate::koebe`].
    pub total: f64,
}

/// The account of a Koebe run (the `solver` object of the report).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct KoebeReport {
    /// `"koebe"`.
    pub method: String,
    /// The loop mapped onto the unit circle.
    pub outer_loop: usize,
    /// Sweeps performed (each maps once with every hole open, then with the outer loop).
    pub sweeps: usize,
    /// Planar steps performed.
    pub steps: usize,
    /// Whether the run converged: the polish's Newton iteration when it ran, else the
    /// Koebe iteration ([`Self::koebe_converged`]).
    pub converged: bool,
    /// Whether the Koebe sweeps brought the worst circle residual to the tolerance before
    /// the sweep cap.
    pub koebe_converged: bool,
    /// The tolerance in force.
    pub tol: f64,
    /// Worst hole circle residual after the first disk map (entry 0) and after every sweep.
    pub residual_history: Vec<f64>,
    /// Every planar step.
    pub step_history: Vec<KoebeStepRecord>,
    /// The first disk map (CEM on the surface with every hole filled).
    pub initial: SolverReport,
    /// Symbolic analyses of `L_II` (at most one per loop).
    pub symbolic_factorizations: usize,
    /// Numeric factorizations of `L_II` (one per planar step).
    pub numeric_factorizations: usize,
    /// The final circle-domain energy minimization (`None` when switched off or without
    /// holes).
    pub polish: Option<PolishReport>,
    /// Things the user should know about this run.
    pub notes: Vec<String>,
    /// Per-stage timings.
    pub timings_ms: KoebeTimings,
}

/// A conformal map onto the unit disk with circular holes.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct CircleDomainMap {
    /// Map value of every input vertex, in the input's vertex order, normalized as
    /// [`crate::koebe`] describes.
    pub map: Vec<Complex64>,
    /// Every boundary loop's circle in the normalized map, in loop order.
    pub circles: Vec<LoopCircle>,
    /// The hole made concentric with the unit circle by the normalization (the hole loop of
    /// smallest index), `None` without holes.
    pub reference_hole: Option<usize>,
    /// For two loops, the conformal modulus `ln(R / r)` of the concentric annulus (`R = 1`,
    /// `r` the hole's radius): a conformal invariant of the surface. `None` otherwise (with
    /// more holes, the normalized centres and radii of [`Self::circles`] describe it).
    pub modulus: Option<f64>,
    /// How it was computed.
    pub report: KoebeReport,
}
