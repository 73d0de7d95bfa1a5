//! The uniformity energy (Jin et al. 2004, Eq. 6–7, made scale-free) over the coefficient
//! sphere: its analytic gradient and Hessian from the per-face area forms, a saddle-free
//! Newton method on the sphere, and the seeded multistart.
//!
//! In whitened coordinates `μ` (see `products.rs`) the layout area of face `f` is
//! `a_f = μᵀ Q̃_f μ`, the total `A = |μ|²`, and the energy
//! `E(μ) = Σ_f (a_f / A − s_f)²` (`s_f = S_f / ΣS`) is homogeneous of degree 0, so it is
//! optimized on the unit sphere. At `|μ| = 1`, with `u_f = Q̃_f μ`, `r_f = a_f − s_f`,
//! `R = Σ r_f u_f`, `ρ = Σ r_f a_f`:
//! - `∇E = 4 (R − ρ μ)` (tangent to the sphere: `μ · ∇E = 0`);
//! - `∇²E = 8 Σ (u_f − a_f μ)(u_f − a_f μ)ᵀ + 4 Σ r_f Q̃_f − 8 (R μᵀ + μ Rᵀ) − 4ρ I
//!   + 16 ρ μ μᵀ`.
//!
//! Each evaluation reads an [`EnergyModel`]: the moments of `moments.rs` (`n⁴` flops,
//! `n = 2g`, never the faces) or the direct face sums of `faces.rs` (`O(F n²)`), whichever
//! `faces::use_moments` finds cheaper; `energy` (tests only) is the one-pass sum over the
//! area forms of `products.rs`, an independent check.

use crate::forms::dense::symmetric_eigen;
use crate::forms::optimal::aggregates::Aggregates;
use crate::forms::optimal::faces::FaceForms;
use crate::forms::optimal::moments::Moments;
#[cfg(test)]
use crate::forms::optimal::products::AreaProducts;

/// The search stops when `|∇E| ≤ GRADIENT_TOL · E`. Default `1e-9`: Newton converges
/// quadratically, so the last step takes the energy to rounding level; distinct optima
/// differ by 0.1 % or more (papers README), far above this.
pub const GRADIENT_TOL: f64 = 1e-9;

/// The gradient test's energy is floored at `ROUNDING · Σ s_f²` (the scale of the moments'
/// three terms, see `moments.rs`). Default `1e-6`: the moments evaluate `E` with an absolute
/// error near `1e-16 · Σ s_f²`, so a relative gradient test on an energy far below that
/// scale could never be met; real genus ≥ 2 forms (zeros) stay far above the floor.
pub const ROUNDING: f64 = 1e-6;

/// The search also stops, converged, when the Newton decrement `−∇E·d` (the decrease the
/// quadratic model promises) is below `NEWTON_DECREMENT_TOL · E`. Default `1e-14`, about 50
/// rounding units: the energy cannot resolve a smaller decrease, so the gradient test
/// (`|∇E| ≤ 1e-9 E`) may be out of reach at an optimum whose gradient is at its rounding
/// floor (measured: `|∇E| ≈ 1.8e-12` at `E ≈ 1e-3` on eightsim, with the line search
/// accepting noise-level steps until the iteration cap). The direct face sums use their
/// own, larger rounding bound `F ε` ([`EnergyModel::resolution`]).
pub const NEWTON_DECREMENT_TOL: f64 = 1e-14;

/// Newton iterations per start at most. Default 100: converged starts need 5–15.
pub const MAX_NEWTON_ITERATIONS: usize = 100;

/// Armijo sufficient-decrease constant. Default `1e-4` (Nocedal–Wright).
pub const ARMIJO: f64 = 1e-4;

/// Step halvings per line search at most. Default 40 (a step of `2^-40`: no progress left).
pub const MAX_HALVINGS: usize = 40;

