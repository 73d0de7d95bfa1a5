//! The `solver` object of a report: the [`SolverSummary`] every solver crate returns (its
//! four common fields first), then the solver's own part ([`SolverDetail`]).

use conformap_disk::{KoebeReport, SolverReport};
use conformap_operators::SolverSummary;
use conformap_sphere::{DoubleCoverReport, MobiusReport, SphereReport};
use serde::ser::Error as _;
use serde::{Serialize, Serializer};
use serde_json::{Map, Value};

use super::sorted::sorted_object;

/// The `solver` object: the solver's summary, then its own report.
#[derive(Debug, Clone)]
pub struct SolverSection {
    /// Iterations, converged (as the solver decided it), energy history, residual.
    pub summary: SolverSummary,
    /// The rest of the solver's account, by command.
    pub detail: SolverDetail,
    /// The options given that the map did not use, each with why (written as
    /// `ignored_options` among the solver's own keys, only when there is one).
    pub ignored_options: Vec<String>,
}

impl SolverSection {
    /// The section of `summary` and `detail`.
    pub fn new(summary: SolverSummary, detail: SolverDetail) -> Self {
        Self {
            summary,
            detail,
            ignored_options: Vec::new(),
        }
    }

    /// With the options the map did not use (`ignored`, each with why).
    pub fn with_ignored_options(mut self, ignored: Vec<String>) -> Self {
        self.ignored_options = ignored;
        self
    }
}

/// The solver's own part of the `solver` object, by command. It is written after the
/// summary with its keys in sorted order at every depth (the report's order since its
/// first version), without the summary's four keys a library report repeats.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum SolverDetail {
    /// A direct method with nothing to add (`flatten`, `atlas`).
    None,
    /// A disk method of conformap-disk (`harmonic`, `cem`, `ccem`, `ccem-qn`).
    Disk(SolverReport),
    /// Koebe's iteration (`disk` on several boundary loops; boxed: the largest report).
    Koebe(Box<KoebeReport>),
    /// The disk map through the double covering.
    DoubleCover(DoubleCoverDetail),
    /// The sphere map and its optional Möbius normalization.
    Sphere(SphereDetail),
    /// The Möbius optimization of a given map.
    Mobius(MobiusDetail),
    /// A global map by a holomorphic 1-form.
    Global(GlobalDetail),
    /// The starting map returned by the topological optimization (no slit paid).
    TopologySteps(TopologyStepsDetail),
    /// A direct map with a note on how it was made (a disk without interior vertices).
    Note(NoteDetail),
}

/// A note on how a direct map was made.
#[derive(Debug, Clone, Serialize)]
pub struct NoteDetail {
    /// The note.
    pub note: &'static str,
}

/// The double cover's report, what its history means and the flip-free repair.
#[derive(Debug, Clone, Serialize)]
pub struct DoubleCoverDetail {
    /// The library's report.
    #[serde(flatten)]
    pub report: DoubleCoverReport,
    /// What `energy_history` holds.
    pub energy_history_is: &'static str,
    /// The flip-free repair of a folded covering map (`null` when none was needed).
    pub unfolded: Option<UnfoldedSection>,
}

/// What the flip-free guard of conformap-disk changed.
#[derive(Debug, Clone, Serialize)]
pub struct UnfoldedSection {
    /// Flipped faces before the repair.
    pub flipped_before: usize,
    /// Flipped faces after it.
    pub flipped_after: usize,
    /// Gaps repaired.
    pub repaired_gaps: usize,
    /// The smallest gap kept.
    pub gap_floor: f64,
}

/// The sphere map's report and its Möbius normalization.
#[derive(Debug, Clone, Serialize)]
pub struct SphereDetail {
    /// What `energy_history` holds.
    pub energy_history_is: &'static str,
    /// The Möbius normalization (`null` without one).
    pub mobius: Option<MobiusReport>,
    /// The sphere map's report.
    pub sphere: SphereReport,
}

/// The Möbius optimization's report, and what its history and residual mean.
#[derive(Debug, Clone, Serialize)]
pub struct MobiusDetail {
    /// What `energy_history` holds.
    pub energy_history_is: &'static str,
    /// The optimization's report.
    pub mobius: MobiusReport,
    /// What `residual` is.
    pub residual_is: &'static str,
}

