//! The descent loop of CCEM on the boundary angles: direction (steepest descent,
//! Algorithm 4.1, or BFGS, Algorithm 4.2), the bijectivity guard, the line search, and
//! the stopping rules.
//!
//! The guard keeps every gap between consecutive boundary angles at least `floor`:
//! - gaps already at the floor that the direction would shrink are held (their vertices
//!   move together: the direction is projected);
//! - a straight step goes at most `ρ` of the way to the nearest collision and never below
//!   the floor;
//! - when the straight step is cut short, the step continues on the projected path
//!   `Π(θ + α d)` (Bertsekas-style projected search), which sets the gaps that would close
//!   to the floor, so that many boundary vertices can reach the floor in one step.

use crate::angles::{
    gaps, hold_gaps_at_floor, largest_gap, max_step, project_to_floor, remove_mean,
};
use crate::ccem::energy::{dot, evaluate, quadratic_coefficients, step, Eval};
use crate::ccem::hessian::Preconditioner;
use crate::ccem::line_search::{is_wolfe, wolfe_search, LineOutcome, LinePoint, WolfeParams};
use crate::ccem::options::{CcemOptions, CcemVariant};
use crate::ccem::qn::Bfgs;
use crate::ccem::schur::Schur;
use crate::report::{LineSearchReport, StepRecord};

/// Euclidean norm.
pub(crate) fn norm(v: &[f64]) -> f64 {
    dot(v, v).sqrt()
}

/// The rounding level of `E_C`, in units of `ε · (½ fᴴAf + |Area|)`: decreases below it are
/// noise.
pub(crate) const ROUNDING_ULPS: f64 = 64.0;

/// Why a descent stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stop {
    /// A Wolfe step lowered `E_C` by at most `tol · E_C`.
    Tolerance,
    /// No decrease was left above the rounding level of `E_C` (or the projected gradient
    /// vanished).
    Rounding,
    /// The line search found no decrease although one was predicted.
    Stalled,
    /// The iteration cap.
    MaxIter,
}

/// BFGS pairs a model must hold for a tolerance stop to restart it instead: a model of
/// fewer pairs is fresh, and its small decrease is taken as the minimum.
const RESTART_MIN_PAIRS: usize = 2;

/// The state of one CCEM minimization.
pub(crate) struct Descent<'s, 'a, 'm> {
    pub schur: &'s Schur<'a, 'm>,
    pub options: &'s CcemOptions,
    pub params: WolfeParams,
    /// Current floor on gaps.
    pub floor: f64,
    pub history: Vec<f64>,
    /// The first entry of `history` at the current floor (the returned iterate is the
    /// least from there on; see `SolverReport::best_from`).
    pub best_from: usize,
    pub gnorm: Vec<f64>,
    pub ls: LineSearchReport,
    /// Gaps held at the floor by the last direction.
    pub held: usize,
    pub bfgs: Bfgs,
    pub iterations: usize,
    /// The factored Hessian at the start, used as BFGS's `H₀` (and for the first step)
    /// until a search along its direction stalls.
    pub precond: Option<Preconditioner>,
    /// Whether a preconditioner was dropped after a stall.
    pub precond_dropped: bool,
}

/// One accepted step, or why there is none.
enum StepResult {
    Accepted(Box<Eval>, StepRecord),
    /// The line search found no decrease; `predicted` is the decrease the first trial
    /// promised (`−slope · α₀`).
    Stalled {
        predicted: f64,
    },
}

impl<'s, 'a, 'm> Descent<'s, 'a, 'm> {
    /// A descent with the given schur complement and options, starting with an empty log.
    pub fn new(schur: &'s Schur<'a, 'm>, options: &'s CcemOptions) -> Self {
        Self {
            schur,
            options,
            params: WolfeParams {
                gamma1: options.gamma1,
                gamma2: options.gamma2,
                max_evals: options.max_line_evals,
            },
            floor: options.min_gap,
            history: Vec::new(),
            best_from: 0,
            gnorm: Vec::new(),
            ls: LineSearchReport::default(),
            held: 0,
            bfgs: Bfgs::new(options.qn_memory, false),
            iterations: 0,
            precond: None,
            precond_dropped: false,
        }
    }