/// Hessian eigenvalues are floored at this fraction of the largest `|eigenvalue|` before
/// inversion. Default `1e-10`: the rotation `φ → e^{iθ} φ` makes one tangent direction
/// flat at every optimum; the floor keeps the step finite there.
pub const HESSIAN_FLOOR: f64 = 1e-10;

/// Tangent directions whose Hessian eigenvalue is below this fraction of the largest in
/// absolute value are searched on their great circle instead of by the Newton step:
/// `1e-3`. The rotation `φ → e^{iθ} φ` of the form is nearly flat (measured on
/// armadillo's slit surfaces: `|λ| ≈ 1e-4` of the largest, slightly negative, the next
/// eigenvalue `1e-2`); a Newton step along it is `g·v/|λ|`, large and meaningless for a
/// non-quadratic direction, and the saddle-free search crawled along it, one rotation of
/// about 0.1 per step, the gradient falling by ~10 % per step (20–30 Newton steps per
/// start). On the circle the energy is a trigonometric polynomial of degree 2 in `2θ`
/// ([`EnergyModel::great_circle`], one `O(F n)` pass): its exact minimum is one step.
/// Only for models with a great circle (the direct sums); the moments keep the plain
/// saddle-free step.
pub const FLAT_RELATIVE: f64 = 1e-3;

/// The great-circle search of the near-flat directions ([`FLAT_RELATIVE`]) runs when
/// their share of the gradient norm is at least this: `0.5` (or when no curved step is
/// left). While the curved directions dominate the gradient the Newton step shrinks them
/// quadratically and the circle (two `O(F n)` passes) would gain little; on all faces of
/// armadillo every pass streams 83 MB, and the search is bound by memory traffic.
pub const CIRCLE_SHARE: f64 = 0.5;

/// A Newton step's Hessian is kept for the next step when the step was a full one (the
/// line search's first trial accepted) and the gradient norm fell below this fraction of
/// its value before the step: `0.4`. That is the local regime, where the Hessian barely
/// changes between iterates and the step with the kept one (a chord step) contracts the
/// gradient nearly as fast as a fresh one; the next step that contracts less gets a fresh
/// Hessian. Only for models whose gradient is cheap ([`EnergyModel::cheap_gradient`]: the
/// direct sums, `O(F n)` against `O(F n²)` per Hessian): with the great-circle steps and the
/// seeded levels, armadillo's searches take about half as many Hessians as Newton steps
/// (docs/benchmarks.md, issue 23, second pass). Far from an optimum (damped steps) every step gets a
/// fresh Hessian, as before, so a start descends into the same basin. Was `0.25`: the
/// polish on all faces contracted the gradient ~0.3 per step with fresh Hessians and with
/// the kept one alike (the energy's nonlinearity, not the Hessian, limits those steps), so
/// 0.25 bought a full `O(F n²)` Hessian for nothing; with 0.4 the genus-15 searches take
/// 5–12 % fewer Hessians and the same optima (energies equal to 8 digits on armadillo,
/// brain, kitten_53k and hand; issue 23, third pass).
pub const HESSIAN_REUSE_CONTRACTION: f64 = 0.4;

/// The energy and, optionally, gradient and Hessian at a unit `μ`.
pub struct Evaluation {
    /// `E(μ)`.
    pub energy: f64,
    /// `∇E` (empty when not requested).
    pub gradient: Vec<f64>,
    /// `∇²E`, row-major (empty when not requested).
    pub hessian: Vec<f64>,
}

/// `E(μ)` for `μ ≠ 0` (any length: the energy is scale-free), summed over the area forms
/// (the independent check of the tests).
#[cfg(test)]
pub fn energy(p: &AreaProducts, mu: &[f64]) -> f64 {
    let n = p.n;
    let norm2: f64 = mu.iter().map(|x| x * x).sum();
    let mut e = 0.0;
    for f in 0..p.faces() {
        let q = p.face(f);
        let mut a = 0.0;
        for i in 0..n {
            let row: f64 = (0..n).map(|j| q[i * n + j] * mu[j]).sum();
            a += mu[i] * row;
        }
        e += (a / norm2 - p.s[f]).powi(2);
    }
    e
}

