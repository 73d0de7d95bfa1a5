//! What the optimal-form search is asked for ([`Objective`]) and what it reports
//! ([`ObjectiveReport`], [`ZeroAllocationReport`]).

use serde::{Deserialize, Serialize};

use crate::forms::optimal::eigen::EmphasisReport;
use crate::forms::optimal::search::UniformSearch;

/// Which holomorphic 1-form [`crate::global_map`] lays out (ignored when
/// [`crate::GlobalMapOptions::form`] names a basis form).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub enum Objective {
    /// The most uniform form: the minimum of the scale-free uniformity energy
    /// `Σ_f (a_f/Σa − S_f/ΣS)²` (Eq. 6–7) over the coefficient sphere, by multistart Newton.
    /// The default.
    #[default]
    Uniform,
    /// The least uniform form (its maximum), as the paper's figures compare them.
    LeastUniform,
    /// The basis form of lowest uniformity energy (no search; issue 15's default).
    BestBasisForm,
    /// The form giving `faces` (0-based faces of the input) the largest share of the
    /// parameter area (Eq. 8–9), or the smallest when `maximize` is false.
    Emphasize {
        /// The region's faces.
        faces: Vec<usize>,
        /// Maximize (emphasize) or minimize (de-emphasize) the region's share.
        maximize: bool,
    },
    /// The form with zeros at the given input vertices (Eq. 13–14): for at most `g − 1`
    /// targets the most uniform form among those vanishing at every target (exact, see
    /// `targets.rs`); beyond, the least `Σ |ω(v_i)|²` under the area constraint (the
    /// compromise). Needs genus ≥ 2.
    Zeros {
        /// Target vertices (0-based, of the input).
        vertices: Vec<usize>,
    },
}

impl Objective {
    /// The objective's name as the CLI spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::LeastUniform => "least-uniform",
            Self::BestBasisForm => "basis",
            Self::Emphasize { maximize: true, .. } => "emphasize",
            Self::Emphasize {
                maximize: false, ..
            } => "de-emphasize",
            Self::Zeros { .. } => "zeros",
        }
    }
}

/// One zero-allocation target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct ZeroTarget {
    /// The target vertex (input numbering).
    pub vertex: usize,
    /// Edge rings from the target to the nearest zero's vertex (`None`: the form has no
    /// zero).
    pub ring_distance: Option<usize>,
    /// That zero's vertex.
    pub nearest_zero: Option<usize>,
    /// `|ω(v)|` at the target: the mean of `|φ(e)|/|e|` over its edges, for the laid-out
    /// form (area normalized to the surface's), the paper's estimate.
    pub residual: f64,
}

/// The zero-allocation result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct ZeroAllocationReport {
    /// Per target.
    pub targets: Vec<ZeroTarget>,
    /// Whether an exact solution exists in theory (`n ≤ g − 1` distinct targets).
    pub exact_expected: bool,
    /// `exact`: the most uniform form among those vanishing at every target (`n ≤ g − 1`;
    /// [`ObjectiveReport::search`] is that search); `least-squares`: the form of least
    /// `Σ |ω(v_i)|²` per unit parameter area (more targets than a form has free zeros).
    pub method: String,
    /// The median `|ω(v)|` over the input's vertices (the residuals' yardstick).
    pub median_stretch: f64,
    /// `Σ |ω(v_i)|²` of the chosen form per unit parameter area, `ω(v)` the fitted value of
    /// `targets.rs` (rounding level for `exact`).
    pub eigenvalue: f64,
}

/// What the objective chose and what it measured.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct ObjectiveReport {
    /// [`Objective::name`].
    pub objective: String,
    /// The coefficients `λ_k` of the laid-out form over the holomorphic basis, scaled so
    /// that the user's faces have parameter area `Σ λᵀ Q_f λ = 1`.
    pub coefficients: Vec<f64>,
    /// The scale-free uniformity energy of the chosen form over the user's faces.
    pub uniformity: f64,
    /// The uniformity energy of each basis form.
    pub basis_uniformity: Vec<f64>,
    /// The search of the objective (`Uniform`, `LeastUniform`, and `Zeros` with an exact
    /// solution: the search within the forms vanishing at the targets); `None` for genus 1
    /// (nothing to choose) and the other objectives.
    pub search: Option<UniformSearch>,
    /// The opposite extreme's search when [`crate::forms::FormSearchOptions::compare`].
    pub opposite: Option<UniformSearch>,
    /// Largest over smallest uniformity energy when both extremes are known (1 for genus 1).
    pub max_min_ratio: Option<f64>,
    /// `Emphasize` only.
    pub emphasis: Option<EmphasisReport>,
    /// `Zeros` only (filled after the layout).
    pub zeros: Option<ZeroAllocationReport>,
    /// How the search evaluated the energy: `moments` (precomputed second moments of the
    /// area forms, `O((2g)⁴)` per Newton step) or `direct` (sums over the faces,
    /// `O(F (2g)²)` per Newton step; on large meshes with a coarse level first, see
    /// `faces::COARSE_FACES`), whichever costs less for the search's starts; empty when
    /// there was no search.
    #[serde(default)]
    pub energy_model: String,
    /// Wall-clock milliseconds: the area forms, then the objective's solve.
    pub products_ms: f64,
    /// See [`Self::products_ms`].
    pub solve_ms: f64,
}