    /// Norm of the projected gradient: `∇E` with its mean removed and the components that
    /// would push gaps at the floor further down averaged out. It is `‖∇E‖` when no gap is
    /// at the floor, and it vanishes at a minimum of `E_C` under the guard.
    pub fn projected_gradient_norm(&self, cur: &Eval) -> f64 {
        let mut d: Vec<f64> = cur.grad.iter().map(|x| -x).collect();
        remove_mean(&mut d);
        hold_gaps_at_floor(&gaps(&cur.theta), &mut d, self.floor);
        norm(&d)
    }

    /// Logs a state reached other than by a step (the start, a projection onto a raised
    /// floor).
    pub fn log_state(&mut self, cur: &Eval) {
        self.history.push(cur.energy);
        self.gnorm.push(self.projected_gradient_norm(cur));
    }

    /// Iterates from `cur` until a stopping rule holds; returns the last iterate.
    pub fn minimize(&mut self, mut cur: Eval) -> (Eval, Stop) {
        let qn = self.options.variant == CcemVariant::QuasiNewton;
        while self.iterations < self.options.max_iter {
            let (d, slope) = self.direction(&cur, qn);
            let quadratic = !qn || self.bfgs.is_empty();
            // a unit quasi-Newton step promises at most −slope: when that is below the
            // rounding level of E_C (a difference of two terms of size `scale`), no line
            // search can measure a decrease (on a 1M-face square it spent 30 evaluations per
            // step trying)
            if !quadratic && -slope <= ROUNDING_ULPS * f64::EPSILON * cur.scale {
                return (cur, Stop::Rounding);
            }
            let (new, record) = match self.step(&cur, &d, slope, quadratic) {
                StepResult::Accepted(new, record) => (new, record),
                StepResult::Stalled { predicted } => {
                    if self.precond.is_some() {
                        // retry as the plain Algorithm 4.2 from here
                        self.precond = None;
                        self.precond_dropped = true;
                        self.bfgs.reset();
                        continue;
                    }
                    if qn && !self.bfgs.is_empty() {
                        // retry along the steepest descent before giving up
                        self.bfgs.reset();
                        self.ls.gradient_fallbacks += 1;
                        continue;
                    }
                    let noise = ROUNDING_ULPS * f64::EPSILON * cur.scale;
                    let small = predicted <= noise.max(self.options.tol * cur.energy.abs());
                    return (cur, if small { Stop::Rounding } else { Stop::Stalled });
                }
            };
            self.iterations += 1;
            let drop = cur.energy - new.energy;
            if qn {
                let s: Vec<f64> = new
                    .theta
                    .iter()
                    .zip(&cur.theta)
                    .map(|(a, b)| a - b)
                    .collect();
                let y: Vec<f64> = new.grad.iter().zip(&cur.grad).map(|(a, b)| a - b).collect();
                self.bfgs.update(s, y);
            }
            self.record(record);
            cur = *new;
            self.log_state(&cur);
            if record.kind == "wolfe" && drop <= self.options.tol * cur.energy.abs() {
                // one small decrease is no proof of a minimum when the quasi-Newton model
                // is stale (gaps held at the floor bend the energy surface the pairs
                // describe): restart from the preconditioner alone, and stop only when
                // the steps of a fresh model meet the tolerance too (igea_open.obj: the
                // stale model stopped 7.6e-5 above the minimum after 125 iterations)
                if qn && self.bfgs.len() >= RESTART_MIN_PAIRS {
                    self.bfgs.reset();
                    self.ls.qn_restarts += 1;
                    // with the Hessian preconditioner the fresh model's Newton step
                    // predicts its decrease, −½ ∇E·d: when that meets the tolerance too,
                    // stop here instead of searching for it at the rounding level (a
                    // 250k-face cap: 22 evaluations spent finding nothing)
                    // (only the whole Hessian predicts it: a banded model underestimates
                    // the decrease along the directions its band leaves out)
                    if self.precond.as_ref().is_some_and(|p| p.band.is_none()) {
                        let (_, slope) = self.direction(&cur, qn);
                        if -0.5 * slope <= self.options.tol * cur.energy.abs() {
                            return (cur, Stop::Tolerance);
                        }
                    }
                    continue;
                }
                return (cur, Stop::Tolerance);
            }
        }
        (cur, Stop::MaxIter)
    }

