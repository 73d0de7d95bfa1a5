//! What a disk solver reports besides the map.

use num_complex::Complex64;
use serde::Serialize;

/// Wall-clock time per stage, milliseconds. Field names follow the report schema of
/// `design.md` (`timings_ms`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Assembling the Laplacian and its blocks.
    pub assemble: f64,
    /// Sparse factorizations (symbolic + numeric), all of them.
    pub factor: f64,
    /// Everything after the factorizations: initial map, iterations, final solve.
    pub solve: f64,
    /// Total time inside the solver.
    pub total: f64,
}

/// The solver's account of a run (the `solver` object of the report).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SolverReport {
    /// Method name: `harmonic`, `cem`, `ccem` or `ccem-qn`.
    pub method: String,
    /// Boundary iterations performed (0 for a single harmonic solve).
    pub iterations: usize,
    /// Whether the stopping tolerance was met before the iteration cap.
    pub converged: bool,
    /// Conformal energy `E_C` of every iterate, the initial map first.
    pub energy_history: Vec<f64>,
    /// Index into `energy_history` of the iterate returned (the one of least energy).
    pub best_iteration: usize,
    /// Relative residual `‖L_II f_I + L_IB f_B‖∞ / ‖L_IB f_B‖∞` of the returned map's
    /// interior solve.
    pub residual: f64,
    /// Number of sparse factorizations performed.
    pub factorizations: usize,
    /// Things the user should know about this run (e.g. an orientation fix).
    pub notes: Vec<String>,
    /// Per-stage timings.
    pub timings_ms: Timings,
}

/// A disk map: one complex value per input vertex (`f = u + i v`), with its report.
#[derive(Debug, Clone)]
pub struct DiskMap {
    /// Map value of every vertex, in the input's vertex order.
    pub map: Vec<Complex64>,
    /// How it was computed.
    pub report: SolverReport,
}
