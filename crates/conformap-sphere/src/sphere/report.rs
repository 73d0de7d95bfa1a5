//! Reports of the sphere map (serde-serializable, stable field names).

use serde::{Deserialize, Serialize};

/// Wall-clock milliseconds by stage.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Timings {
    /// Assembling the Laplacian and its blocks.
    pub assemble: f64,
    /// Sparse factorizations (symbolic + numeric).
    pub factor: f64,
    /// Everything else: solves, projections, per-stage quality checks.
    pub solve: f64,
    /// Total.
    pub total: f64,
}

/// Quality after one stage of [`crate::sphere_map`].
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct StageRecord {
    /// What the stage did.
    pub stage: String,
    /// Mean chord-angle distortion (degrees), as in [`crate::SphereMetrics`].
    pub mean_angle_distortion_deg: f64,
    /// Faces inverted on the sphere.
    pub flipped_faces: usize,
}

/// How a sphere map was computed.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct SphereReport {
    /// `"angenent+stereographic-corrections"`.
    pub method: String,
    /// The face carrying Angenent's dipole.
    pub source_face: usize,
    /// The vertex pinned to 0 in Angenent's solve.
    pub pinned_vertex: usize,
    /// Whether Angenent's map was mirrored to make the chord triangles counter-clockwise.
    pub conjugated: bool,
    /// Vertices kept fixed in each correction solve.
    pub fixed_vertices: usize,
    /// Corrections kept (the returned map is the output of stage `best_stage`: the last
    /// correction kept, or the Möbius centring after it).
    pub corrections: usize,
    /// Every stage tried, in order: Angenent's map, then each correction (the last one may
    /// have been rejected).
    pub stages: Vec<StageRecord>,
    /// Index into `stages` of the returned map.
    pub best_stage: usize,
    /// Sparse factorizations done.
    pub factorizations: usize,
    /// Relative residual `‖L_uu f − b‖∞ / ‖b‖∞` of Angenent's solve.
    pub residual: f64,
    /// Timings.
    pub timings_ms: Timings,
    /// What the flip-free guard did, when the cotangent Laplacian's map inverted a face
    /// (`None`: it did not, and nothing was re-solved).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub guard: Option<String>,
}