/// What a Newton search needs of the energy: its value anywhere and its aggregates (for
/// the gradient and Hessian) at unit points. Two models: the moments of `moments.rs` and
/// the direct face sums of `faces.rs`, picked by `faces::use_moments`.
pub trait EnergyModel: Sync {
    /// `2g`.
    fn dim(&self) -> usize;
    /// `Σ s_f²`: the energy's scale, for rounding-level tolerances (see [`ROUNDING`]).
    fn scale(&self) -> f64;
    /// `E(μ)` for `μ ≠ 0` (any length).
    fn energy(&self, mu: &[f64]) -> f64;
    /// The sums of [`Aggregates`] at a unit `μ`.
    fn aggregates(&self, mu: &[f64]) -> Aggregates;
    /// `E` and `∇E = 4 (R − ρ μ)` at a unit `μ` (see the module docs), without the
    /// Hessian. Default: from [`Self::aggregates`].
    fn first_order(&self, mu: &[f64]) -> (f64, Vec<f64>) {
        let a = self.aggregates(mu);
        let gradient = (0..mu.len())
            .map(|i| 4.0 * (a.big_r[i] - a.rho * mu[i]))
            .collect();
        (a.energy, gradient)
    }
    /// Whether [`Self::first_order`] costs much less than [`Self::aggregates`] (then a
    /// search may keep a Hessian across steps, see [`HESSIAN_REUSE_CONTRACTION`], and
    /// searches the near-flat directions on their great circle, see [`FLAT_RELATIVE`]).
    /// Default `false`.
    fn cheap_gradient(&self) -> bool {
        false
    }
    /// The energy on the great circle `cos θ μ + sin θ w` (unit, orthogonal `μ` and `w`)
    /// as the six sums `c` of `E(φ) = c₀ + 2c₁ cos φ + 2c₂ sin φ + c₃ cos²φ + c₄ sin²φ +
    /// 2c₅ cos φ sin φ`, `φ = 2θ` (each face's area is `p + q cos φ + r sin φ` there).
    /// Default `None` (no such form).
    fn great_circle(&self, _mu: &[f64], _w: &[f64]) -> Option<[f64; 6]> {
        None
    }
    /// The smallest relative decrease of the energy the model resolves: a search stops
    /// when its Newton model (or the great circle) promises less. Default
    /// [`NEWTON_DECREMENT_TOL`].
    fn resolution(&self) -> f64 {
        NEWTON_DECREMENT_TOL
    }
}

impl EnergyModel for Moments {
    fn dim(&self) -> usize {
        self.n
    }
    fn scale(&self) -> f64 {
        Moments::scale(self)
    }
    fn energy(&self, mu: &[f64]) -> f64 {
        Moments::energy(self, mu)
    }
    fn aggregates(&self, mu: &[f64]) -> Aggregates {
        Moments::aggregates(self, mu)
    }
}

impl EnergyModel for FaceForms {
    fn dim(&self) -> usize {
        self.n
    }
    fn scale(&self) -> f64 {
        self.weight * self.s.iter().map(|s| s * s).sum::<f64>()
    }
    fn energy(&self, mu: &[f64]) -> f64 {
        FaceForms::energy(self, mu)
    }
    fn aggregates(&self, mu: &[f64]) -> Aggregates {
        FaceForms::aggregates(self, mu)
    }
    fn first_order(&self, mu: &[f64]) -> (f64, Vec<f64>) {
        FaceForms::first_order(self, mu)
    }
    fn cheap_gradient(&self) -> bool {
        true
    }
    fn great_circle(&self, mu: &[f64], w: &[f64]) -> Option<[f64; 6]> {
        Some(FaceForms::great_circle(self, mu, w))
    }
    /// `F ε` (at least [`NEWTON_DECREMENT_TOL`]): the rounding bound of a sum of `F`
    /// face terms; below it the direct sums cannot tell a decrease from noise (at 86k
    /// faces `1.9e-11`: the last one or two polish steps on all faces chased it).
    fn resolution(&self) -> f64 {
        (self.faces() as f64 * f64::EPSILON).max(NEWTON_DECREMENT_TOL)
    }
}

