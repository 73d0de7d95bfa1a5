//! What a disk solver reports besides the map: the fields every method fills, and CCEM's
//! own part ([`CcemReport`]).

use num_complex::Complex64;
use serde::Serialize;

mod ccem;

pub use ccem::{BoundaryReport, CcemReport, CcemStages, LineSearchReport, SchurReport, StepRecord};

/// Wall-clock time per stage, milliseconds. Field names follow the report schema of
/// `docs/design.md` (`timings_ms`).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Timings {
    /// Assembling the Laplacian and its blocks.
    pub assemble: f64,
    /// Sparse factorizations (symbolic + numeric), all of them.
    pub factor: f64,
    /// Everything after the factorizations: initial map, iterations, final solve.
    pub solve: f64,
    /// Wall-clock time inside the solver (the setup of [`crate::DiskProblem`] included:
    /// less than `assemble + factor + solve` where the assembly and the symbolic analysis
    /// overlap, see [`crate::DiskProblem::setup_ms`]).
    pub total: f64,
}

/// The solver's account of a run (the `solver` object of the report).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct SolverReport {
    /// Method name: `harmonic`, `cem`, `ccem` or `ccem-qn`.
    pub method: String,
    /// Iterations performed (0 for a single harmonic solve): one per entry of
    /// `energy_history` after the first, so `energy_history.len() == iterations + 1`. For
    /// CCEM these are its boundary steps and the states it reaches otherwise (a Möbius
    /// re-alignment, the projection onto a raised gap floor); the flip-free repair of a
    /// folded harmonic or CEM map counts as one.
    pub iterations: usize,
    /// Whether the stopping tolerance was met before the iteration cap.
    pub converged: bool,
    /// Conformal energy `E_C` of every iterate, the initial map first; when the best
    /// harmonic or CEM iterate folded, the energy of its flip-free repair
    /// ([`crate::unfold_disk_map`]) is appended last.
    pub energy_history: Vec<f64>,
    /// Index into `energy_history` of the iterate returned (`≤ iterations`): the one of
    /// least energy among the entries from [`Self::best_from`] on.
    pub best_iteration: usize,
    /// The first entry of `energy_history` the returned iterate is chosen among: 0, or
    /// the entry where the run went on from a map that folded faces — the projection
    /// onto a raised gap floor (CCEM, when boundary gaps at the floor are below what f64
    /// resolves on the mesh) or the flip-free repair of a folded harmonic or CEM map.
    /// The entries before it may have lower energy: their maps fold faces.
    pub best_from: usize,
    /// Relative residual `‖L_II f_I + L_IB f_B‖∞ / ‖L_IB f_B‖∞` of the returned map, `L`
    /// the problem's Laplacian (not small when the notes say the interior was re-solved
    /// with a reserve operator).
    pub residual: f64,
    /// Number of sparse factorizations performed.
    pub factorizations: usize,
    /// Things the user should know about this run (e.g. an orientation fix).
    pub notes: Vec<String>,
    /// The method asked for, when it could not map the mesh flip-free and [`Self::method`]
    /// is the simpler method that did (see [`crate::run_disk_method`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fallback_from: Option<String>,
    /// Per-stage timings.
    pub timings_ms: Timings,
    /// What only CCEM reports (its fields appear in the JSON beside the common ones;
    /// `None` for the other methods).
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub ccem: Option<CcemReport>,
}

/// A disk map: one complex value per input vertex (`f = u + i v`), with its report.
#[derive(Debug, Clone)]
pub struct DiskMap {
    /// Map value of every vertex, in the input's vertex order.
    pub map: Vec<Complex64>,
    /// How it was computed.
    pub report: SolverReport,
}
