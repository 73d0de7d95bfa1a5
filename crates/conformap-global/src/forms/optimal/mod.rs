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
//! - `mod.rs` (here): [`Objective`], [`ObjectiveReport`], the dispatch.

mod eigen;
mod faces;
mod moments;
mod products;
mod search;
mod targets;
mod uniform;

#[cfg(test)]
mod real_tests;
#[cfg(test)]
mod tests;

use conformap_mesh::{EdgeIndex, TriMesh};
use serde::{Deserialize, Serialize};

pub use eigen::EmphasisReport;
pub use search::{
    FormSearchOptions, UniformSearch, DEFAULT_SEED, DEFAULT_STARTS, OPTIMUM_MATCH_REL,
};
pub use uniform::{GRADIENT_TOL, MAX_NEWTON_ITERATIONS};

use crate::forms::cohomology::Cochain;
use crate::forms::optimal::faces::FaceForms;
use crate::forms::optimal::products::AreaProducts;
use crate::forms::optimal::uniform::EnergyModel;
use crate::forms::periods::holomorphic_basis;
use crate::forms::zeros::{vertex_stretch, ZeroReport};
use crate::GlobalError;

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
    /// The opposite extreme's search when [`FormSearchOptions::compare`].
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

/// Inputs of [`choose`].
pub(crate) struct Surface<'a> {
    pub mesh: &'a TriMesh,
    pub edges: &'a EdgeIndex,
    /// The real harmonic forms and the conjugation `Λ` (row-major): the holomorphic basis
    /// is `a_k = h_k + i Σ_j Λ_jk h_j`.
    pub harmonic: &'a [Cochain],
    pub lambda: &'a [f64],
    pub input_faces: usize,
    pub input_vertices: usize,
}

