//! Where the cones go and what angles they get: least area spread for a given number.
//!
//! 1. **Angles for given vertices** ([`best_defects`]): the face log scales are linear in
//!    the cone defects (`2φ(u) = Σ k_c A_c − R`, module `metric`), so the defects with the
//!    least spread solve a small least-squares problem (one column per cone), under
//!    `Σ k = 2πχ` on a closed surface: a `(C+1)²` KKT system.
//! 2. **Greedy** ([`place_cones`], first pass): the next cone goes where the current scale
//!    factor is most extreme (the rule of boundary first flattening), but each time with
//!    the best angles for the cones so far instead of `u = 0` at the cones.
//! 3. **Moves** (second pass): each cone in turn is taken out and the strongest extremes
//!    of the scale factor without it are tried in its place; a move is kept when it lowers
//!    the spread. Rounds until none helps or [`ConeOptions::move_rounds`] is reached.
//! 4. **Local descent** (small surfaces): each cone slides to the neighbour that lowers the
//!    spread most, a few rounds; only the [`SLIDE_TRIALS`] neighbours whose first-order
//!    change of the spread is lowest are solved for.
//!
//! Steps 2–4 run twice, ranking extremes by their distance from the mean scale and from the
//! cones' own scale (boundary first flattening's rule); the set with less spread is kept.
//!
//! A cone angle must lie in [[`MIN_CONE_ANGLE`], [`MAX_CONE_ANGLE`]] = [π/2, 4π]; a
//! configuration whose best angles break that has the offending cones held at the bound
//! (active set).

use rustc_hash::FxHashMap as HashMap;

use serde::{Deserialize, Serialize};

use super::metric::ConeMetric;

/// The smallest cone angle a placement may give, radians: π/2. Sharper cones make
/// needle-thin wedges around them in the layout, where the harmonic interior folds and
/// the angles suffer (armadillo at π/4: area spread 1.71 but mean angle distortion 2.80°,
/// 199 pieces after unfolding and splitting; at π/2: 1.86, 1.60°, 43 pieces).
pub const MIN_CONE_ANGLE: f64 = std::f64::consts::FRAC_PI_2;

/// The largest cone angle a placement may give, radians: 4π. A saddle cone wraps its
/// neighbourhood round it that many times in the layout, which overlaps itself and is
/// split into pieces (armadillo unbounded: a 967° cone, 55 pieces; at 4π: 43).
pub const MAX_CONE_ANGLE: f64 = 4.0 * std::f64::consts::PI;

/// A new cone is looked for no nearer to an existing one than this share of `√(surface
/// area)`: 0.1. Right at a cone the scale factor has its logarithmic spike (the
/// discrete Green's function drops by a unit or more to the cone's neighbours), which
/// would otherwise draw the next cone next to it.
pub const CONE_SPACING: f64 = 0.1;

/// How cones are placed. `Default` is [`ConeOptions::DEFAULT`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ConeOptions {
    /// Rounds of moves after the greedy pass. Default: 3 (on spot, armadillo, brain and
    /// david_head the third round changes the spread by under 1 %).
    pub move_rounds: usize,
    /// Extremes of the scale factor tried in place of a cone per move. Default: 4.
    pub candidates: usize,
    /// Rounds of local descent after the moves: each cone moved to the neighbour that
    /// lowers the spread most. Default: 4 (spot: 0.835 → 0.825, converged after 3).
    pub local_rounds: usize,
    /// Local descent only on closed genus-0 surfaces with at most this many vertices (on
    /// genus ≥ 1 it slid cones next to the handle loops): a round costs
    /// [`SLIDE_TRIALS`] Green's function solves per cone and one more for the round's
    /// first-order ranking.
    /// Default: 5,000: spot (2,930 vertices) keeps it (0.835 → 0.825); on david_head
    /// (10,671) it gains 0.246 → 0.240 and the neck cut that packs 0.59 → 0.68 (BFF's
    /// 0.41) for about a quarter of the whole run's time, on the 90k-face meshes 1–2 % of
    /// spread for seconds.
    pub local_max_vertices: usize,
}

