//! What [`super::flatten`] returns: the map, the boundary data and the report.

use conformap_metrics::MapMetrics;
use num_complex::Complex64;
use serde::Serialize;

/// Wall-clock milliseconds of the steps of [`super::flatten`].
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
#[non_exhaustive]
pub struct FlattenTimings {
    /// Filling holes, assembling `L` and factoring `L_II`.
    pub setup: f64,
    /// The boundary conversion (Dirichlet ↔ Neumann), including the factorization of the
    /// pinned Laplacian when a Neumann problem is solved.
    pub boundary: f64,
    /// Integrating and closing the boundary curve.
    pub curve: f64,
    /// The interior extension (and any re-solve of a folded interior).
    pub interior: f64,
    /// The quality metrics and the boundary self-intersection check.
    pub metrics: f64,
    /// The whole call.
    pub total: f64,
}

/// The report of a flattening (serializes to the `"flatten"` object of a JSON report; its
/// [`Self::metrics`] and [`Self::timings_ms`] are the report's own `metrics` and
/// `timings_ms`, so they are not serialized here).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct FlattenReport {
    /// The boundary mode: `free`, `scale`, `angles`, `circle`, `rectangle` or `polygon`.
    pub boundary: &'static str,
    /// The interior variant that produced the map: `harmonic` or `conjugate`.
    pub interior: &'static str,
    /// The operator of the interior solve: `cotan`, `intrinsic-delaunay` or `mean-value`.
    pub interior_operator: &'static str,
    /// Faces the first interior solve folded, before the fallback operators.
    pub flipped_before_fallback: usize,
    /// Corner vertices (rectangle, polygon), in boundary order; empty otherwise.
    pub corners: Vec<u32>,
    /// `|Σ l̃ T|` of the integrated curve before closing, relative to its perimeter.
    pub closure_gap: f64,
    /// `|Σ l* T|` after closing, relative to the perimeter.
    pub closure_residual: f64,
    /// Largest relative change of a boundary edge length made by the closing.
    pub closure_max_length_change: f64,
    /// Smallest boundary scale factor `u` (lengths multiply by `e^u`).
    pub boundary_u_min: f64,
    /// Largest boundary scale factor.
    pub boundary_u_max: f64,
    /// Rectangle only: the conformal modulus, width (first corner to second) over height.
    pub conformal_aspect: Option<f64>,
    /// Rectangle only: the aspect of the map (the asked one, or the conformal modulus).
    pub aspect: Option<f64>,
    /// Rectangle with an asked aspect: the cost of reaching it, the dilatation
    /// `K = max(a/M, M/a) ≥ 1` of the affine stretch applied to the conformal rectangle
    /// (the least possible largest dilatation of any map between the two rectangles:
    /// Grötzsch); the Beltrami coefficient is `(K − 1)/(K + 1)` on every face.
    pub aspect_dilatation: Option<f64>,
    /// Pairs of non-adjacent boundary edges of the map that cross or touch (0: every
    /// boundary curve of the image is simple).
    pub boundary_touches: usize,
    /// No face with non-positive image area (besides the [`Self::straight_side_ears`]) and
    /// no boundary touching itself: for a disk, the map is then one to one (an
    /// overlap-free image).
    pub overlap_free: bool,
    /// Faces of three consecutive boundary vertices inside one straight side of a rectangle
    /// or polygon: their image is a segment of the side by construction (degenerate, never
    /// flipped; `metrics.degenerate_faces` counts them). Refine such ears away for a map
    /// without degenerate faces.
    pub straight_side_ears: usize,
    /// Holes filled with centroid fans before flattening (several boundary loops: the
    /// longest loop is the outer boundary; the holes take the shape the map gives them).
    pub filled_holes: usize,
    /// Which Laplacian the solves used, and why.
    pub laplacian: String,
    /// Quality of the map (E_C, angle and area distortion, flipped faces…), judged on the
    /// input mesh by `conformap-metrics`; `area_distortion_log.sd` is the area spread
    /// (all zero when [`crate::flatten::FlattenOptions::measure`] is off).
    #[serde(skip_serializing)]
    pub metrics: MapMetrics,
    /// Step timings.
    #[serde(skip_serializing)]
    pub timings_ms: FlattenTimings,
}

/// The result of [`super::flatten`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Flattening {
    /// The flat map, one point per vertex of the input, in its vertex order.
    pub map: Vec<Complex64>,
    /// The boundary scale factors `(vertex, u)` along the outer loop, in loop order.
    pub boundary_scale: Vec<(u32, f64)>,
    /// The closure residual (see [`FlattenReport::closure_residual`]).
    pub closure_residual: f64,
    /// Corner vertices used (rectangle, polygon), in boundary order.
    pub corners: Vec<u32>,
    /// Step timings (also in the report).
    pub timings: FlattenTimings,
    /// The report.
    pub report: FlattenReport,
}
