//! Holomorphic 1-forms of surfaces of genus ≥ 1 and the global conformal parameterization
//! they induce (Jin, Wang, Yau, Gu 2004, §3.1, building on Gu and Yau 2003).
//!
//! Module map:
//! - `blocked.rs`: tall-and-skinny products over the edges or faces, block by block.
//! - `dense.rs`: small dense linear algebra (inverse, Jacobi eigen, matrix functions).
//! - `cohomology.rs`: the closed basis dual to the tree–cotree generators, `∫ α ∧ β` and
//!   `∫ α ∧ *β`.
//! - `harmonic.rs`: harmonic projection, one factorization for all `2g` forms (two of half
//!   the size on a double covering).
//! - `conjugate.rs`: the Gu–Yau wedge system and its nearest exact complex structure
//!   ([`ConjugateMethod`]).
//! - `periods.rs`: holomorphic basis, period matrix, bilinear residual, τ
//!   ([`reduce_modulus`]).
//! - `layout.rs`: integration over the fundamental domain, one UV per corner.
//! - `zeros.rs`: zeros by winding ([`ZeroReport`]), conformal factor (Eq. 12).
//! - `quality.rs`: angle and area distortion, the scale-free uniformity energy
//!   ([`LayoutMetrics`]).
//! - `optimal/`: the optimal form ([`Objective`]: uniform, least uniform, emphasized area,
//!   zero allocation) over the coefficient sphere.
//! - `options.rs`, `global_map.rs`, `pipeline.rs`: the options, the result [`GlobalMap`], and
//!   the entry point [`global_map`] with its steps.
//! - `seamed.rs`: [`SeamedLayout`], the layout as a file writes it (per-corner texture
//!   coordinates in the unit square).

mod blocked;
mod cohomology;
mod conjugate;
mod dense;
mod global_map;
mod harmonic;
mod layout;
mod optimal;
mod options;
mod periods;
mod pipeline;
mod quality;
mod seamed;
mod zeros;

#[cfg(test)]
mod tests;

pub use conjugate::ConjugateMethod;
pub use global_map::{GlobalMap, GlobalTimings};
pub use optimal::{
    EmphasisReport, FormSearchOptions, Objective, ObjectiveReport, UniformSearch,
    ZeroAllocationReport, ZeroTarget, DEFAULT_SEED, DEFAULT_STARTS, GRADIENT_TOL,
    MAX_NEWTON_ITERATIONS, OPTIMUM_MATCH_REL,
};
pub use options::GlobalMapOptions;
pub use periods::{reduce_modulus, MODULUS_MAX_STEPS};
pub use pipeline::global_map;
pub(crate) use pipeline::global_map_ranked;
pub use quality::LayoutMetrics;
pub use seamed::SeamedLayout;
pub use zeros::{Zero, ZeroReport};