/// Energy, gradient and Hessian at a unit `μ`, from the model's aggregates.
pub fn evaluate<M: EnergyModel + ?Sized>(model: &M, mu: &[f64]) -> Evaluation {
    let n = model.dim();
    let nn = n * n;
    let Aggregates {
        energy: e,
        rho,
        a2,
        big_r,
        au,
        uu,
        rq,
    } = model.aggregates(mu);
    let gradient: Vec<f64> = (0..n).map(|i| 4.0 * (big_r[i] - rho * mu[i])).collect();
    let mut hessian = vec![0.0; nn];
    for i in 0..n {
        for j in i..n {
            let gauss = uu[i * n + j] - au[i] * mu[j] - mu[i] * au[j] + a2 * mu[i] * mu[j];
            let delta = if i == j { 1.0 } else { 0.0 };
            let h = 8.0 * gauss + 4.0 * rq[i * n + j]
                - 8.0 * (big_r[i] * mu[j] + mu[i] * big_r[j])
                - 4.0 * rho * delta
                + 16.0 * rho * mu[i] * mu[j];
            hessian[i * n + j] = h;
            hessian[j * n + i] = h;
        }
    }
    Evaluation {
        energy: e,
        gradient,
        hessian,
    }
}

/// One local search's outcome.
#[derive(Debug, Clone)]
pub struct LocalOptimum {
    /// Unit whitened coefficients.
    pub mu: Vec<f64>,
    /// Energy there.
    pub energy: f64,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Whether the gradient test was met.
    pub converged: bool,
    /// Hessians evaluated (at most `iterations + 1`; fewer when kept across steps, see
    /// [`HESSIAN_REUSE_CONTRACTION`], or seeded, see [`local_search_seeded`]).
    pub hessians: usize,
    /// The last Hessian the search used (row-major, ambient coordinates): a seed for the
    /// search on a finer level.
    pub hessian: Vec<f64>,
}

fn normalized(v: &[f64]) -> Vec<f64> {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.iter().map(|x| x / norm).collect()
}

/// Saddle-free Newton on the unit sphere from `start`, minimizing `E` (`maximize`:
/// minimizing `−E`). The step solves with `|P H P|` (eigenvalues in absolute value,
/// floored), `P = I − μμᵀ`, restricted to the tangent space; retraction by normalization,
/// Armijo backtracking. In the local regime the Hessian is kept across steps (see
/// [`HESSIAN_REUSE_CONTRACTION`]); the gradient is always fresh, so the tests are exact.
pub fn local_search<M: EnergyModel + ?Sized>(
    moments: &M,
    start: &[f64],
    maximize: bool,
) -> LocalOptimum {
    local_search_seeded(moments, start, maximize, None)
}

