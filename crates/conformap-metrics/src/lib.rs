//! Quality metrics of planar conformal maps: conformal energy, angle distortion, Beltrami
//! coefficient, area distortion, flips.
//!
//! Depends on `conformap-mesh` (the validated [`conformap_mesh::TriMesh`]) and
//! `conformap-operators` (the per-face cotangents and angles behind its Laplacian, so `E_D`
//! here is exactly the solvers' `½ fᴴ L f`). Never solves anything, assembles no matrix and
//! touches no file: it judges a map given as one [`num_complex::Complex64`] per vertex,
//! whoever computed it.
//!
//! # Contents
//! - [`planar_map_metrics`] → [`MapMetrics`]: everything, as the `"metrics"` object of the
//!   JSON report (`serde::Serialize`), configured by [`MetricsOptions`].
//! - Building blocks for solvers: [`dirichlet_energy`] (CEM Eq. 5), [`image_area`] (Eq. 8),
//!   [`conformal_energy`] (Eq. 7).
//! - Per face, for pictures and custom statistics: [`face_distortions`] /
//!   [`face_distortion`] → [`FaceDistortion`] (corner angle differences, `|μ|`, areas), and
//!   [`isometric_chart`] to judge maps into 3D (a sphere map's chord triangles) the same way.
//! - Overlap of a layout: [`raster_overlap`] (texels covered twice on an `N × N` raster,
//!   as texture atlases are judged) and [`boundary_crossings`] (exact: a flip-free layout
//!   whose boundary image crosses nowhere is one-to-one).
//! - [`MetricsError`]: a map that cannot be judged (wrong length, NaN at a vertex, …).
//!
//! # Example
//! ```
//! use conformap_metrics::{planar_map_metrics, MetricsOptions};
//! use num_complex::Complex64;
//! // a regular hexagon around its centre, mapped by the similarity z ↦ (0.3 + 0.4i) z
//! let mut positions = vec![[0.0, 0.0, 0.0]];
//! positions.extend((0..6).map(|k| {
//!     let t = std::f64::consts::PI / 3.0 * k as f64;
//!     [t.cos(), t.sin(), 0.0]
//! }));
//! let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
//! let mesh = conformap_mesh::TriMesh::try_new(positions, faces)?;
//! let map: Vec<Complex64> = mesh.positions().iter()
//!     .map(|p| Complex64::new(0.3, 0.4) * Complex64::new(p[0], p[1]))
//!     .collect();
//! let m = planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT)?;
//! assert!(m.conformal_energy.abs() < 1e-14);
//! assert!(m.angle_distortion_deg.max < 1e-12);
//! assert_eq!(m.flipped_faces, 0);
//! // the boundary lies on a circle of radius ½, not on the unit circle
//! assert!((m.circle_residual_max - 0.5).abs() < 1e-15);
//! assert!((m.image_area - 0.25 * 1.5 * 3f64.sqrt()).abs() < 1e-15);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod circles;
mod cross_ratio;
mod energy;
mod error;
mod face;
mod metrics;
mod options;
mod overlap;
mod per_face;
mod report;
mod stats;
mod summary;

pub use cross_ratio::{cross_ratio_distortion, cross_ratio_logs};
pub use energy::{conformal_energy, dirichlet_energy, image_area};
pub use error::{MetricsError, MAP_ABS_LIMIT};
pub use face::BELTRAMI_ABS_CAP;
pub use metrics::{corner_map_metrics, planar_map_metrics};
pub use options::{MetricsOptions, OuterCircle};
pub use overlap::{
    boundary_crossings, raster_overlap, segments_meet, RasterFrame, RasterOverlap,
    OVERLAP_RESOLUTION,
};
pub use per_face::{face_distortion, face_distortions, isometric_chart, FaceDistortion};
pub use report::{Histogram, LoopCircle, MapMetrics};
pub use stats::ANGLE_HISTOGRAM_EDGES_DEG;
pub use summary::{
    abs_log_stats, angle_stats, log_ratio_stats, summary_stats, AbsLogStats, AngleStats,
    LogRatioStats, SummaryStats,
};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