impl ConeOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        move_rounds: 3,
        candidates: 4,
        local_rounds: 4,
        local_max_vertices: 5_000,
    };

    /// With another number of move rounds (0: the greedy pass alone).
    pub fn with_move_rounds(mut self, rounds: usize) -> Self {
        self.move_rounds = rounds;
        self
    }
}

impl Default for ConeOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// One cone: a vertex and its angle defect `k = 2π − cone angle` (radians).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Cone {
    /// The vertex.
    pub vertex: u32,
    /// Angle defect, radians (positive: a convex tip, cone angle below 2π).
    pub defect: f64,
}

impl Cone {
    /// The cone angle, degrees.
    pub fn angle_deg(&self) -> f64 {
        (std::f64::consts::TAU - self.defect).to_degrees()
    }
}

/// Cones with their scale factor and its area spread.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct ConeSet {
    /// The cones, in the order they were placed.
    pub cones: Vec<Cone>,
    /// The scale factor `u` per vertex.
    pub u: Vec<f64>,
    /// The area spread of the cone metric (sd over faces of `2u`).
    pub area_spread: f64,
    /// The spread after the greedy pass, before the moves.
    pub greedy_spread: f64,
    /// Moves kept.
    pub moves: usize,
}

impl ConeSet {
    /// No cones on a surface of `vertices` vertices: `u = 0` (a free boundary keeps its
    /// lengths), no spread measured (NaN).
    pub fn none(vertices: usize) -> Self {
        Self {
            cones: Vec::new(),
            u: vec![0.0; vertices],
            area_spread: f64::NAN,
            greedy_spread: f64::NAN,
            moves: 0,
        }
    }
}

/// The per-face columns of the least-squares problem, cached per vertex.
struct Columns<'a> {
    metric: &'a ConeMetric,
    cache: HashMap<u32, Vec<f64>>,
    rhs: Vec<f64>,
    /// `‖rhs‖²`, summed once (every [`best_with`] needs it: a pass over the faces each
    /// time was 5 % of eight's atlas).
    rhs_norm2: f64,
    /// Dot products of two columns (smaller vertex first), and of a column with `rhs`:
    /// each pair is summed over the faces once, however many sets it appears in.
    dots: HashMap<(u32, u32), f64>,
    rhs_dots: HashMap<u32, f64>,
    /// Green's functions per vertex (one solve each, shared by the columns and the
    /// guidance metric).
    greens: HashMap<u32, Vec<f64>>,
    /// The guidance metric without cones (one solve).
    start: Option<Vec<f64>>,
}

impl<'a> Columns<'a> {
    fn new(metric: &'a ConeMetric) -> Self {
        let rhs = centered(metric.face_log_scale(metric.curvature_potential()));
        Self {
            metric,
            cache: HashMap::default(),
            rhs_norm2: rhs.iter().map(|x| x * x).sum(),
            rhs,
            dots: HashMap::default(),
            rhs_dots: HashMap::default(),
            greens: HashMap::default(),
            start: None,
        }
    }

    fn green(&mut self, v: u32) -> &[f64] {
        let metric = self.metric;
        self.greens.entry(v).or_insert_with(|| metric.green(v))
    }

    /// The Green's functions of those of `vertices` not cached yet, from one solve with
    /// that many right-hand sides (the candidates of a move, the neighbours of a cone).
    fn prefetch(&mut self, vertices: &[u32]) {
        let mut missing: Vec<u32> = vertices
            .iter()
            .copied()
            .filter(|v| !self.greens.contains_key(v))
            .collect();
        missing.sort_unstable();
        missing.dedup();
        if missing.is_empty() {
            return;
        }
        for (v, g) in missing.iter().zip(self.metric.greens(&missing)) {
            self.greens.insert(*v, g);
        }
    }

