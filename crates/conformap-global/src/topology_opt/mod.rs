//! Topological optimization (Jin, Wang, Yau, Gu 2004, §3.5): conformal maps shrink
//! exponentially along tubes (fingers, ears, legs), and neither a Möbius transform nor a
//! choice of holomorphic form undoes it; cutting a short slit at each extreme point, double
//! covering the slit surface and mapping it by its most uniform form does.
//!
//! Module map:
//! - `options.rs`: [`TopologyOptOptions`] and its documented defaults (slit length 4 % of
//!   the bounding-box diagonal, 16 slits, patience 3, extreme thresholds).
//! - `clusters.rs`: the per-vertex area ratio (the discrete `λ⁻²` of Eq. 12) and the
//!   extreme clusters, their centres and the nearest vertices.
//! - `run.rs`: the greedy loop [`topology_opt`] → [`TopologyOpt`] (every step, the best
//!   layout seen, starting map included: the uniform-Möbius sphere map of a closed genus-0
//!   surface, the uniform-Möbius disk map of a disk, the most uniform form otherwise).
//!
//! The slits themselves (paths, cutting) are `conformap_mesh::SlitPlanner`'s.

mod clusters;
mod options;
mod run;

pub use options::{
    TopologyOptOptions, DEFAULT_EXTREME_AREA_FRACTION, DEFAULT_MAX_EXTREME_AREA_RATIO,
    DEFAULT_MAX_SLITS, DEFAULT_PATIENCE, DEFAULT_SLIT_LENGTH, TOPOLOGY_BASIS_STARTS,
    TOPOLOGY_RANDOM_STARTS,
};
pub use run::{
    topology_opt, BestLayout, SlitRecord, TopologyOpt, TopologyStep, CENTRE_CANDIDATES,
    FIRST_STEP_RELAXATIONS,
};
