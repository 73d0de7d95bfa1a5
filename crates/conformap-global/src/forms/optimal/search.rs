//! The seeded multistart of the uniformity search: the `2g` basis forms and
//! [`FormSearchOptions::starts`] random points of the coefficient sphere, each descended
//! (or ascended) by Newton; the best optimum kept, the distinct optima counted by energy.

use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::forms::optimal::uniform::{
    local_search, local_search_seeded, EnergyModel, LocalOptimum,
};

/// Default number of random starts. 48: on fertility (g = 4) the best optimum is reached by
/// about a quarter of the starts (papers README; measured here, see the tests), so 48
/// starts miss it with probability below `0.75^48 ≈ 1e-6`; the search takes well under a
/// second on fertility in release.
pub const DEFAULT_STARTS: usize = 48;

/// Default seed of the start generator (any fixed value: runs are reproducible).
pub const DEFAULT_SEED: u64 = 0x05ee_d0ff_04d5;

/// Two local optima are the same when their energies agree to this relative tolerance.
/// Default `1e-7`: converged energies agree to ~1e-12; distinct optima differ by 0.1 % or
/// more. Energies are compared, never coefficients (an optimum is a whole circle
/// `e^{iθ} φ`, and coefficients depend on the homology basis).
pub const OPTIMUM_MATCH_REL: f64 = 1e-7;

/// Options of the uniformity search.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct FormSearchOptions {
    /// Random starts on the coefficient sphere, in addition to the `2g` basis forms, which
    /// are always starts (so the optimum is never worse than a basis form). Default
    /// [`DEFAULT_STARTS`].
    pub starts: usize,
    /// Seed of the start generator. Default [`DEFAULT_SEED`].
    pub seed: u64,
    /// Start from at most this many basis forms, those of lowest energy (ties by index).
    /// Default `None`: all `2g`, so the optimum is never worse than a basis form (which
    /// holds for any `Some(k ≥ 1)` too: the best basis form is always a start). At high
    /// genus every start costs `O(g⁴)` per Newton step; the topological optimization
    /// (genus up to 20 and more) keeps a few.
    #[serde(default)]
    pub basis_starts: Option<usize>,
    /// Also search the opposite extreme (the least uniform form for `Uniform`, the most
    /// uniform for `LeastUniform`) and report the ratio max/min. Default `true`.
    pub compare: bool,
}

impl FormSearchOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        starts: DEFAULT_STARTS,
        seed: DEFAULT_SEED,
        basis_starts: None,
        compare: true,
    };

    /// Sets [`Self::starts`].
    #[must_use]
    pub fn with_starts(mut self, starts: usize) -> Self {
        self.starts = starts;
        self
    }

    /// Sets [`Self::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`Self::basis_starts`].
    #[must_use]
    pub fn with_basis_starts(mut self, basis_starts: Option<usize>) -> Self {
        self.basis_starts = basis_starts;
        self
    }

    /// Sets [`Self::compare`].
    #[must_use]
    pub fn with_compare(mut self, compare: bool) -> Self {
        self.compare = compare;
        self
    }
}

impl Default for FormSearchOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What one multistart search found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct UniformSearch {
    /// Whether the energy was maximized (least uniform).
    pub maximize: bool,
    /// The best energy reached (scale-free, over the user's faces).
    pub energy: f64,
    /// Starts run (`2g` basis forms + random).
    pub starts: usize,
    /// Starts whose optimum matches the best (within [`OPTIMUM_MATCH_REL`]).
    pub reached_best: usize,
    /// The distinct local optima's energies, best first.
    pub local_optima: Vec<f64>,
    /// How many starts reached each of [`Self::local_optima`].
    pub local_optimum_counts: Vec<usize>,
    /// Newton iterations over all starts.
    pub iterations_total: usize,
    /// Most Newton iterations of one start.
    pub iterations_max: usize,
    /// Hessians evaluated over all starts (and levels): at most one per Newton iteration
    /// plus one per start, fewer when kept across steps in the local regime (see
    /// `uniform::HESSIAN_REUSE_CONTRACTION`).
    #[serde(default)]
    pub hessians_total: usize,
    /// Starts that stopped without meeting the gradient test.
    pub unconverged: usize,
    /// Newton iterations on the coarse levels (samples of the faces) over all starts,
    /// before [`Self::iterations_total`] on all faces; 0 without a coarse level.
    #[serde(default)]
    pub coarse_iterations: usize,
    /// Starts whose optimum on a coarse level was more than `POLISH_WINDOW` from the best
    /// one there: not refined further, not counted in [`Self::starts`] nor in the optima.
    #[serde(default)]
    pub unpolished: usize,
    /// Wall-clock milliseconds of the search.
    pub time_ms: f64,
    /// The best form's whitened coefficients (unit length).
    #[serde(skip)]
    pub mu: Vec<f64>,
}

