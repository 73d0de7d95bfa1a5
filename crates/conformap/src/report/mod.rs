//! The JSON report of a map command (schema in docs/design.md: stable field names), as types:
//! a field the schema requires cannot be left out without a compile error.
//!
//! Every map command returns a [`Report`]; the pipeline writes it with `--report` and the
//! caller (the binary, `batch`, the Python package) gets the same value. Each section is a
//! type: the solver's (`solver.rs`), the metrics (`metrics.rs`), the command-specific
//! top-level sections (`sections.rs`), the repairs (`repairs.rs`); the parts that have
//! always been written with sorted keys are [`Sorted`] (`sorted.rs`).

use std::path::Path;

use conformap_mesh::TriMesh;
use serde::Serialize;

mod metrics;
mod repairs;
mod sections;
mod solver;
mod sorted;

pub use metrics::{MapQuality, MetricsExtra, MetricsSection};
pub use repairs::RepairsReport;
pub use sections::{
    CircleDomainSection, FactorizationSection, GlobalSection, Sections, TopologySection,
    WrittenMesh, ZeroEntry,
};
pub use solver::{
    DoubleCoverDetail, GlobalDetail, MobiusDetail, NoteDetail, SolverDetail, SolverSection,
    SphereDetail, TopologyStepsDetail, UnfoldedSection,
};
pub use sorted::Sorted;

/// The report of one map command.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// The version of conformap that wrote it.
    pub conformap_version: &'static str,
    /// The subcommand: `disk`, `sphere`, `mobius`, …
    pub command: &'static str,
    /// The method that computed the map (`ccem-qn`, `koebe`, `double-cover`, …).
    pub method: String,
    /// The mesh that was mapped.
    pub input: InputInfo,
    /// The map file a command started from (`mobius`), if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub param: Option<ParamInfo>,
    /// What the solver did.
    pub solver: SolverSection,
    /// Command-specific sections at the top level (`factorization`, `circle_domain`, …).
    #[serde(flatten)]
    pub sections: Sections,
    /// How good the map is.
    pub metrics: MetricsSection,
    /// The memory check: estimate, limit, measured peak.
    pub memory: MemoryReport,
    /// What `--repair` changed (only with `--repair`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repairs: Option<RepairsReport>,
    /// Wall-clock milliseconds per stage.
    pub timings_ms: StageTimings,
}

/// The `input` object of a report.
#[derive(Debug, Clone, Serialize)]
pub struct InputInfo {
    /// Path as given on the command line.
    pub path: String,
    /// Vertex count (after glTF welding).
    pub vertices: usize,
    /// Face count (after triangulation).
    pub faces: usize,
    /// Number of boundary loops.
    pub boundaries: usize,
    /// Genus (null for several components).
    pub genus: Option<i64>,
    /// Connected components.
    pub components: usize,
}

impl InputInfo {
    /// Describes `mesh` read from `path`.
    pub fn new(path: &Path, mesh: &TriMesh) -> Self {
        Self {
            path: path.display().to_string(),
            vertices: mesh.num_vertices(),
            faces: mesh.num_faces(),
            boundaries: mesh.boundary_loops().len(),
            genus: mesh.genus(),
            components: mesh.num_components(),
        }
    }
}

/// The `param` object: the map file a command read, and which of its data held the map.
#[derive(Debug, Clone, Serialize)]
pub struct ParamInfo {
    /// Path as given.
    pub path: String,
    /// `texture coordinates`, `flat positions`, `sphere positions`, …
    pub map_from: &'static str,
}

/// The `memory` object. `limit_bytes` and `peak_rss_bytes` are measurements of the machine
/// and the run (like timings), not of the input.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct MemoryReport {
    /// The estimated peak of the run (the larger of reading and solving).
    pub estimated_peak_bytes: u64,
    /// The limit the estimate was held against, if known.
    pub limit_bytes: Option<u64>,
    /// Where the limit came from (`--max-memory`, `MemAvailable`, `cgroup memory.max`).
    pub limit_source: Option<&'static str>,
    /// The measured peak resident memory of the process (Linux `VmHWM`); in a `batch` with
    /// one job at a time, of this run alone (the mark is reset before each input).
    pub peak_rss_bytes: Option<u64>,
}

/// The `timings_ms` object of a report.
#[derive(Debug, Clone, Default, Serialize)]
pub struct StageTimings {
    /// Reading and validating the input.
    pub read: f64,
    /// Assembling the Laplacian and its blocks. For the disk methods with the cotangent
    /// Laplacian it runs at the same time as the symbolic analysis (two cores), so
    /// `assemble + factor + solve` exceeds the solver's wall-clock `solver.timings_ms.total`
    /// by about the shorter of the two.
    pub assemble: f64,
    /// Sparse factorizations (symbolic analysis included).
    pub factor: f64,
    /// Of `factor`, the symbolic analysis (fill-reducing ordering and structure) of the
    /// interior Laplacian `L_II`: `tools/bench`'s `analyse` stage (its `factor` stage is
    /// `factor − analyse`, its `iterate` stage is `solve`). 0 for commands that do not
    /// factor one `L_II`.
    pub analyse: f64,
    /// Everything else inside the solver.
    pub solve: f64,
    /// Computing the quality metrics.
    pub metrics: f64,
    /// Writing the output files.
    pub write: f64,
    /// Wall-clock total of the command.
    pub total: f64,
}

/// Milliseconds since `t`.
pub fn ms_since(t: std::time::Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
