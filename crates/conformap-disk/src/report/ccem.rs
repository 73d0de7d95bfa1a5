//! What a CCEM run reports besides the fields every disk solver fills: its gradients,
//! stages, line searches, Schur-complement path and boundary.

use serde::Serialize;

/// CCEM's own part of the solver report.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct CcemReport {
    /// Euclidean norm of the projected gradient of `E_C(θ)` (CCEM Eq. 4.1, with the
    /// components that would push boundary gaps held at the floor further down removed;
    /// the plain `‖∇_θ E_C‖` when no gap is held) at every iterate, aligned with
    /// `energy_history`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub gradient_norm_history: Vec<f64>,
    /// What the line searches did.
    pub line_search: LineSearchReport,
    /// How the Schur complement was applied.
    pub schur: SchurReport,
    /// The state of the boundary of the returned map.
    pub boundary: BoundaryReport,
    /// Where the run spent its time.
    pub stages_ms: CcemStages,
}

/// Milliseconds per stage of a CCEM run (after the problem's assembly and factorization).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct CcemStages {
    /// The starting boundary (Angenent's map from the Schur complement by default; CEM,
    /// with its own factorization, on request) and the Hessian preconditioner at it.
    pub start: f64,
    /// Forming the dense Schur complement (0 for implicit).
    pub schur: f64,
    /// The iterations on the boundary angles.
    pub iterations: f64,
    /// The final harmonic solve(s), the fold check and the residual.
    pub finish: f64,
}

/// Counts of the line searches of a CCEM run.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct LineSearchReport {
    /// Energy (and gradient) evaluations over all searches, the quadratic-step products
    /// not included.
    pub evaluations: usize,
    /// Accepted steps that satisfy both Wolfe conditions (CCEM Eq. 4.7 and 4.9).
    pub wolfe_steps: usize,
    /// Accepted steps cut by the bijectivity guard (sufficient decrease only: the
    /// minimizer along the line lies where boundary vertices would meet).
    pub guard_limited_steps: usize,
    /// Accepted steps along the projected path `Π(θ + α d)` past the guard (gaps that would
    /// close set to the floor), with sufficient decrease measured along the displacement.
    pub projected_steps: usize,
    /// Accepted steps with sufficient decrease whose curvature condition could not be met
    /// within the evaluation budget.
    pub decrease_only_steps: usize,
    /// Quasi-Newton iterations that fell back to the steepest descent direction because
    /// the quasi-Newton one did not descend (after the guard's projection).
    pub gradient_fallbacks: usize,
    /// Curvature pairs the quasi-Newton update refused (`sᵀy` not positive).
    pub qn_pairs_skipped: usize,
    /// Quasi-Newton restarts: a Wolfe step whose decrease met the tolerance while BFGS
    /// held two or more pairs emptied the pairs and went on; the run stops only when the
    /// first steps after a restart meet it too (see `CcemOptions::tol`).
    pub qn_restarts: usize,
    /// Every accepted step, when [`crate::CcemOptions::record_steps`] is set.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub steps: Vec<StepRecord>,
}

/// One accepted step of a CCEM run: the data to check the Wolfe conditions.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StepRecord {
    /// Step length `α`.
    pub alpha: f64,
    /// Largest step the bijectivity guard allowed.
    pub alpha_max: f64,
    /// `E_C(θ_k)`.
    pub energy_before: f64,
    /// `E_C(θ_k + α d)`.
    pub energy_after: f64,
    /// Directional derivative `∇E_C(θ_k)·d` (negative).
    pub slope_before: f64,
    /// Directional derivative `∇E_C(θ_k + α d)·d`.
    pub slope_after: f64,
    /// Energy evaluations of this search.
    pub evaluations: usize,
    /// `"wolfe"`, `"guard"`, `"projected"` or `"decrease"` (see [`LineSearchReport`]).
    pub kind: &'static str,
}

/// How CCEM applied the Schur complement `A` (CCEM Eq. 3.15).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SchurReport {
    /// `"dense"` (formed once, `n_B × n_B`) or `"implicit"` (a solve per product).
    pub mode: String,
    /// Milliseconds spent forming the dense matrix (0 for implicit).
    pub form_ms: f64,
    /// Products `A x` over the run (each a complex vector: two real columns).
    pub products: usize,
}

/// The boundary of a CCEM map: how close its vertices came to each other.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct BoundaryReport {
    /// Smallest angle between consecutive boundary vertices, radians.
    pub min_gap: f64,
    /// Boundary loop position after which that gap lies.
    pub min_gap_after: usize,
    /// The guard's floor on gaps ([`crate::CcemOptions::min_gap`]).
    pub gap_floor: f64,
    /// Gaps held at the floor when the run stopped: where the conformal map would put
    /// boundary vertices closer than f64 (or the floor) resolves.
    pub gaps_at_floor: usize,
    /// Gaps of the starting boundary that had to be repaired (backward or collapsed).
    pub start_repaired_gaps: usize,
    /// Faces of the returned map with non-positive signed image area.
    pub flipped_faces: usize,
}