/// A SplitMix64 stream with Box–Muller normals: uniform directions on the sphere.
struct Normals(u64);

impl Normals {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// `count` seeded random directions in `n` dimensions (not normalized: uniform on the
/// sphere after normalization).
pub fn random_directions(n: usize, count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut g = Normals(seed);
    (0..count)
        .map(|_| (0..n).map(|_| g.normal()).collect())
        .collect()
}

/// A coarse optimum is polished on all faces only when its coarse energy is within this
/// relative window of the best coarse optimum's: `0.05`. The coarse energy (16k sampled
/// faces) differs from the full one by well under 1 % near the optima (measured on
/// armadillo and spot, docs/benchmarks.md, issue 23), while distinct local optima of a
/// high-genus surface differ by 0.4 % and more; a coarse optimum 5 % worse than the best
/// does not win after its polish, and each polish costs a few full `O(F n²)` Newton steps.
/// The same window applies from the coarsest level (2k faces) to the coarse one.
pub const POLISH_WINDOW: f64 = 0.05;

/// One level of the refinement: the optimum of each start on the level before (`None`: a
/// start dropped there) polished on `model` — once per distinct optimum (energies equal
/// within [`OPTIMUM_MATCH_REL`]: the same local optimum, whose polish the other starts would
/// repeat step for step; they share its result, with 0 iterations of their own), and only
/// within [`POLISH_WINDOW`] of the best (the others are dropped).
fn refine<M: EnergyModel + ?Sized>(
    model: &M,
    near: &[Option<LocalOptimum>],
    maximize: bool,
) -> Vec<Option<LocalOptimum>> {
    let sign = if maximize { -1.0 } else { 1.0 };
    let best = near
        .iter()
        .flatten()
        .map(|r| sign * r.energy)
        .fold(f64::INFINITY, f64::min);
    let promising = |e: f64| sign * e <= best + POLISH_WINDOW * best.abs();
    let mut rep: Vec<Option<usize>> = Vec::with_capacity(near.len());
    for (i, a) in near.iter().enumerate() {
        let Some(a) = a else {
            rep.push(None);
            continue;
        };
        let same = (0..i).find(|&j| match &near[j] {
            Some(b) if rep[j] == Some(j) => {
                (a.energy - b.energy).abs() <= OPTIMUM_MATCH_REL * b.energy.abs()
            }
            _ => false,
        });
        rep.push(Some(same.unwrap_or(i)));
    }
    let polished: Vec<Option<LocalOptimum>> = (0..near.len())
        .into_par_iter()
        .map(|i| match &near[i] {
            Some(a) if rep[i] == Some(i) && promising(a.energy) => Some(local_search_seeded(
                model,
                &a.mu,
                maximize,
                Some(&a.hessian),
            )),
            _ => None,
        })
        .collect();
    rep.iter()
        .enumerate()
        .map(|(i, r)| {
            let r = (*r)?;
            let mut out = polished[r].clone()?;
            if r != i {
                out.iterations = 0;
                out.hessians = 0;
            }
            Some(out)
        })
        .collect()
}

/// Each start descended on the coarsest of `levels` (samples of the faces, coarsest
/// first), then refined ([`refine`]) on each finer level and last on `model`. Returns the
/// optima of the starts polished on `model`, the Newton iterations and Hessians on the
/// coarse levels, and the starts dropped on the way.
fn multi_level<M: EnergyModel + ?Sized>(
    model: &M,
    levels: &[&dyn EnergyModel],
    starts: &[Vec<f64>],
    maximize: bool,
) -> (Vec<LocalOptimum>, [usize; 2], usize) {
    let work = |near: &[Option<LocalOptimum>]| -> [usize; 2] {
        let it = near.iter().flatten();
        [
            it.clone().map(|r| r.iterations).sum(),
            it.map(|r| r.hessians).sum(),
        ]
    };
    let mut near: Vec<Option<LocalOptimum>> = match levels.first() {
        Some(first) => starts
            .par_iter()
            .map(|s| Some(local_search(*first, s, maximize)))
            .collect(),
        None => Vec::new(),
    };
    let mut coarse = work(&near);
    for level in levels.iter().skip(1) {
        near = refine(*level, &near, maximize);
        let [i, h] = work(&near);
        coarse = [coarse[0] + i, coarse[1] + h];
    }
    let results: Vec<LocalOptimum> = refine(model, &near, maximize)
        .into_iter()
        .flatten()
        .collect();
    let skipped = starts.len() - results.len();
    (results, coarse, skipped)
}

/// The multistart search of the most (`maximize = false`) or least uniform form on
/// `model`, from the whitened basis forms `basis` (the lowest-energy
/// [`FormSearchOptions::basis_starts`] of them, by `basis_energy` when known, else
/// evaluated) and the seeded random starts. With
/// `coarse` models (samples of the faces, `faces.rs`, coarsest first), each start descends
/// on the coarsest first and its optimum is then refined level by level and polished on
/// `model`: the finer Newton steps, `O(F n²)` each on all faces, are spent only near an
/// optimum, where Newton converges in a few.
pub fn multistart<M: EnergyModel + ?Sized>(
    model: &M,
    coarse: &[&dyn EnergyModel],
    basis: &[Vec<f64>],
    basis_energy: Option<&[f64]>,
    maximize: bool,
    options: &FormSearchOptions,
) -> UniformSearch {
    let t = Instant::now();
    let n = model.dim();
    let mut starts: Vec<Vec<f64>> = basis.to_vec();
    if let Some(keep) = options.basis_starts.filter(|&k| k < starts.len()) {
        let sign = if maximize { -1.0 } else { 1.0 };
        let value: Vec<f64> = match basis_energy {
            Some(e) => e.iter().map(|x| sign * x).collect(),
            None => starts.iter().map(|s| sign * model.energy(s)).collect(),
        };
        let mut order: Vec<usize> = (0..starts.len()).collect();
        order.sort_by(|&a, &b| value[a].total_cmp(&value[b]).then(a.cmp(&b)));
        starts = order[..keep.max(1)]
            .iter()
            .map(|&k| starts[k].clone())
            .collect();
    }
    starts.extend(random_directions(n, options.starts, options.seed));
    let (results, coarse_iterations, unpolished) = match coarse {
        [_, ..] => multi_level(model, coarse, &starts, maximize),
        [] => {
            let results: Vec<LocalOptimum> = starts
                .par_iter()
                .map(|s| local_search(model, s, maximize))
                .collect();
            (results, [0, 0], 0)
        }
    };
    let [coarse_iterations, coarse_hessians] = coarse_iterations;
    let better = |a: f64, b: f64| if maximize { a > b } else { a < b };
    let mut energies: Vec<f64> = results.iter().map(|r| r.energy).collect();
    energies.sort_by(|a, b| {
        if maximize {
            b.total_cmp(a)
        } else {
            a.total_cmp(b)
        }
    });
    let (mut optima, mut counts): (Vec<f64>, Vec<usize>) = (Vec::new(), Vec::new());
    for e in energies {
        match optima.last() {
            Some(&last) if (e - last).abs() <= OPTIMUM_MATCH_REL * last.abs() => {
                *counts.last_mut().unwrap_or(&mut 0) += 1;
            }
            _ => {
                optima.push(e);
                counts.push(1);
            }
        }
    }
    let best = results
        .iter()
        .fold(None::<&LocalOptimum>, |acc, r| match acc {
            Some(b) if !better(r.energy, b.energy) => Some(b),
            _ => Some(r),
        })
        .map(|r| r.mu.clone())
        .unwrap_or_default();
    UniformSearch {
        maximize,
        energy: optima.first().copied().unwrap_or(f64::NAN),
        starts: results.len(),
        reached_best: counts.first().copied().unwrap_or(0),
        local_optima: optima,
        local_optimum_counts: counts,
        iterations_total: results.iter().map(|r| r.iterations).sum(),
        iterations_max: results.iter().map(|r| r.iterations).max().unwrap_or(0),
        hessians_total: coarse_hessians + results.iter().map(|r| r.hessians).sum::<usize>(),
        unconverged: results.iter().filter(|r| !r.converged).count(),
        coarse_iterations,
        unpolished,
        time_ms: t.elapsed().as_secs_f64() * 1e3,
        mu: best,
    }
}
