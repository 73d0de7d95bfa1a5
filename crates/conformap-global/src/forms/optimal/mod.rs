//! The optimal holomorphic 1-form (Jin et al. 2004, §3.2–3.3, §3.6): which combination
//! `φ = Σ λ_k φ_k` of the `2g` basis forms to lay out.
//!
//! Module map:
//! - `faces.rs`: the whitened basis forms' values on each face's edges, and the energy,
//!   gradient and Hessian summed straight over the faces from them (`O(F (2g)²)` per
//!   Hessian; high genus, few starts).
//! - `products.rs`: per-face `2g × 2g` area forms, whitened by the total area form (the
//!   emphasized area and the zero allocation).
//! - `moments.rs`: the second moments of the area forms, so that the energy and its
//!   derivatives cost `O((2g)⁴)` whatever the face count (low genus, many starts).
//! - `uniform.rs`: the scale-free uniformity energy (Eq. 6–7), analytic gradient and
//!   Hessian, saddle-free Newton on the coefficient sphere.
//! - `search.rs`: the seeded multistart ([`FormSearchOptions`], [`UniformSearch`]).
//! - `targets.rs`: zero allocation as linear conditions (the form's value at a vertex),
//!   the subspace of forms vanishing at the targets.
//! - `eigen.rs`: the emphasized area (Eq. 8–9) and the zero allocation (Eq. 13–14) as
//!   symmetric eigenproblems ([`EmphasisReport`]), edge-ring distances.
//! - `objective.rs`: [`Objective`], [`ObjectiveReport`], [`ZeroAllocationReport`].
//! - `choose.rs`: the dispatch, one named step per objective, and the zero report's
//!   completion once the layout's zeros are known.
//! - `aggregates.rs`: the sums over faces every energy model returns.

mod aggregates;
mod choose;
mod eigen;
mod faces;
mod moments;
mod objective;
mod products;
mod search;
mod targets;
mod uniform;

#[cfg(test)]
mod real_tests;
#[cfg(test)]
mod tests;

pub(crate) use choose::{choose, finish_zeros, Surface};
pub use eigen::EmphasisReport;
pub use objective::{Objective, ObjectiveReport, ZeroAllocationReport, ZeroTarget};
pub use search::{
    FormSearchOptions, UniformSearch, DEFAULT_SEED, DEFAULT_STARTS, OPTIMUM_MATCH_REL,
};
pub use uniform::{GRADIENT_TOL, MAX_NEWTON_ITERATIONS};
