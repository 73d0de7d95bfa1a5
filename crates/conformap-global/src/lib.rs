//! Global conformal maps of surfaces of genus g ≥ 1 for conformap: holomorphic 1-form
//! bases, the optimal form, its zeros, topological optimization.
//!
//! Depends on `conformap-mesh` (validated meshes, homology, cuts, slits),
//! `conformap-operators` (cotangent Laplacian, sparse Cholesky, vector primitives),
//! `conformap-disk` (the starting disk map of a topological optimization),
//! `conformap-metrics` (summary statistics) and `conformap-sphere` (the double covering of
//! surfaces with boundary, the sphere maps and Möbius optimizations a topological
//! optimization starts from); never touches files, never prints, and owns no genus-0 map
//! (those are `conformap-sphere`'s and `conformap-disk`'s).
//!
//! # Contents
//! - **Global maps by holomorphic 1-forms** (Jin et al. 2004, §3.1–3.3, §3.6): [`global_map`]
//!   → [`GlobalMap`] (homology, harmonic and holomorphic bases, periods, τ, the chosen
//!   form laid out over the fundamental domain, its [`Zero`]s, conformal factor and
//!   [`LayoutMetrics`]), configured by [`GlobalMapOptions`] with an [`Objective`] (best
//!   basis form, most or least uniform, emphasized area, zeros at given vertices) and
//!   [`FormSearchOptions`]; [`GlobalMap::seamed_layout`] → [`SeamedLayout`].
//! - **Topological optimization** (§3.5): [`topology_opt`] slits the surface (closed
//!   genus 0, a disk, or higher genus) at the extreme points of its map and maps the slit
//!   surface by its most uniform holomorphic form, greedily, returning the best layout seen
//!   ([`TopologyOpt`], [`TopologyOptOptions`]).
//! - [`GlobalError`]: the one error type (genus-0 failures inside it are
//!   [`GlobalError::Sphere`]).
//!
//! # Example
//! ```
//! use conformap_global::{global_map, GlobalMapOptions};
//! # let torus = conformap_mesh::doc_torus();
//! // `torus`: a closed genus-1 mesh (a coarse torus of revolution, radii 2 and 1)
//! let map = global_map(&torus, &GlobalMapOptions::DEFAULT)?;
//! assert_eq!(map.genus, 1);
//! assert!(map.seam_residual < 1e-12); // across a seam: a pure translation
//! assert_eq!(map.zeros.multiplicity_sum, 0); // 2g − 2 zeros on a torus
//! assert!(map.metrics.image_area > 0.0);
//! # Ok::<(), conformap_global::GlobalError>(())
//! ```

mod error;
mod forms;
mod summary;
mod topology_opt;

pub use error::GlobalError;
pub use forms::{
    global_map, reduce_modulus, ConjugateMethod, EmphasisReport, FormSearchOptions, GlobalMap,
    GlobalMapOptions, GlobalTimings, LayoutMetrics, Objective, ObjectiveReport, SeamedLayout,
    UniformSearch, Zero, ZeroAllocationReport, ZeroReport, ZeroTarget, DEFAULT_SEED,
    DEFAULT_STARTS, GRADIENT_TOL, MAX_NEWTON_ITERATIONS, MODULUS_MAX_STEPS, OPTIMUM_MATCH_REL,
};
pub use summary::{global_map_peak_bytes, topology_opt_peak_bytes};
pub use topology_opt::{
    topology_opt, BestLayout, SlitRecord, TopologyOpt, TopologyOptOptions, TopologyStep,
    CENTRE_CANDIDATES, DEFAULT_EXTREME_AREA_FRACTION, DEFAULT_MAX_EXTREME_AREA_RATIO,
    DEFAULT_MAX_SLITS, DEFAULT_PATIENCE, DEFAULT_SLIT_LENGTH, FIRST_STEP_RELAXATIONS,
    TOPOLOGY_BASIS_STARTS, TOPOLOGY_RANDOM_STARTS,
};

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