    /// The product of the columns of `a` and `b`, filled by [`Self::fill_dots`].
    fn dot(&self, a: u32, b: u32) -> f64 {
        self.dots[&(a.min(b), a.max(b))]
    }

    /// The products of the columns of `vertices` with each other and with the right-hand
    /// side not cached yet, computed a column against up to [`FUSED`] others in one pass
    /// over the faces: each product is the same running sum, face by face, as one pass per
    /// product gives (so the same number to the last bit), but the running sums of a pass
    /// are independent chains of additions the processor overlaps, where one sum waits on
    /// each addition (the products were a quarter of spot's cone search).
    fn fill_dots(&mut self, vertices: &[u32]) {
        for &v in vertices {
            self.column(v);
        }
        for (i, &a) in vertices.iter().enumerate() {
            let mut others: Vec<Option<u32>> = vertices[..=i]
                .iter()
                .filter(|&&b| !self.dots.contains_key(&(a.min(b), a.max(b))))
                .map(|&b| Some(b))
                .collect();
            if !self.rhs_dots.contains_key(&a) {
                // None: the right-hand side
                others.push(None);
            }
            let column = &self.cache[&a];
            for group in others.chunks(FUSED) {
                let slices: Vec<&[f64]> = group
                    .iter()
                    .map(|b| match b {
                        Some(b) => self.cache[b].as_slice(),
                        None => self.rhs.as_slice(),
                    })
                    .collect();
                let sums = running_sums(column, &slices);
                for (b, d) in group.iter().zip(sums) {
                    match b {
                        Some(b) => self.dots.insert((a.min(*b), a.max(*b)), d),
                        None => self.rhs_dots.insert(a, d),
                    };
                }
            }
        }
    }

    /// `⟨r, a_w⟩` for every vertex `w`, with `r = Σ k_c a_c − R` the residual of the cones
    /// `vertices` with defects `k` (columns and `R` centred, so `r` is).
    fn pullback(&mut self, vertices: &[u32], k: &[f64]) -> Vec<f64> {
        let mut r: Vec<f64> = self.rhs.iter().map(|x| -x).collect();
        for (&v, &kc) in vertices.iter().zip(k) {
            for (x, a) in r.iter_mut().zip(self.column(v)) {
                *x += kc * a;
            }
        }
        self.metric.face_pullback(&r)
    }

    fn column(&mut self, v: u32) -> &[f64] {
        if !self.cache.contains_key(&v) {
            let col = centered(self.metric.face_log_scale(self.green(v)));
            self.cache.insert(v, col);
        }
        &self.cache[&v]
    }
}

/// Columns [`Columns::fill_dots`] takes in one pass: 4 (four chains of additions cover
/// an addition's latency; more streams of columns gain nothing more).
const FUSED: usize = 4;

/// `Σ_f a[f] · b[f]` for each `b` of `others` (at most [`FUSED`]), each summed face by face
/// from `-0.0` as `Iterator::sum` does, all in one pass.
fn running_sums(a: &[f64], others: &[&[f64]]) -> Vec<f64> {
    let mut sums = [-0.0f64; FUSED];
    let k = others.len().min(FUSED);
    match k {
        4 => {
            let [mut s0, mut s1, mut s2, mut s3] = sums;
            let columns = others[0]
                .iter()
                .zip(others[1])
                .zip(others[2])
                .zip(others[3]);
            for (&x, (((&y0, &y1), &y2), &y3)) in a.iter().zip(columns) {
                s0 += x * y0;
                s1 += x * y1;
                s2 += x * y2;
                s3 += x * y3;
            }
            sums = [s0, s1, s2, s3];
        }
        _ => {
            for (f, &x) in a.iter().enumerate() {
                for c in 0..k {
                    sums[c] += x * others[c][f];
                }
            }
        }
    }
    sums[..k].to_vec()
}