/// [`local_search`] whose first step uses the Hessian `seed` (ambient coordinates, as
/// [`LocalOptimum::hessian`]) instead of a fresh one, when the model's gradient is cheap
/// ([`EnergyModel::cheap_gradient`]): a start refined from a coarser level's optimum takes
/// that level's last Hessian. Near the optimum the sampled faces' Hessian is close to all
/// faces' one, so the first steps are chord steps at `O(F n)` each; the first step that
/// contracts the gradient by less than [`HESSIAN_REUSE_CONTRACTION`] gets a fresh Hessian.
pub fn local_search_seeded<M: EnergyModel + ?Sized>(
    moments: &M,
    start: &[f64],
    maximize: bool,
    seed: Option<&[f64]>,
) -> LocalOptimum {
    let n = moments.dim();
    // the gradient test, floored at rounding level of the moments' terms (see `ROUNDING`)
    let tol = |e: f64| GRADIENT_TOL * e.max(ROUNDING * moments.scale());
    let sign = if maximize { -1.0 } else { 1.0 };
    let mut mu = normalized(start);
    let (mut ev, mut hessians) = match seed {
        Some(h) if moments.cheap_gradient() && h.len() == n * n => {
            let (energy, gradient) = moments.first_order(&mu);
            let hessian = h.to_vec();
            (
                Evaluation {
                    energy,
                    gradient,
                    hessian,
                },
                0,
            )
        }
        _ => (evaluate(moments, &mu), 1),
    };
    let mut last_full = false;
    for it in 0..MAX_NEWTON_ITERATIONS {
        let g: Vec<f64> = ev.gradient.iter().map(|x| sign * x).collect();
        let gnorm = g.iter().map(|x| x * x).sum::<f64>().sqrt();
        if gnorm <= tol(ev.energy) {
            return LocalOptimum::at(mu, ev, it, true, hessians);
        }
        // P H P
        let h: Vec<f64> = ev.hessian.iter().map(|x| sign * x).collect();
        let mut ph = vec![0.0; n * n];
        let hmu: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| h[i * n + j] * mu[j]).sum())
            .collect();
        let muhmu: f64 = (0..n).map(|i| mu[i] * hmu[i]).sum();
        for i in 0..n {
            for j in 0..n {
                ph[i * n + j] =
                    h[i * n + j] - mu[i] * hmu[j] - hmu[i] * mu[j] + mu[i] * mu[j] * muhmu;
            }
        }
        let (eig, vecs) = tangent_eigen(&ph, n);
        let top = eig.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let floor = (HESSIAN_FLOOR * top).max(f64::MIN_POSITIVE);
        // near-flat directions go to the great-circle search when the model has one
        let flat_below = if moments.cheap_gradient() {
            FLAT_RELATIVE * top
        } else {
            0.0
        };
        let mut d = vec![0.0; n];
        let mut flat = vec![0.0; n];
        for (k, &lam) in eig.iter().enumerate() {
            let v: Vec<f64> = (0..n).map(|i| vecs[i * n + k]).collect();
            let along: f64 = (0..n).map(|i| v[i] * mu[i]).sum();
            if along.abs() > 0.5 {
                continue; // the normal direction μ itself
            }
            let gv: f64 = (0..n).map(|i| g[i] * v[i]).sum();
            if lam.abs() < flat_below {
                for i in 0..n {
                    flat[i] -= gv * v[i];
                }
                continue;
            }
            let scale = gv / lam.abs().max(floor);
            for i in 0..n {
                d[i] -= scale * v[i];
            }
        }
        let slope: f64 = (0..n).map(|i| g[i] * d[i]).sum();
        let flat_norm = flat.iter().map(|x| x * x).sum::<f64>().sqrt();
        let curved = -slope > moments.resolution() * ev.energy.abs();
        if !curved && flat_norm <= tol(ev.energy) {
            // the Newton model promises no decrease the energy can resolve
            return LocalOptimum::at(mu, ev, it, true, hessians);
        }
        let mut accepted = Some((mu.clone(), false));
        let mut moved = false;
        // the first trial's energy and gradient, when it is likely to be accepted (the
        // last step was a full one): the gradient at the new point then comes for free
        let mut known: Option<(f64, Vec<f64>)> = None;
        if curved {
            accepted = None;
            let mut t = 1.0;
            for halvings in 0..MAX_HALVINGS {
                let trial: Vec<f64> =
                    normalized(&(0..n).map(|i| mu[i] + t * d[i]).collect::<Vec<_>>());
                let et = if halvings == 0 && last_full && moments.cheap_gradient() {
                    let (e, g) = moments.first_order(&trial);
                    known = Some((e, g));
                    e
                } else {
                    known = None;
                    moments.energy(&trial)
                };
                if sign * et <= sign * ev.energy + ARMIJO * t * slope {
                    accepted = Some((trial, halvings == 0));
                    moved = true;
                    break;
                }
                t *= 0.5;
            }
        }
        // the near-flat directions: on their great circle when they hold a good share of
        // the gradient (or no curved step is left)
        let flat_due = !curved || flat_norm >= CIRCLE_SHARE * gnorm;
        if let Some((next, _)) = accepted.as_mut() {
            if flat_due && flat_norm > tol(ev.energy) {
                if let Some(rotated) = circle_step(moments, next, &flat, sign, ev.energy) {
                    *next = rotated;
                    moved = true;
                    known = None;
                }
            }
        }
        if !moved {
            // neither the Newton step nor the great circle resolves a decrease
            return LocalOptimum::at(mu, ev, it, true, hessians);
        }
        match accepted {
            Some((next, full_step)) => {
                mu = next;
                last_full = full_step;
                ev = next_evaluation(moments, &mu, ev, (full_step, gnorm, known), &mut hessians);
            }
            None => {
                let converged = gnorm <= 1e3 * tol(ev.energy);
                return LocalOptimum::at(mu, ev, it, converged, hessians);
            }
        }
    }
    LocalOptimum::at(mu, ev, MAX_NEWTON_ITERATIONS, false, hessians)
}

