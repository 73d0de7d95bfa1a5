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
use crate::forms::optimal::faces::FaceForms;
use crate::forms::optimal::moments::{Aggregates, Moments};
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
/// accepting noise-level steps until the iteration cap).
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
}

fn normalized(v: &[f64]) -> Vec<f64> {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.iter().map(|x| x / norm).collect()
}

/// Saddle-free Newton on the unit sphere from `start`, minimizing `E` (`maximize`:
/// minimizing `−E`). The step solves with `|P H P|` (eigenvalues in absolute value,
/// floored), `P = I − μμᵀ`, restricted to the tangent space; retraction by normalization,
/// Armijo backtracking.
pub fn local_search<M: EnergyModel + ?Sized>(
    moments: &M,
    start: &[f64],
    maximize: bool,
) -> LocalOptimum {
    let n = moments.dim();
    // the gradient test, floored at rounding level of the moments' terms (see `ROUNDING`)
    let tol = |e: f64| GRADIENT_TOL * e.max(ROUNDING * moments.scale());
    let sign = if maximize { -1.0 } else { 1.0 };
    let mut mu = normalized(start);
    let mut ev = evaluate(moments, &mu);
    for it in 0..MAX_NEWTON_ITERATIONS {
        let g: Vec<f64> = ev.gradient.iter().map(|x| sign * x).collect();
        let gnorm = g.iter().map(|x| x * x).sum::<f64>().sqrt();
        if gnorm <= tol(ev.energy) {
            return LocalOptimum {
                mu,
                energy: ev.energy,
                iterations: it,
                converged: true,
            };
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
        let (eig, vecs) = symmetric_eigen(&ph, n);
        let top = eig.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let floor = (HESSIAN_FLOOR * top).max(f64::MIN_POSITIVE);
        let mut d = vec![0.0; n];
        for (k, &lam) in eig.iter().enumerate() {
            let v: Vec<f64> = (0..n).map(|i| vecs[i * n + k]).collect();
            let along: f64 = (0..n).map(|i| v[i] * mu[i]).sum();
            if along.abs() > 0.5 {
                continue; // the normal direction μ itself
            }
            let gv: f64 = (0..n).map(|i| g[i] * v[i]).sum();
            let scale = gv / lam.abs().max(floor);
            for i in 0..n {
                d[i] -= scale * v[i];
            }
        }
        let slope: f64 = (0..n).map(|i| g[i] * d[i]).sum();
        if -slope <= NEWTON_DECREMENT_TOL * ev.energy.abs() {
            // the Newton model promises no decrease the energy can resolve
            return LocalOptimum {
                mu,
                energy: ev.energy,
                iterations: it,
                converged: true,
            };
        }
        let mut t = 1.0;
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let trial: Vec<f64> = normalized(&(0..n).map(|i| mu[i] + t * d[i]).collect::<Vec<_>>());
            let et = moments.energy(&trial);
            if sign * et <= sign * ev.energy + ARMIJO * t * slope {
                accepted = Some(trial);
                break;
            }
            t *= 0.5;
        }
        match accepted {
            Some(next) => {
                mu = next;
                ev = evaluate(moments, &mu);
            }
            None => {
                return LocalOptimum {
                    mu,
                    energy: ev.energy,
                    iterations: it,
                    converged: gnorm <= 1e3 * tol(ev.energy),
                }
            }
        }
    }
    LocalOptimum {
        mu,
        energy: ev.energy,
        iterations: MAX_NEWTON_ITERATIONS,
        converged: false,
    }
}