fn centered(mut x: Vec<f64>) -> Vec<f64> {
    let mean = x.iter().sum::<f64>() / x.len().max(1) as f64;
    x.iter_mut().for_each(|v| *v -= mean);
    x
}

/// The defects of cones at `vertices` with the least area spread, and that spread; `None`
/// when the best angles make a cone angle non-positive or the system is singular (two
/// cones at one vertex, a pinned vertex).
pub fn best_defects(metric: &ConeMetric, vertices: &[u32]) -> Option<(Vec<f64>, f64)> {
    best_with(&mut Columns::new(metric), vertices, true)
}

/// [`best_defects`]; with `valid` false, also angles that are not valid cone angles (the
/// greedy pass needs the unconstrained optimum of a set too small to carry `2πχ`).
fn best_with(cols: &mut Columns<'_>, vertices: &[u32], valid: bool) -> Option<(Vec<f64>, f64)> {
    let c = vertices.len();
    if vertices.iter().any(|&v| cols.metric.pinned(v)) {
        return None;
    }
    // the normal equations' Gram matrix and right-hand side (cached pairwise)
    cols.fill_dots(vertices);
    let mut gram = vec![0.0; c * c];
    let mut rhs = vec![0.0; c];
    for i in 0..c {
        for j in 0..=i {
            let d = cols.dot(vertices[i], vertices[j]);
            gram[i * c + j] = d;
            gram[j * c + i] = d;
        }
        rhs[i] = cols.rhs_dots[&vertices[i]];
    }
    let total = cols.metric.closed().then(|| cols.metric.total_defect());
    // active set: a cone whose best defect leaves no positive angle is held at the bound
    // and the others solved again (the spread is convex in the defects)
    let upper = std::f64::consts::TAU - MIN_CONE_ANGLE;
    let lower = std::f64::consts::TAU - MAX_CONE_ANGLE;
    let mut held: Vec<Option<f64>> = vec![None; c];
    let k = loop {
        let k = constrained_least_squares(&gram, &rhs, c, &held, total)?;
        let excess = |i: usize| (k[i] - upper).max(lower - k[i]);
        let worst = (0..c)
            .filter(|&i| held[i].is_none() && excess(i) > 0.0)
            .max_by(|&x, &y| excess(x).total_cmp(&excess(y)));
        match worst {
            Some(i) if valid => held[i] = Some(if k[i] > upper { upper } else { lower }),
            _ => break k,
        }
    };
    if !k.iter().all(|d| d.is_finite()) {
        return None;
    }
    // the columns and the right-hand side have mean 0 over the faces, so the spread is
    // ‖A k − R‖ / √F = √(kᵀGk − 2kᵀb + RᵀR) / √F, with no pass over the faces
    let n = cols.rhs.len().max(1) as f64;
    let mut q = cols.rhs_norm2;
    for i in 0..c {
        q -= 2.0 * k[i] * rhs[i];
        for j in 0..c {
            q += k[i] * gram[i * c + j] * k[j];
        }
    }
    Some((k, (q.max(0.0) / n).sqrt()))
}