/// The residuals of a global map besides the bilinear relations.
#[derive(Debug, Clone, Serialize)]
pub struct GlobalDetail {
    /// The harmonic projection's residual.
    pub harmonic_residual: f64,
    /// What `residual` is.
    pub residual_is: &'static str,
    /// The largest mismatch of a seam's two sides from a pure translation.
    pub seam_residual: f64,
}

/// What the history of the topological optimization's steps means.
#[derive(Debug, Clone, Serialize)]
pub struct TopologyStepsDetail {
    /// What `energy_history` holds.
    pub energy_history_is: String,
}

/// The summary followed by the detail's sorted entries (without the summary's keys).
#[derive(Serialize)]
struct Written<'a> {
    #[serde(flatten)]
    summary: &'a SolverSummary,
    #[serde(flatten)]
    detail: Map<String, Value>,
}

/// The keys of [`SolverSummary`], written once.
const SUMMARY_KEYS: [&str; 4] = ["iterations", "converged", "energy_history", "residual"];

impl Serialize for SolverSection {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut detail = sorted_object(&self.detail).map_err(S::Error::custom)?;
        detail.retain(|k, _| !SUMMARY_KEYS.contains(&k.as_str()));
        if !self.ignored_options.is_empty() {
            let ignored = serde_json::to_value(&self.ignored_options).map_err(S::Error::custom)?;
            detail.insert("ignored_options".to_string(), ignored);
        }
        Written {
            summary: &self.summary,
            detail,
        }
        .serialize(serializer)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    /// The summary's four keys come first and once (the library report repeats them), the
    /// solver's own keys after them in sorted order.
    #[test]
    fn summary_first_then_the_solvers_own_keys_sorted() {
        let report = SolverReport {
            method: "cem".into(),
            iterations: 3,
            converged: true,
            energy_history: vec![4.0, 2.0, 1.0, 0.5],
            residual: 1e-13,
            factorizations: 1,
            ..SolverReport::default()
        };
        let section = SolverSection::new(report.summary(), SolverDetail::Disk(report));
        let json = serde_json::to_string(&section).unwrap();
        assert!(
            json.starts_with(
                r#"{"iterations":3,"converged":true,"energy_history":[4.0,2.0,1.0,0.5],"residual":1e-13,"best_from":0,"best_iteration":0,"#
            ),
            "{json}"
        );
        assert_eq!(json.matches("\"iterations\"").count(), 1, "{json}");
        let at = |key: &str| json.find(&format!("\"{key}\":")).unwrap();
        let own = [
            "best_from",
            "best_iteration",
            "factorizations",
            "method",
            "notes",
            "timings_ms",
        ];
        assert!(own.windows(2).all(|w| at(w[0]) < at(w[1])), "{json}");
        assert!(at("residual") < at("best_from"), "{json}");
    }

    /// The ignored options are written among the solver's own keys, in their sorted place,
    /// and not at all when there is none.
    #[test]
    fn ignored_options_are_written_in_sorted_place_only_when_some() {
        let report = SolverReport {
            method: "harmonic".into(),
            ..SolverReport::default()
        };
        let plain = SolverSection::new(report.summary(), SolverDetail::Disk(report.clone()));
        let json = serde_json::to_string(&plain).unwrap();
        assert!(!json.contains("ignored_options"), "{json}");
        let ignored = plain.with_ignored_options(vec!["--tol: harmonic does not iterate".into()]);
        let json = serde_json::to_string(&ignored).unwrap();
        let at = |key: &str| json.find(&format!("\"{key}\":")).unwrap();
        assert!(at("factorizations") < at("ignored_options"), "{json}");
        assert!(at("ignored_options") < at("method"), "{json}");
        assert!(
            json.contains(r#""ignored_options":["--tol: harmonic does not iterate"]"#),
            "{json}"
        );
    }

    /// A direct method with nothing of its own writes the summary alone.
    #[test]
    fn a_direct_method_writes_its_summary_alone() {
        let section = SolverSection::new(SolverSummary::direct(true, 2.5e-16), SolverDetail::None);
        let json = serde_json::to_string(&section).unwrap();
        assert_eq!(
            json,
            r#"{"iterations":0,"converged":true,"energy_history":[],"residual":2.5e-16}"#
        );
    }
}
