//! The result of [`crate::planar_map_metrics`]: the `"metrics"` object of the JSON report.

use serde::{Deserialize, Serialize};

pub use conformap_operators::LoopCircle;

use crate::summary::{AngleStats, LogRatioStats, SummaryStats};

/// A histogram: `counts[k]` values fell in `[edges_deg[k], edges_deg[k + 1])` (the last bin
/// is closed).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Histogram {
    /// Bin edges in degrees, `counts.len() + 1` of them; see
    /// [`crate::ANGLE_HISTOGRAM_EDGES_DEG`].
    pub edges_deg: Vec<f64>,
    /// Number of values per bin.
    pub counts: Vec<u64>,
}

/// Quality metrics of a planar map; the first ten fields are the `"metrics"` object of the
/// report schema in `docs/design.md`, with the same names. Every number is finite.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct MapMetrics {
    /// `E_C = E_D − A` (CEM Eq. 7) of the (orientation-fixed) map.
    pub conformal_energy: f64,
    /// `E_D = ½ fᴴ L f` (CEM Eq. 5), cotangent weights of the mesh.
    pub dirichlet_energy: f64,
    /// `A`, the signed image area of CEM Eq. 8 (boundary loops; faces for a closed mesh) of
    /// the orientation-fixed map: never negative when the orientation is fixed.
    pub image_area: f64,
    /// Corner angle distortion, degrees.
    pub angle_distortion_deg: AngleStats,
    /// `|μ|`, `μ = f_z̄ / f_z` per face.
    pub beltrami_abs: SummaryStats,
    /// Per-face log area ratio.
    pub area_distortion_log: LogRatioStats,
    /// Faces whose image has negative signed area (after the orientation fix).
    pub flipped_faces: usize,
    /// Faces whose image area is exactly zero (collinear or coincident image vertices).
    pub degenerate_faces: usize,
    /// Largest `residual_max` over [`Self::boundary_circles`] (0 for a closed mesh).
    pub circle_residual_max: f64,
    /// Whether the map as given was mirrored (negative image area) and was conjugated
    /// before scoring.
    pub orientation_reversed: bool,
    /// Faces in the per-face statistics: all faces but the degenerate ones.
    pub measured_faces: usize,
    /// Histogram of the corner angle distortion, degrees.
    pub angle_histogram: Histogram,
    /// Index of the outer loop (`None` for a closed mesh).
    pub outer_loop: Option<usize>,
    /// One entry per boundary loop, in loop order.
    pub boundary_circles: Vec<LoopCircle>,
}