/// Minimizes `kᵀ G k − 2 bᵀ k` over the defects not `held` (those are at their held
/// value), with `Σ k = total` when given: the KKT system of the free defects and the
/// multiplier.
fn constrained_least_squares(
    gram: &[f64],
    rhs: &[f64],
    c: usize,
    held: &[Option<f64>],
    total: Option<f64>,
) -> Option<Vec<f64>> {
    let free: Vec<usize> = (0..c).filter(|&i| held[i].is_none()).collect();
    let f = free.len();
    let m = if total.is_some() { f + 1 } else { f };
    let mut k: Vec<f64> = held.iter().map(|h| h.unwrap_or(0.0)).collect();
    if m == 0 {
        return Some(k);
    }
    let mut sys = vec![0.0; m * (m + 1)];
    for (r, &i) in free.iter().enumerate() {
        for (q, &j) in free.iter().enumerate() {
            sys[r * (m + 1) + q] = gram[i * c + j];
        }
        let fixed: f64 = (0..c).map(|j| gram[i * c + j] * k[j]).sum();
        sys[r * (m + 1) + m] = rhs[i] - fixed;
    }
    if let Some(t) = total {
        for r in 0..f {
            sys[r * (m + 1) + f] = 1.0;
            sys[f * (m + 1) + r] = 1.0;
        }
        let fixed: f64 = k.iter().sum();
        sys[f * (m + 1) + m] = t - fixed;
    }
    let x = solve_dense(sys, m)?;
    for (r, &i) in free.iter().enumerate() {
        k[i] = x[r];
    }
    Some(k)
}

/// Gaussian elimination with partial pivoting on the augmented `m × (m+1)` row-major
/// system; `None` when singular.
fn solve_dense(mut s: Vec<f64>, m: usize) -> Option<Vec<f64>> {
    let w = m + 1;
    let scale = s
        .iter()
        .fold(0.0f64, |a, &b| a.max(b.abs()))
        .max(f64::MIN_POSITIVE);
    for col in 0..m {
        let piv =
            (col..m).max_by(|&a, &b| s[a * w + col].abs().total_cmp(&s[b * w + col].abs()))?;
        if !(s[piv * w + col].abs() > 1e-14 * scale) {
            return None;
        }
        for j in 0..w {
            s.swap(col * w + j, piv * w + j);
        }
        for r in 0..m {
            if r != col {
                let f = s[r * w + col] / s[col * w + col];
                if f != 0.0 {
                    for j in col..w {
                        s[r * w + j] -= f * s[col * w + j];
                    }
                }
            }
        }
    }
    Some((0..m).map(|i| s[i * w + m] / s[i * w + i]).collect())
}

/// How a greedy pass and the moves rank the vertices of a scale factor: by `|u − r|` with
/// `r` the mean of `u`, or its value at the cones (boundary first flattening's rule: `u` is
/// the same at every cone of the guidance metric, the next cone goes where it is farthest
/// from that).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Reference {
    Mean,
    Cones,
}

/// Places `count` cones with the least area spread this search finds (module docs): a
/// greedy pass and its moves for each way of ranking extremes (the mean and the cones'
/// own scale as reference; neither wins on every mesh: spot 0.835 against 0.904,
/// armadillo 2.743 against 1.691), the set with the least spread kept.
/// `count = 0` gives the cone-free metric (on a closed surface the pinned vertex then
/// carries all of `2πχ`: useful only for comparison).
pub fn place_cones(metric: &ConeMetric, count: usize, options: &ConeOptions) -> ConeSet {
    // the two searches share nothing but the metric: one per core, each with its own
    // cache of Green's functions (spot: 37 → 21 ms wall; the result is the same)
    let run = |reference| search(metric, &mut Columns::new(metric), count, options, reference);
    let (mut best, other) = rayon::join(|| run(Reference::Mean), || run(Reference::Cones));
    if other.spread < best.spread {
        best = other;
    }
    let cones = cones_of(&best.vertices, &best.defects);
    let u = metric.scale_factor(&cones);
    let area_spread = metric.area_spread(&u);
    ConeSet {
        cones: cones
            .iter()
            .map(|&(vertex, defect)| Cone { vertex, defect })
            .collect(),
        u,
        area_spread,
        greedy_spread: best.greedy_spread,
        moves: best.moves,
    }
}