impl LocalOptimum {
    /// The search's outcome at `mu`, evaluated as `ev` (its Hessian kept as the seed).
    fn at(
        mu: Vec<f64>,
        ev: Evaluation,
        iterations: usize,
        converged: bool,
        hessians: usize,
    ) -> Self {
        Self {
            mu,
            energy: ev.energy,
            iterations,
            converged,
            hessians,
            hessian: ev.hessian,
        }
    }
}

/// The eigen decomposition of the symmetric `n × n` row-major `a` (eigenvalues, and the
/// eigenvectors as the columns of a row-major matrix, as `dense::symmetric_eigen`) by
/// faer's tridiagonal divide and conquer: at `n = 30` about 20× faster than the cyclic
/// Jacobi sweeps, which cost as much as a Hessian of the moments or of a coarse level and
/// ran once per Newton step. Falls back to Jacobi if faer's iteration fails.
fn tangent_eigen(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| a[i * n + j]);
    match m.self_adjoint_eigen(faer::Side::Lower) {
        Ok(evd) => {
            let (s, u) = (evd.S(), evd.U());
            let values = (0..n).map(|k| s.column_vector()[k]).collect();
            let vectors = (0..n * n).map(|k| u[(k / n, k % n)]).collect();
            (values, vectors)
        }
        Err(_) => symmetric_eigen(a, n),
    }
}

/// The minimum of `sign · E` on the great circle through the unit `mu` in the tangent
/// direction of `flat` (projected onto the tangent space at `mu`), from the model's exact
/// trigonometric form of the energy there ([`EnergyModel::great_circle`]); `None` when the
/// model has none or the circle offers no decrease the energy can resolve (below
/// [`EnergyModel::resolution`] of `energy`).
fn circle_step<M: EnergyModel + ?Sized>(
    model: &M,
    mu: &[f64],
    flat: &[f64],
    sign: f64,
    energy: f64,
) -> Option<Vec<f64>> {
    let along: f64 = flat.iter().zip(mu).map(|(a, b)| a * b).sum();
    let w = normalized(
        &flat
            .iter()
            .zip(mu)
            .map(|(f, m)| f - along * m)
            .collect::<Vec<_>>(),
    );
    if !w.iter().all(|x| x.is_finite()) {
        return None;
    }
    let c = model.great_circle(mu, &w)?;
    let theta = circle_minimum(&c.map(|x| sign * x));
    let value = |phi: f64| circle_energy(&c, phi);
    let gain = sign * (value(0.0) - value(2.0 * theta));
    if !(gain > model.resolution() * energy.abs()) {
        return None;
    }
    let (s, co) = theta.sin_cos();
    Some(normalized(
        &mu.iter()
            .zip(&w)
            .map(|(m, x)| co * m + s * x)
            .collect::<Vec<_>>(),
    ))
}

