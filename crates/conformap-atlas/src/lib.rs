//! Texture atlases for conformap: charts of any mesh packed without overlap into the unit
//! square.
//!
//! An atlas is a set of charts (flat, fold-free layouts of pieces of a surface, each a disk)
//! placed side by side in the texture square `[0,1]²` with one texel density and a margin
//! between them. This crate owns that placement; the charts come from the flattening code
//! of `conformap-disk`. Packing depends on nothing of the workspace (charts are plain
//! points); cones on `conformap-mesh` and `conformap-operators`. It never reads or writes
//! files.
//!
//! # Contents
//! - [`build_atlas`] → [`Atlas`]: the whole atlas of a triangle soup (every component
//!   charted, self-overlapping charts split, everything packed), with its [`AtlasReport`].
//! - [`chart`]: one component's chart ([`chart_component`]), its quality, and the
//!   distortion polish ([`chart::polish()`], [`AtlasOptions::polish`]).
//! - [`pack_charts`] / [`pack_outlined`] → [`Packing`]: the charts scaled by one common
//!   factor (the largest that fits), placed both as rectangles (each turned to its
//!   smallest bounding rectangle, a skyline packer) and by their outlines (a profile
//!   packer: each chart dropped onto the others where it rests lowest, its bays taking
//!   their spikes), the better kept; configured by [`PackOptions`] (resolution, margin in
//!   texels, rotation). [`build_atlas`] also cuts a chart that sets the scale alone at a
//!   neck of its outline when the parts pack at least 3 % denser.
//! - [`cones`]: the cone metric of a set of cone singularities ([`ConeMetric`], one
//!   factorization) and their automatic placement with the least area spread
//!   ([`place_cones`]).
//! - [`hull`]: convex hull and the minimum-area bounding rectangle (rotating calipers).
//! - The options beyond placement: cones as given ([`chart_given`],
//!   [`build_atlas_with_cones`]) or as many as reach an area spread ([`chart_auto`]),
//!   charts kept unpacked ([`Layout`]) or scaled per component ([`ChartScale`]), and
//!   non-manifold input split into a manifold one ([`split_non_manifold`]).
//! - [`AtlasError`]: what cannot be packed.
//!
//! # Example
//! ```
//! use conformap_atlas::{pack_charts, PackOptions};
//! // three charts: a 2 × 1 rectangle, a unit square and a thin triangle
//! let charts = vec![
//!     vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]],
//!     vec![[5.0, 5.0], [6.0, 5.0], [6.0, 6.0], [5.0, 6.0]],
//!     vec![[0.0, 0.0], [3.0, 0.0], [0.0, 0.5]],
//! ];
//! let packing = pack_charts(&charts, &PackOptions::default())?;
//! for (chart, placement) in charts.iter().zip(&packing.charts) {
//!     for &p in chart {
//!         let [u, v] = placement.apply(p);
//!         assert!((0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v));
//!     }
//! }
//! // their rectangles pack best as a 3 × 1.5 block: 3.75 / 9 of the square
//! assert!(packing.efficiency > 0.41);
//! # Ok::<(), conformap_atlas::AtlasError>(())
//! ```

mod build;
pub mod chart;
mod component;
pub mod cones;
mod error;
pub mod hull;
mod layout;
mod neck;
pub mod nonmanifold;
mod pack;
mod polish_mode;
mod profile;
mod skyline;
mod summary;

pub use build::{
    build_atlas, build_atlas_of_mesh, build_atlas_with_cones, split_components, Atlas,
    AtlasOptions, AtlasReport, AtlasTimings, AutoConesReport, ConeEntry, SEAMLESS_TOLERANCE,
};
pub use chart::given::{chart_auto, chart_given, AutoCones, MAX_AUTO_CONES};
pub use chart::seamless::{chart_seamless, quantize_cones, seam_rigidity, SeamRigidity};
pub use chart::{chart_closed, chart_component, chart_quality, Chart, ChartQuality};
pub use component::ComponentChart;
pub use cones::{place_cones, Cone, ConeMetric, ConeOptions, ConeSet};
pub use error::AtlasError;
pub use layout::{keep_in_rows, ChartScale, Layout};
pub use nonmanifold::{split_non_manifold, NonManifoldSplit, SplitReport};
pub use pack::{
    pack_charts, pack_outlined, ChartPlacement, PackOptions, Packing, PROFILE_CELL, PROFILE_REFINE,
    PROFILE_REFINE_STEPS, PROFILE_STEPS,
};
pub use polish_mode::{Polish, POLISH_AUTO_SPREAD, POLISH_AUTO_VERTICES};
pub use summary::{atlas_peak_bytes, atlas_peak_bytes_with};