/// The fewest cones, from `first` to `last`, whose greedy pass alone (no moves: the
/// prefixes of one greedy pass, since each cone is chosen from those before it) gives a
/// set of angles within `max_spread`, for either way of ranking extremes (the two on the
/// two cores); `None` when no count up to `last` does. [`place_cones`] at that count
/// reaches `max_spread` too (its moves only lower the greedy set's spread): `--cones auto`
/// looks below it with full placements, not above (`chart::given`).
pub(crate) fn greedy_count(
    metric: &ConeMetric,
    first: usize,
    last: usize,
    max_spread: f64,
) -> Option<usize> {
    let run = |reference| {
        let mut cols = Columns::new(metric);
        let mut vertices: Vec<u32> = Vec::new();
        while vertices.len() < last {
            let u = guidance(&mut cols, &vertices);
            let next = extremes(metric, &u, &vertices, 1, reference)
                .first()
                .copied()?;
            vertices.push(next);
            if vertices.len() >= first
                && best_with(&mut cols, &vertices, true).is_some_and(|b| b.1 <= max_spread)
            {
                return Some(vertices.len());
            }
        }
        None
    };
    let (a, b) = rayon::join(|| run(Reference::Mean), || run(Reference::Cones));
    match (a, b) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// One greedy pass and its moves.
struct Search {
    vertices: Vec<u32>,
    defects: Vec<f64>,
    spread: f64,
    greedy_spread: f64,
    moves: usize,
}

fn search(
    metric: &ConeMetric,
    cols: &mut Columns<'_>,
    count: usize,
    options: &ConeOptions,
    reference: Reference,
) -> Search {
    let mut vertices: Vec<u32> = Vec::new();
    // greedy: the most extreme vertex of the guidance metric of the cones so far
    while vertices.len() < count {
        let u = guidance(cols, &vertices);
        let Some(next) = extremes(metric, &u, &vertices, 1, reference)
            .first()
            .copied()
        else {
            break;
        };
        vertices.push(next);
    }
    // a set whose best angles are no cone angles counts as infinitely spread: the moves
    // then take the first valid set they meet
    let mut current = (Vec::new(), f64::INFINITY);
    if let Some(best) = best_with(cols, &vertices, true) {
        current = best;
    } else if let Some(best) = best_with(cols, &vertices, false) {
        current = (best.0, f64::INFINITY);
    }
    let greedy_spread = current.1;
    let mut moves = 0;
    for _ in 0..options.move_rounds {
        let mut improved = false;
        for i in 0..vertices.len() {
            let mut rest = vertices.clone();
            rest.remove(i);
            let without = guidance(cols, &rest);
            let candidates = extremes(metric, &without, &rest, options.candidates, reference);
            cols.prefetch(&candidates);
            for cand in candidates {
                if cand == vertices[i] {
                    continue;
                }
                let mut trial = rest.clone();
                trial.insert(i, cand);
                if let Some(best) = best_with(cols, &trial, true) {
                    if best.1 < current.1 * (1.0 - 1e-9) {
                        vertices = trial;
                        current = best;
                        improved = true;
                        moves += 1;
                    }
                }
            }
        }
        if !improved {
            break;
        }
    }
    // on a surface with pinned handle loops the cones slid next to the loops: fertility's
    // angle distortion rose from 1.53° to 1.91° for 4 % less spread
    let small = metric.closed() && metric.curvature().len() <= options.local_max_vertices;
    let local_rounds = if small { options.local_rounds } else { 0 };
    for _ in 0..local_rounds {
        if !current.1.is_finite() || !slide(metric, cols, &mut vertices, &mut current) {
            break;
        }
        moves += 1;
    }
    Search {
        vertices,
        defects: current.0,
        spread: current.1,
        greedy_spread,
        moves,
    }
}

/// One round of local descent: each cone in turn moved to the neighbour (free, not a
/// cone) that lowers the spread most, if one does. Returns whether any cone moved.
///
/// Only the [`SLIDE_TRIALS`] neighbours the first-order change of the spread ranks best
/// are solved for: moving defect `k` from `v` to `w` changes the residual `r = A k − R` by
/// `k (a_w − a_v)`, whose first-order effect `2k ⟨r, a_w − a_v⟩` one solve gives for every
/// vertex ([`ConeMetric::face_pullback`]), instead of a Green's function per neighbour.
fn slide(
    metric: &ConeMetric,
    cols: &mut Columns<'_>,
    vertices: &mut [u32],
    current: &mut (Vec<f64>, f64),
) -> bool {
    let mut moved = false;
    // one solve per round: the ranking after a move in it uses the round's first residual
    let slope = cols.pullback(vertices, &current.0);
    for i in 0..vertices.len() {
        let here = vertices[i];
        let k = current.0[i];
        let mut ranked: Vec<u32> = metric
            .neighbours(here)
            .iter()
            .copied()
            .filter(|&w| !metric.pinned(w) && !vertices.contains(&w))
            .collect();
        ranked.sort_by(|&a, &b| {
            (k * slope[a as usize])
                .total_cmp(&(k * slope[b as usize]))
                .then(a.cmp(&b))
        });
        ranked.truncate(SLIDE_TRIALS);
        let mut best: Option<(u32, (Vec<f64>, f64))> = None;
        cols.prefetch(&ranked);
        for &w in &ranked {
            vertices[i] = w;
            if let Some(found) = best_with(cols, vertices, true) {
                let bar = best.as_ref().map_or(current.1 * (1.0 - 1e-9), |b| b.1 .1);
                if found.1 < bar {
                    best = Some((w, found));
                }
            }
        }
        match best {
            Some((w, found)) => {
                vertices[i] = w;
                *current = found;
                moved = true;
            }
            None => vertices[i] = here,
        }
    }
    moved
}

/// Neighbours of a cone solved for per cone and round of local descent: 2 (of 6 on
/// average), those whose first-order change of the spread is lowest (the module docs,
/// step 4).
pub const SLIDE_TRIALS: usize = 2;

/// The scale factor of boundary first flattening's rule for cones at `vertices`: the
/// defects that make `u = 0` at every cone (a `C × C` system in the Green's functions).
/// Its extremes lie away from the cones, where the next cone pays most; the least-spread
/// angles' scale factor has logarithmic spikes at its cones instead, whose neighbours
/// would be picked next.
fn guidance(cols: &mut Columns<'_>, vertices: &[u32]) -> Vec<f64> {
    let metric = cols.metric;
    let c = vertices.len();
    if c == 0 {
        return cols
            .start
            .get_or_insert_with(|| start_potential(metric))
            .clone();
    }
    for &v in vertices {
        cols.green(v);
    }
    let greens = &cols.greens;
    // unknowns: the defects and, on a closed surface, a constant (u is defined up to one
    // there: the pinned vertex only fixes the gauge), with Σ k = 2πχ as the last equation
    let uk = metric.curvature_potential();
    let m = if metric.closed() { c + 1 } else { c };
    let mut sys = vec![0.0; m * (m + 1)];
    for (i, &vi) in vertices.iter().enumerate() {
        for (j, &vj) in vertices.iter().enumerate() {
            sys[i * (m + 1) + j] = greens[&vj][vi as usize];
        }
        if metric.closed() {
            sys[i * (m + 1) + c] = 1.0;
        }
        sys[i * (m + 1) + m] = uk[vi as usize];
    }
    if metric.closed() {
        for j in 0..c {
            sys[c * (m + 1) + j] = 1.0;
        }
        sys[c * (m + 1) + m] = metric.total_defect();
    }
    let Some(k) = solve_dense(sys, m) else {
        return cols
            .start
            .get_or_insert_with(|| start_potential(metric))
            .clone();
    };
    // u = Σ k_c g_c − u_K from the Green's functions at hand: no solve
    let mut u: Vec<f64> = uk.iter().map(|x| -x).collect();
    for (j, &v) in vertices.iter().enumerate() {
        for (x, g) in u.iter_mut().zip(&greens[&v]) {
            *x += k[j] * g;
        }
    }
    u
}

fn cones_of(vertices: &[u32], defects: &[f64]) -> Vec<(u32, f64)> {
    vertices
        .iter()
        .copied()
        .zip(defects.iter().copied())
        .collect()
}

/// The scale factor the greedy pass starts from: on a closed surface, the one that spreads
/// `2πχ` evenly over the vertices (no cone yet); with a boundary, the cone-free one.
fn start_potential(metric: &ConeMetric) -> Vec<f64> {
    if !metric.closed() {
        return metric.scale_factor(&[]);
    }
    let n = metric.curvature().len();
    let share = metric.total_defect() / n as f64;
    let cones: Vec<(u32, f64)> = (0..n as u32).map(|v| (v, share)).collect();
    metric.scale_factor(&cones)
}

/// The `count` free vertices (not pinned, not near `taken`) where `u` is farthest from its
/// reference (its mean, or its value at the first cone), strongest first.
fn extremes(
    metric: &ConeMetric,
    u: &[f64],
    taken: &[u32],
    count: usize,
    reference: Reference,
) -> Vec<u32> {
    let mean = match (reference, taken.first()) {
        (Reference::Cones, Some(&c)) => u[c as usize],
        _ => u.iter().sum::<f64>() / u.len().max(1) as f64,
    };
    // strongest first, ties by index: a total order, so the first `count` free vertices
    // of the strongest few (checked for nearness to `taken` only there) are the first
    // `count` of the whole filtered order; the whole order only when too few are free
    let cmp = |a: &u32, b: &u32| {
        (u[*b as usize] - mean)
            .abs()
            .total_cmp(&(u[*a as usize] - mean).abs())
            .then(a.cmp(b))
    };
    let free = |v: u32| !taken.iter().any(|&t| metric.near(v, t, CONE_SPACING));
    if count == 0 {
        return Vec::new();
    }
    let mut order: Vec<u32> = (0..u.len() as u32).filter(|&v| !metric.pinned(v)).collect();
    // the strongest 4·count + 16 first: a few cones' spacing disks seldom hold more of
    // them (the result does not depend on the number: too few free ones there and the
    // whole order is filtered below)
    let head = (4 * count + 16).min(order.len());
    if head > 0 && head < order.len() {
        order.select_nth_unstable_by(head - 1, cmp);
    }
    order[..head].sort_by(cmp);
    let first: Vec<u32> = order[..head]
        .iter()
        .copied()
        .filter(|&v| free(v))
        .take(count)
        .collect();
    if first.len() == count || head == order.len() {
        return first;
    }
    let mut order: Vec<u32> = order.into_iter().filter(|&v| free(v)).collect();
    if count < order.len() {
        order.select_nth_unstable_by(count - 1, cmp);
        order.truncate(count);
    }
    order.sort_by(cmp);
    order
}

#[cfg(test)]
mod tests {
    use super::running_sums;

    /// Each fused product is the running sum of one pass per product, to the last bit, for
    /// one to four columns at a time.
    #[test]
    fn fused_products_are_the_running_sums_bit_for_bit() {
        let n = 5_861;
        let column = |s: usize| -> Vec<f64> {
            (0..n)
                .map(|i| (((i * (7 + s) + 3 * s) % 101) as f64 - 50.0) / (3.0 + s as f64))
                .collect()
        };
        let a = column(0);
        let others: Vec<Vec<f64>> = (1..=4).map(column).collect();
        for k in 1..=4 {
            let slices: Vec<&[f64]> = others[..k].iter().map(|b| b.as_slice()).collect();
            let fused = running_sums(&a, &slices);
            for (b, got) in others[..k].iter().zip(&fused) {
                let single: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
                assert_eq!(got.to_bits(), single.to_bits(), "{k} columns");
            }
        }
    }
}