    /// Direction at `cur`: quasi-Newton (when pairs are stored) or steepest descent, mean
    /// removed, gaps at the floor held. Returns the direction and its slope `∇E·d`.
    fn direction(&mut self, cur: &Eval, qn: bool) -> (Vec<f64>, f64) {
        let g = &cur.grad;
        let gp = gaps(&cur.theta);
        if let Some(h) = &self.precond {
            let mut d = if qn && !self.bfgs.is_empty() {
                self.bfgs.direction_with(g, |q| h.apply_inverse(q))
            } else {
                let mut q: Vec<f64> = g.iter().map(|x| -x).collect();
                h.apply_inverse(&mut q);
                q
            };
            remove_mean(&mut d);
            self.held = hold_gaps_at_floor(&gp, &mut d, self.floor);
            let s = dot(g, &d);
            if s < -1e-8 * norm(g) * norm(&d) {
                return (d, s);
            }
        }
        if qn && !self.bfgs.is_empty() {
            let mut d = self.bfgs.direction(g);
            remove_mean(&mut d);
            self.held = hold_gaps_at_floor(&gp, &mut d, self.floor);
            let s = dot(g, &d);
            // a descent direction at a sane angle to the gradient
            if s < -1e-8 * norm(g) * norm(&d) {
                return (d, s);
            }
            self.ls.gradient_fallbacks += 1;
        }
        let mut d: Vec<f64> = g.iter().map(|x| -x).collect();
        remove_mean(&mut d);
        self.held = hold_gaps_at_floor(&gp, &mut d, self.floor);
        let s = dot(g, &d);
        (d, s)
    }

    /// One iteration from `cur` along `d`: the Wolfe search on the straight path up to
    /// the guard, then, if the guard cut it, the projected path.
    fn step(&mut self, cur: &Eval, d: &[f64], slope: f64, quadratic: bool) -> StepResult {
        let gp = gaps(&cur.theta);
        let to_zero = max_step(&gp, d, 0.0);
        let to_floor = max_step(&gp, d, self.floor);
        let alpha_max = (self.options.rho * to_zero).min(to_floor);
        if !(slope < 0.0) {
            return StepResult::Stalled { predicted: 0.0 };
        }
        let alpha0 = if quadratic {
            // Eq. 4.6; a concave model gives no step: try the guard's limit
            let (c1, c2) = quadratic_coefficients(self.schur, cur, d);
            if c2 > 0.0 {
                -c1 / (2.0 * c2)
            } else {
                alpha_max.min(1.0)
            }
        } else {
            1.0
        };
        let predicted = -slope * alpha0;
        if !(alpha_max > 0.0) {
            return self.projected_only(cur, d, alpha0, predicted);
        }
        let mut tried: Vec<Eval> = Vec::new();
        let schur = self.schur;
        let (outcome, evals) =
            wolfe_search(&self.params, cur.energy, slope, alpha0, alpha_max, |a| {
                let e = evaluate(schur, step(&cur.theta, d, a));
                let p = LinePoint {
                    alpha: a,
                    value: e.energy,
                    slope: dot(&e.grad, d),
                    id: tried.len(),
                };
                tried.push(e);
                p
            });
        self.ls.evaluations += evals;
        let (point, kind) = match outcome {
            LineOutcome::Wolfe(p) => (p, "wolfe"),
            LineOutcome::AtLimit(p) => (p, "guard"),
            LineOutcome::DecreaseOnly(p) => (p, "decrease"),
            LineOutcome::Failed => return StepResult::Stalled { predicted },
        };
        debug_assert!(
            kind != "wolfe" || is_wolfe(&self.params, cur.energy, slope, &point),
            "the line search returned a non-Wolfe point as Wolfe"
        );
        debug_assert!(
            point.value <= cur.energy,
            "an accepted step raised the energy"
        );
        if point.id >= tried.len() {
            return StepResult::Stalled { predicted };
        }
        let mut new = tried.swap_remove(point.id);
        let mut record = StepRecord {
            alpha: point.alpha,
            alpha_max,
            energy_before: cur.energy,
            energy_after: point.value,
            slope_before: slope,
            slope_after: point.slope,
            evaluations: evals,
            kind,
        };
        if kind == "guard" {
            // the minimizer along the line lies past a collision: bend the path onto the
            // feasible set and take the longer, projected step if it decreases enough
            let trial = alpha0.max(4.0 * alpha_max);
            if let Some((e, a, n)) = self.projected_step(cur, d, alpha_max, trial) {
                if e.energy < new.energy {
                    record.alpha = a;
                    record.energy_after = e.energy;
                    record.slope_after = dot(&e.grad, d);
                    record.kind = "projected";
                    new = e;
                }
                record.evaluations += n;
            }
        }
        StepResult::Accepted(Box::new(new), record)
    }

