//! The JSON report of a map command (schema in docs/design.md: stable field names), as types:
//! a field the schema requires cannot be left out without a compile error.
//!
//! Every map command returns a [`Report`]; the pipeline writes it with `--report` and the
//! caller (the binary, `batch`, the Python package) gets the same value.

use std::path::Path;

use conformap_mesh::{RepairLog, TriMesh};
use serde::Serialize;
use serde_json::{Map, Value};

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

/// The command-specific top-level sections of a report, each present only for the
/// commands that have it (declared in alphabetical order, the order they are written in).
#[derive(Debug, Clone, Default, Serialize)]
pub struct Sections {
    /// The atlas (`atlas`): components, charts, cones, overlap, packing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atlas: Option<conformap_atlas::AtlasReport>,
    /// The disk with circular holes (`disk` on several boundary loops).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub circle_domain: Option<CircleDomainSection>,
    /// The one sparse factorization of the solve (`disk`, `global`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factorization: Option<FactorizationSection>,
    /// The boundary first flattening (`flatten`): boundary mode, corners, the curve's
    /// closing, the boundary scale factors, overlap.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flatten: Option<conformap_disk::FlattenReport>,
    /// The holomorphic form, its periods, zeros and seams (`global`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub global: Option<Value>,
    /// The topological optimization's steps and slits (`global --topology-opt`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub topology_opt: Option<Value>,
}

/// The `circle_domain` section (fields in alphabetical order, as written).
#[derive(Debug, Clone, Serialize)]
pub struct CircleDomainSection {
    /// Every loop's fitted circle: centre, radius, residual.
    pub circles: Vec<conformap_operators::LoopCircle>,
    /// For two loops, the conformal modulus ln(R/r).
    pub modulus: Option<f64>,
    /// How the domain is normalized.
    pub normalization: &'static str,
    /// The loop mapped onto the unit circle.
    pub outer_loop: usize,
    /// The hole centred at 0 (the lowest loop index), if any.
    pub reference_hole: Option<usize>,
}

/// The `factorization` section: the size of the one sparse factor.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum FactorizationSection {
    /// The interior Laplacian `L_II` of a disk map (fields in alphabetical order).
    Interior {
        /// Interior vertices (the dimension of `L_II`).
        interior_vertices: usize,
        /// Nonzeros of the Cholesky factor.
        nnz_factor: usize,
        /// The fill-reducing ordering used.
        ordering: &'static str,
    },
    /// The Laplacian of the surface the forms live on (`global`).
    Forms {
        /// Its dimension.
        dim: usize,
        /// Nonzeros of the factor.
        nnz_factor: usize,
    },
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

/// The `solver` object: the schema's four common fields, then the solver's own report.
#[derive(Debug, Clone, Serialize)]
pub struct SolverSection {
    /// Iterations of the solver's main loop (what counts as one is the method's).
    pub iterations: usize,
    /// Whether the solver met its stopping rule (not its iteration cap).
    pub converged: bool,
    /// The energy (or the quantity named by `energy_history_is`) after each iteration.
    pub energy_history: Vec<f64>,
    /// The solver's final residual (its meaning is the method's, documented there).
    pub residual: f64,
    /// The rest of the solver's own report.
    #[serde(flatten)]
    pub detail: Map<String, Value>,
}

impl SolverSection {
    /// The common fields, and `detail` (a library report) without the keys they repeat.
    pub fn new(
        iterations: usize,
        converged: bool,
        energy_history: Vec<f64>,
        residual: f64,
        detail: &impl Serialize,
    ) -> Self {
        let mut detail = object(detail);
        for key in ["iterations", "converged", "energy_history", "residual"] {
            detail.remove(key);
        }
        Self {
            iterations,
            converged,
            energy_history,
            residual,
            detail,
        }
    }

    /// Adds `key: value` to the solver's own part.
    pub fn with(mut self, key: &str, value: impl Serialize) -> Self {
        self.detail.insert(key.to_string(), to_value(&value));
        self
    }
}

