//! The [`SolverSummary`] of each disk solver, built from its own report: the solver
//! decides whether it converged.

use conformap_operators::SolverSummary;

use crate::{CircleDomainMap, FlattenReport, SolverReport};

/// Largest relative closing residual `|Σ l* T|` / perimeter of a boundary first flattening
/// whose boundary curve counts as closed (its [`FlattenReport::summary`] then says
/// `converged`); the closing itself reaches round-off (measured ≤ 6e-16 on every shared mesh).
pub const FLATTEN_CLOSURE_TOL: f64 = 1e-9;

impl SolverReport {
    /// The four common fields: boundary iterations, the method's own stopping rule, the
    /// `E_C` history and the interior residual.
    pub fn summary(&self) -> SolverSummary {
        SolverSummary::new(
            self.iterations,
            self.converged,
            self.energy_history.clone(),
            self.residual,
        )
    }
}

impl CircleDomainMap {
    /// The four common fields: Koebe sweeps, whether the run converged (the polish's
    /// Newton iteration when it ran, else the sweeps), the polish's energy history (empty
    /// without a polish) and the worst circle residual of the returned map.
    pub fn summary(&self) -> SolverSummary {
        let r = &self.report;
        let history = r
            .polish
            .as_ref()
            .map_or_else(Vec::new, |p| p.energy_history.clone());
        let residual = self
            .circles
            .iter()
            .fold(0.0f64, |a, c| a.max(c.residual_max));
        SolverSummary::new(r.sweeps, r.converged, history, residual)
    }
}

impl FlattenReport {
    /// A direct method (linear solves, no iteration): converged when the boundary curve
    /// closed, its [`Self::closure_residual`] below [`FLATTEN_CLOSURE_TOL`].
    pub fn summary(&self) -> SolverSummary {
        SolverSummary::direct(
            self.closure_residual < FLATTEN_CLOSURE_TOL,
            self.closure_residual,
        )
    }
}