/// `E(φ) = c₀ + 2c₁ cos φ + 2c₂ sin φ + c₃ cos²φ + c₄ sin²φ + 2c₅ cos φ sin φ`, the energy
/// on a great circle at angle `θ = φ/2` (see [`EnergyModel::great_circle`]).
fn circle_energy(c: &[f64; 6], phi: f64) -> f64 {
    let (s, co) = phi.sin_cos();
    c[0] + 2.0 * c[1] * co + 2.0 * c[2] * s + c[3] * co * co + c[4] * s * s + 2.0 * c[5] * co * s
}

/// Samples of `φ ∈ (−π, π]` before the Newton refinement of [`circle_minimum`]: `64`. The
/// energy on a great circle is a trigonometric polynomial of degree 2 in `φ`: at most two
/// minima, each far wider than `2π/64`.
pub const CIRCLE_SAMPLES: usize = 64;

/// The angle `θ ∈ (−π/2, π/2]` minimizing [`circle_energy`] at `φ = 2θ`: the best of
/// [`CIRCLE_SAMPLES`] samples refined by Newton steps on `φ` (kept only while they descend).
fn circle_minimum(c: &[f64; 6]) -> f64 {
    let step = std::f64::consts::TAU / CIRCLE_SAMPLES as f64;
    let mut phi = (0..CIRCLE_SAMPLES)
        .map(|k| -std::f64::consts::PI + step * (k + 1) as f64)
        .min_by(|a, b| circle_energy(c, *a).total_cmp(&circle_energy(c, *b)))
        .unwrap_or(0.0);
    // exactly 0 when the circle offers nothing: keep the point
    if circle_energy(c, phi) >= circle_energy(c, 0.0) {
        phi = 0.0;
    }
    for _ in 0..8 {
        let (s, co) = phi.sin_cos();
        let d1 = -2.0 * c[1] * s
            + 2.0 * c[2] * co
            + 2.0 * (c[4] - c[3]) * s * co
            + 2.0 * c[5] * (co * co - s * s);
        let d2 = -2.0 * c[1] * co - 2.0 * c[2] * s + 2.0 * (c[4] - c[3]) * (co * co - s * s)
            - 8.0 * c[5] * s * co;
        if !(d2 > 0.0) {
            break;
        }
        let next = phi - d1 / d2;
        if !(circle_energy(c, next) < circle_energy(c, phi)) {
            break;
        }
        phi = next;
    }
    0.5 * phi
}

/// The evaluation at the new iterate `mu` after a step from the point evaluated in `last`
/// (`full_step`: the line search's first trial accepted; `gnorm`: the gradient norm before
/// the step; `known`: the energy and gradient at `mu` when the line search computed them): the fresh energy and gradient with `last`'s Hessian when the step was in the
/// local regime (see [`HESSIAN_REUSE_CONTRACTION`]), else a full evaluation (counted in
/// `hessians`).
fn next_evaluation<M: EnergyModel + ?Sized>(
    model: &M,
    mu: &[f64],
    last: Evaluation,
    (full_step, gnorm, known): (bool, f64, Option<(f64, Vec<f64>)>),
    hessians: &mut usize,
) -> Evaluation {
    if full_step && model.cheap_gradient() {
        let (energy, gradient) = known.unwrap_or_else(|| model.first_order(mu));
        let g_new = gradient.iter().map(|x| x * x).sum::<f64>().sqrt();
        if g_new <= HESSIAN_REUSE_CONTRACTION * gnorm {
            return Evaluation {
                energy,
                gradient,
                hessian: last.hessian,
            };
        }
    }
    *hessians += 1;
    evaluate(model, mu)
}