/// The `metrics` object: a metrics struct of the library (planar or sphere), plus
/// command-specific entries (values before a Möbius move, cross ratios, …).
#[derive(Debug, Clone, Serialize)]
pub struct MetricsSection {
    /// The library's metrics.
    #[serde(flatten)]
    pub base: MapQuality,
    /// Extra entries.
    #[serde(flatten)]
    pub extra: Map<String, Value>,
}

/// The metrics of a map, by domain.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum MapQuality {
    /// A planar map (disk, disk with holes).
    Planar(conformap_metrics::MapMetrics),
    /// A sphere map.
    Sphere(conformap_sphere::SphereMetrics),
}

impl MetricsSection {
    /// The metrics of a planar map.
    pub fn planar(m: conformap_metrics::MapMetrics) -> Self {
        Self {
            base: MapQuality::Planar(m),
            extra: Map::new(),
        }
    }

    /// The metrics of a sphere map.
    pub fn sphere(m: conformap_sphere::SphereMetrics) -> Self {
        Self {
            base: MapQuality::Sphere(m),
            extra: Map::new(),
        }
    }

    /// Adds `key: value`.
    pub fn with(mut self, key: &str, value: impl Serialize) -> Self {
        self.extra.insert(key.to_string(), to_value(&value));
        self
    }

    /// `(conformal energy or uniformity, mean angle distortion in degrees, flipped faces)`:
    /// the numbers a summary line or a batch line shows.
    pub fn headline(&self) -> (f64, f64, usize) {
        match &self.base {
            MapQuality::Planar(m) => (
                m.conformal_energy,
                m.angle_distortion_deg.mean,
                m.flipped_faces,
            ),
            MapQuality::Sphere(m) => (
                m.uniformity_energy,
                m.angle_distortion_deg.mean,
                m.flipped_faces,
            ),
        }
    }
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

/// The `repairs` object: what `--repair` changed, and the sizes of the maps back to the
/// input.
#[derive(Debug, Clone, Serialize)]
pub struct RepairsReport {
    /// One line per repair applied.
    pub applied: Vec<String>,
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces of the input.
    pub input_faces: usize,
    /// Duplicate faces dropped.
    pub duplicate_faces: usize,
    /// Components of the input.
    pub components: usize,
    /// Faces dropped with the smaller components.
    pub component_faces_dropped: usize,
    /// Vertices dropped with the smaller components.
    pub component_vertices_dropped: usize,
    /// Faces re-oriented.
    pub flipped_faces: usize,
    /// Unreferenced vertices dropped.
    pub unreferenced_vertices: usize,
    /// Sizes of the vertex maps.
    pub vertex_map: Value,
    /// Size of the face map.
    pub face_map: Value,
}

impl RepairsReport {
    /// The report of `log`.
    pub fn new(log: &RepairLog) -> Self {
        Self {
            applied: log.actions(),
            input_vertices: log.input_vertices,
            input_faces: log.input_faces,
            duplicate_faces: log.duplicate_faces,
            components: log.components,
            component_faces_dropped: log.component_faces_dropped,
            component_vertices_dropped: log.component_vertices_dropped,
            flipped_faces: log.flipped_faces,
            unreferenced_vertices: log.unreferenced_vertices,
            vertex_map: serde_json::json!({
                "repaired_to_input": log.vertex_to_input.len(),
                "input_to_repaired": log.input_to_vertex.len(),
            }),
            face_map: serde_json::json!({ "repaired_to_input": log.face_to_input.len() }),
        }
    }
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

/// `value` as JSON (`null` if it cannot be: the library reports are plain data).
pub fn to_value(value: &impl Serialize) -> Value {
    serde_json::to_value(value).unwrap_or(Value::Null)
}

/// `value` as a JSON object (empty if it is not one).
pub fn object(value: &impl Serialize) -> Map<String, Value> {
    match to_value(value) {
        Value::Object(m) => m,
        _ => Map::new(),
    }
}
