//! Cone singularities: the cone metric of a set of cones and the automatic placement of
//! cones with the least area distortion.

mod metric;
mod placement;

pub use metric::ConeMetric;
pub(crate) use placement::greedy_count;
pub use placement::{
    best_defects, place_cones, Cone, ConeOptions, ConeSet, CONE_SPACING, MAX_CONE_ANGLE,
    MIN_CONE_ANGLE, SLIDE_TRIALS,
};