    /// The step when the straight path is blocked at once (a gap within rounding of the
    /// floor that the direction shrinks): the projected path only.
    fn projected_only(&mut self, cur: &Eval, d: &[f64], alpha0: f64, predicted: f64) -> StepResult {
        match self.projected_step(cur, d, 0.0, alpha0) {
            Some((e, a, n)) => {
                let record = StepRecord {
                    alpha: a,
                    alpha_max: 0.0,
                    energy_before: cur.energy,
                    energy_after: e.energy,
                    slope_before: dot(&cur.grad, d),
                    slope_after: dot(&e.grad, d),
                    evaluations: n,
                    kind: "projected",
                };
                StepResult::Accepted(Box::new(e), record)
            }
            None => StepResult::Stalled { predicted },
        }
    }

    /// Backtracking along the projected path `Π(θ + α d)` (gaps kept at least `floor`)
    /// from `trial` down towards `alpha_free`, where the straight path meets the guard.
    /// Accepts the first point with sufficient decrease along the actual displacement:
    /// `E(x) ≤ E(θ) + γ₁ ∇E·(x − θ)` (and `E(x) < E(θ)`). Returns the point, its `α` and
    /// the evaluations spent.
    fn projected_step(
        &mut self,
        cur: &Eval,
        d: &[f64],
        alpha_free: f64,
        trial: f64,
    ) -> Option<(Eval, f64, usize)> {
        let cut = largest_gap(&cur.theta);
        let mut a = trial;
        let mut evals = 0;
        let mut found = None;
        while evals < self.options.max_line_evals && a > alpha_free * (1.0 + 1e-3) && a > 0.0 {
            if let Some(x) = project_to_floor(&step(&cur.theta, d, a), self.floor, cut) {
                let e = evaluate(self.schur, x);
                evals += 1;
                let moved: f64 = e
                    .theta
                    .iter()
                    .zip(&cur.theta)
                    .zip(&cur.grad)
                    .map(|((x, t), g)| g * (x - t))
                    .sum();
                if moved < 0.0
                    && e.energy < cur.energy
                    && e.energy <= cur.energy + self.options.gamma1 * moved
                {
                    found = Some((e, a, evals));
                    break;
                }
            }
            a = alpha_free + 0.5 * (a - alpha_free);
        }
        self.ls.evaluations += evals;
        found
    }

    fn record(&mut self, record: StepRecord) {
        match record.kind {
            "wolfe" => self.ls.wolfe_steps += 1,
            "guard" => self.ls.guard_limited_steps += 1,
            "projected" => self.ls.projected_steps += 1,
            _ => self.ls.decrease_only_steps += 1,
        }
        if self.options.record_steps {
            self.ls.steps.push(record);
        }
    }
}