fn ms(t: std::time::Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Picks the coefficients for `objective`. `forced`: a basis form named by the user.
pub(crate) fn choose(
    s: &Surface<'_>,
    objective: &Objective,
    forced: Option<usize>,
    search: &FormSearchOptions,
) -> Result<ObjectiveReport, GlobalError> {
    let t = std::time::Instant::now();
    let ff = FaceForms::from_harmonic(s.mesh, s.edges, s.harmonic, s.lambda, s.input_faces)?;
    let products_ms = ms(t);
    let t = std::time::Instant::now();
    let n = ff.n;
    let basis_mu: Vec<Vec<f64>> = (0..n).map(|k| ff.whiten(&unit_vector(n, k))).collect();
    let basis_uniformity = ff.basis_energy.clone();
    let best_basis = (0..n)
        .min_by(|&a, &b| basis_uniformity[a].total_cmp(&basis_uniformity[b]))
        .unwrap_or(0);
    let (mut search_out, mut opposite, mut ratio, mut emphasis, mut zeros) =
        (None, None, None, None, None);
    let mut energy_model = String::new();
    let mu = match (forced, objective) {
        (Some(k), _) => basis_mu[k].clone(),
        (None, Objective::BestBasisForm) => basis_mu[best_basis].clone(),
        (None, Objective::Uniform | Objective::LeastUniform) if n == 2 => {
            ratio = Some(1.0);
            basis_mu[0].clone()
        }
        (None, Objective::Uniform | Objective::LeastUniform) => {
            let maximize = matches!(objective, Objective::LeastUniform);
            let runs = if search.compare { 2 } else { 1 };
            let basis_starts = search.basis_starts.map_or(n, |k| k.clamp(1, n));
            let starts = runs * (basis_starts + search.starts);
            let (found, other) = if faces::use_moments(ff.faces(), n, starts) {
                energy_model = "moments".to_owned();
                let moments = moments::Moments::from_faces(&ff);
                search_pair(
                    &moments,
                    &[],
                    (&basis_mu, &basis_uniformity),
                    maximize,
                    search,
                )
            } else {
                let strides = faces::coarse_strides(ff.faces());
                let samples: Vec<FaceForms> = strides.iter().map(|&s| ff.sample(s)).collect();
                let levels: Vec<&dyn EnergyModel> =
                    samples.iter().map(|s| s as &dyn EnergyModel).collect();
                energy_model = match strides.as_slice() {
                    [] => "direct".to_owned(),
                    _ => format!(
                        "direct, coarse levels {} of the faces",
                        strides
                            .iter()
                            .map(|s| format!("1/{s}"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                };
                search_pair(
                    &ff,
                    &levels,
                    (&basis_mu, &basis_uniformity),
                    maximize,
                    search,
                )
            };
            if let Some(other) = other {
                let (hi, lo) = if maximize {
                    (found.energy, other.energy)
                } else {
                    (other.energy, found.energy)
                };
                ratio = Some(hi / lo);
                opposite = Some(other);
            }
            let mu = found.mu.clone();
            search_out = Some(found);
            mu
        }
        (None, Objective::Emphasize { faces, maximize }) => {
            let mask = crate::region_mask(s.input_faces, faces)?;
            let p = AreaProducts::from_faces(&ff);
            let (mu, report) = eigen::emphasize(&p, &mask, *maximize);
            emphasis = Some(report);
            mu
        }
        (None, Objective::Zeros { vertices }) => {
            if n < 4 {
                return Err(GlobalError::InvalidOption {
                    name: "objective zeros",
                    reason: "a genus-1 form has no zeros: zero allocation needs genus ≥ 2",
                });
            }
            if let Some(&v) = vertices.iter().find(|&&v| v >= s.input_vertices) {
                return Err(GlobalError::ZeroTargetOutOfRange {
                    vertex: v,
                    vertices: s.input_vertices,
                });
            }
            if vertices.is_empty() {
                return Err(GlobalError::InvalidOption {
                    name: "objective zeros",
                    reason: "needs at least one target vertex",
                });
            }
            let mut targets = vertices.clone();
            targets.sort_unstable();
            targets.dedup();
            let p = AreaProducts::from_faces(&ff);
            // the condition rows need the basis's values at the target vertices
            let forms = holomorphic_basis(s.harmonic, s.lambda);
            let m = targets::condition_gram(s.mesh, s.edges, &forms, &p, &targets);
            let free = n.saturating_sub(2 * targets.len());
            let (mu, method) = if free >= 2 {
                // exact zeros: the most uniform form of the subspace vanishing at the targets
                let basis = targets::null_space(&m, n, free);
                let sub = targets::restricted(&p, &basis, free);
                let moments = moments::Moments::new(&sub);
                let sub_basis: Vec<Vec<f64>> = (0..free)
                    .map(|k| sub.whiten(&unit_vector(free, k)))
                    .collect();
                energy_model = "moments".to_owned();
                let found = search::multistart(
                    &moments,
                    &[],
                    &sub_basis,
                    None,
                    false,
                    &search.with_compare(false),
                );
                let mu = targets::lift(&basis, &found.mu, n);
                search_out = Some(found);
                (mu, "exact")
            } else {
                // no form vanishes at all targets: the least Σ|ω(v_i)|² per unit area
                let (_, mu, _) = eigen::extreme_eigenpair(&m, n, false);
                (mu, "least-squares")
            };
            let value = products::quadratic(&m, &mu);
            zeros = Some(ZeroAllocationReport {
                targets: targets
                    .iter()
                    .map(|&vertex| ZeroTarget {
                        vertex,
                        ring_distance: None,
                        nearest_zero: None,
                        residual: f64::NAN,
                    })
                    .collect(),
                exact_expected: free >= 2,
                method: method.to_owned(),
                median_stretch: f64::NAN,
                eigenvalue: value,
            });
            mu
        }
    };
    Ok(ObjectiveReport {
        objective: if forced.is_some() {
            "basis".to_owned()
        } else {
            objective.name().to_owned()
        },
        coefficients: ff.coefficients(&mu),
        uniformity: ff.energy(&mu),
        basis_uniformity,
        search: search_out,
        opposite,
        max_min_ratio: ratio,
        emphasis,
        zeros,
        energy_model,
        products_ms,
        solve_ms: ms(t),
    })
}

/// The `k`-th unit vector of dimension `n`.
fn unit_vector(n: usize, k: usize) -> Vec<f64> {
    let mut e = vec![0.0; n];
    e[k] = 1.0;
    e
}

/// The search for `maximize` on `model` from the whitened basis forms (with their
/// energies) and, with [`FormSearchOptions::compare`], the opposite extreme's.
fn search_pair<M: EnergyModel + ?Sized>(
    model: &M,
    coarse: &[&dyn EnergyModel],
    (basis, energy): (&[Vec<f64>], &[f64]),
    maximize: bool,
    search: &FormSearchOptions,
) -> (UniformSearch, Option<UniformSearch>) {
    let run = |maximize| search::multistart(model, coarse, basis, Some(energy), maximize, search);
    let found = run(maximize);
    let other = search.compare.then(|| run(!maximize));
    (found, other)
}

/// Fills the zero-allocation report once the layout's zeros are known: `form` is the
/// laid-out form per edge of `mesh`.
pub(crate) fn finish_zeros(
    report: &mut ObjectiveReport,
    mesh: &TriMesh,
    edges: &EdgeIndex,
    form: &[num_complex::Complex64],
    zeros: &ZeroReport,
    input_vertices: usize,
) {
    let Some(z) = report.zeros.as_mut() else {
        return;
    };
    let stretch = vertex_stretch(mesh, edges, form);
    let mut goal = vec![false; mesh.num_vertices()];
    for zero in &zeros.zeros {
        goal[zero.vertex] = true;
    }
    for t in &mut z.targets {
        t.residual = stretch[t.vertex];
        if let Some((d, v)) = eigen::ring_distance(mesh, t.vertex, &goal) {
            t.ring_distance = Some(d);
            t.nearest_zero = Some(v);
        }
    }
    let mut s: Vec<f64> = stretch[..input_vertices].to_vec();
    s.sort_by(f64::total_cmp);
    z.median_stretch = s.get(s.len() / 2).copied().unwrap_or(f64::NAN);
}
