//! The JSON report (schema in design.md: stable field names).

use std::path::Path;

use conformap_mesh::TriMesh;
use serde::Serialize;

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
