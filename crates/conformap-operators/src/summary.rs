//! The account every solver gives of its run in the same four fields (the `solver` object
//! of a report opens with them): each solver crate builds it from its own result, so the
//! solver, not its caller, decides whether it converged.

use serde::Serialize;

/// What a solver did, in the four fields common to every solver: iterations, whether it
/// converged (by its own stopping rule), the history of the quantity it minimized, and
/// its final residual. Their meaning in detail is the solver's (its report names it).
///
/// # Examples
/// ```
/// use conformap_operators::SolverSummary;
/// let s = SolverSummary::new(3, true, vec![2.0, 1.0, 0.5, 0.25], 1e-12);
/// assert!(s.converged && s.iterations + 1 == s.energy_history.len());
/// let json = serde_json::to_string(&s).unwrap();
/// assert!(json.starts_with(r#"{"iterations":3,"converged":true,"energy_history""#));
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct SolverSummary {
    /// Iterations of the solver's main loop (what counts as one is the solver's).
    pub iterations: usize,
    /// Whether the solver met its own stopping rule (not its iteration cap).
    pub converged: bool,
    /// The minimized quantity after each iteration (empty for a direct method).
    pub energy_history: Vec<f64>,
    /// The solver's final residual (its meaning is the solver's, documented there).
    pub residual: f64,
}

impl SolverSummary {
    /// The summary of a run.
    pub fn new(
        iterations: usize,
        converged: bool,
        energy_history: Vec<f64>,
        residual: f64,
    ) -> Self {
        Self {
            iterations,
            converged,
            energy_history,
            residual,
        }
    }

    /// The summary of a direct method (no iteration, no history): converged when it
    /// returned a result, with its `residual`.
    pub fn direct(converged: bool, residual: f64) -> Self {
        Self::new(0, converged, Vec::new(), residual)
    }
}
