//! Newton's method for the conformal energy of a disk map on its boundary angles, with the
//! Schur complement formed densely: the inner solver of every Koebe step.
//!
//! With the interior harmonic, the conformal energy of a disk map whose boundary vertices sit
//! at `f_k = e^{iθ_k}` is (CCEM Eq. 3.17, written with `f`)
//! `E(θ) = ½ fᴴ S f − A(θ)`, `A(θ) = ½ Σ_k sin(θ_{k+1} − θ_k)`, where
//! `S = L_BB − L_IBᵀ L_II⁻¹ L_IB` is the Schur complement of CCEM Eq. 3.15. Its gradient and
//! Hessian are explicit:
//! - `∂E/∂θ_m = Im(f̄_m (S f)_m) − ½ (cos(θ_m − θ_{m−1}) − cos(θ_{m+1} − θ_m))`,
//! - `∂²E/∂θ_m∂θ_j = S_mj cos(θ_m − θ_j)` (`j ≠ m`, plus the area terms of the two loop
//!   neighbours), `∂²E/∂θ_m² = S_mm − Re(f̄_m (S f)_m) + ½ (sin(θ_m − θ_{m−1}) + sin(θ_{m+1} − θ_m))`.
//!
//! `E` is unchanged by rotations and, in the continuum, by every Möbius map of the disk, so
//! the discrete energy is nearly flat along those three directions (and tends to 0 if the
//! boundary collapses onto one point). The first vertex therefore keeps its angle and the
//! boundary's vertex mean `Σ e^{iθ_k} / n_B` is held at a given point (CEM's centralization,
//! Algorithm 1 step 8, holds it at 0; a Koebe step holds it where its start has it), by
//! Newton's method on the KKT system. If the start already is the minimizer (a Koebe step on
//! a domain that is already circular) the gradient is zero and the start is returned.
//!
//! Each iteration: a Levenberg–Marquardt-safeguarded Newton direction (dense Cholesky of the
//! Hessian of the Lagrangian, shifted until positive definite, and the 2×2 system of the
//! multipliers), a step limit that keeps every boundary gap above half its length and above
//! a floor (the boundary stays in order), and Armijo backtracking on an ℓ1 merit function.

use conformap_operators::DenseCholesky;

use crate::angles::gaps;

/// Largest fraction of a boundary gap one step may close: `0.5`, so every gap keeps at least
/// half its length per step and the boundary order can never change.
const GAP_SHRINK: f64 = 0.5;
/// No boundary gap may fall below `1e-2` of its length at the start of the minimization.
/// On a coarse loop with sharp corners (the staircase holes of peaks_7holes, 20 vertices)
/// the discrete energy can keep falling as one boundary edge shrinks to nothing, a
/// collapse the continuous map does not have; the floor stops it, and the step ends
/// there (reported as not converged). A domain that is already circular moves no gap, so
/// the floor never binds at the Koebe iteration's fixed point.
const GAP_FLOOR: f64 = 1e-2;
/// Weight of the augmented-Lagrangian term `γ JᵀJ`, `γ = 2 · (largest Hessian diagonal) ·
/// n_B²` (the rows of `J` have squared norm about `1 / (2 n_B)`): enough to lift the two
/// directions the constraint removes above the rest of the spectrum.
const AUGMENT: f64 = 2.0;
/// A step limit below `1e-12` means a gap at its floor blocks the direction.
const BLOCKED_STEP: f64 = 1e-12;
/// Armijo sufficient-decrease constant: `1e-4`, the usual value (Nocedal & Wright §3.1).
const ARMIJO: f64 = 1e-4;
/// Step halvings per line search: `40` (a factor `1e-12`: a step that small is rounding).
const MAX_HALVINGS: usize = 40;
/// Once the predicted decrease `−∇E·δ` is below `1e-10 E_D`, the energy no longer resolves
/// the line search (its rounding is about `1e-16 n_B E_D`): Newton steps are taken whole
/// (they are in the quadratic regime), and the iteration ends when a step fails to halve
/// the previous one (the gradient's own rounding floor, about `1e-10` rad here).
const QUADRATIC_REGIME: f64 = 1e-10;

/// Options of [`minimize`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct NewtonOptions {
    /// Iteration cap.
    pub max_iter: usize,
    /// Stop once a full Newton step moves no angle by more than this (radians).
    pub step_tol: f64,
}

/// What [`minimize`] found.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NewtonResult {
    /// Boundary angles, unwrapped (strictly increasing, span below `2π`).
    pub theta: Vec<f64>,
    /// Newton iterations taken.
    pub iterations: usize,
    /// Whether the step (or the gradient) fell below the tolerance.
    pub converged: bool,
    /// Whether a boundary gap reached its floor and stopped the minimization.
    pub blocked: bool,
    /// `E(θ)` at the returned angles.
    pub energy: f64,
    /// Largest `|∂E/∂θ|` over the free angles at the returned angles.
    pub gradient_max: f64,
}

/// The dense symmetric Schur complement and the energy on the circle.
struct Energy<'a> {
    s: &'a [f64],
    m: usize,
}

/// Energy, gradient and the parts the Hessian needs, at one `θ`.
struct Eval {
    energy: f64,
    dirichlet: f64,
    grad: Vec<f64>,
    cos: Vec<f64>,
    sin: Vec<f64>,
    /// `Re(f̄_m (S f)_m)`.
    re: Vec<f64>,
}

impl Energy<'_> {
    fn eval(&self, theta: &[f64]) -> Eval {
        let m = self.m;
        let cos: Vec<f64> = theta.iter().map(|t| t.cos()).collect();
        let sin: Vec<f64> = theta.iter().map(|t| t.sin()).collect();
        let (mut sc, mut ss) = (vec![0.0; m], vec![0.0; m]);
        for j in 0..m {
            let col = &self.s[j * m..(j + 1) * m];
            let (cj, sj) = (cos[j], sin[j]);
            for i in 0..m {
                sc[i] += col[i] * cj;
                ss[i] += col[i] * sj;
            }
        }
        let mut dirichlet = 0.0;
        let mut area = 0.0;
        let mut grad = vec![0.0; m];
        let mut re = vec![0.0; m];
        for k in 0..m {
            let (prev, next) = ((k + m - 1) % m, (k + 1) % m);
            re[k] = cos[k] * sc[k] + sin[k] * ss[k];
            dirichlet += re[k];
            area += (theta[next] - theta[k]).sin();
            let im = cos[k] * ss[k] - sin[k] * sc[k];
            let d_area = 0.5 * ((theta[k] - theta[prev]).cos() - (theta[next] - theta[k]).cos());
            grad[k] = im - d_area;
        }
        Eval {
            energy: 0.5 * dirichlet - 0.5 * area,
            dirichlet: 0.5 * dirichlet,
            grad,
            cos,
            sin,
            re,
        }
    }

    fn value(&self, theta: &[f64]) -> f64 {
        self.eval(theta).energy
    }

    /// The Hessian restricted to the `free` angles, column-major `nf × nf`.
    fn reduced_hessian(&self, theta: &[f64], e: &Eval, free: &[usize], slot: &[usize]) -> Vec<f64> {
        let m = self.m;
        let nf = free.len();
        let mut h = vec![0.0; nf * nf];
        for (b, &j) in free.iter().enumerate() {
            let col = &self.s[j * m..(j + 1) * m];
            for (a, &i) in free.iter().enumerate() {
                h[b * nf + a] = col[i] * (e.cos[i] * e.cos[j] + e.sin[i] * e.sin[j]);
            }
        }
        for (a, &i) in free.iter().enumerate() {
            let (prev, next) = ((i + m - 1) % m, (i + 1) % m);
            let s_prev = (theta[i] - theta[prev]).sin();
            let s_next = (theta[next] - theta[i]).sin();
            h[a * nf + a] = self.s[i * m + i] - e.re[i] + 0.5 * (s_prev + s_next);
            for (nb, s) in [(prev, s_prev), (next, s_next)] {
                let b = slot[nb];
                if b != usize::MAX && nb != i {
                    h[b * nf + a] -= 0.5 * s;
                }
            }
        }
        h
    }
}

/// Minimizes `E(θ)` for the dense symmetric Schur complement `s` (column-major, `m × m`,
/// `m = theta0.len() ≥ 3`) from the unwrapped, strictly increasing angles `theta0`, with the
/// Möbius freedom fixed as the module docs say: the first vertex keeps its angle and the
/// boundary's vertex mean `Σ e^{iθ_k} / m` is held at `target`.
pub(crate) fn minimize(
    s: &[f64],
    theta0: Vec<f64>,
    target: [f64; 2],
    options: &NewtonOptions,
) -> NewtonResult {
    let m = theta0.len();
    let energy = Energy { s, m };
    let pinned: Vec<usize> = vec![0];
    let free: Vec<usize> = (0..m).filter(|k| !pinned.contains(k)).collect();
    let mut slot = vec![usize::MAX; m];
    for (a, &i) in free.iter().enumerate() {
        slot[i] = a;
    }
    // per-vertex size of the products in the gradient, for a rounding-level test
    let row_scale: Vec<f64> = (0..m)
        .map(|i| (0..m).map(|j| s[j * m + i].abs()).sum::<f64>() + 1.0)
        .collect();
    let mut theta = theta0;
    let mut cur = energy.eval(&theta);
    let mut converged = false;
    let mut iterations = 0;
    let mut lambda = [0.0, 0.0];
    let mut rho: f64 = 0.0;
    let mut previous_step = f64::INFINITY;
    let constraint = |t: &[f64]| {
        let c = centroid(t);
        [c[0] - target[0], c[1] - target[1]]
    };
    let floor: Vec<f64> = gaps(&theta).iter().map(|g| GAP_FLOOR * g).collect();
    let mut blocked = false;
    for _ in 0..options.max_iter {
        let residual = constraint(&theta);
        let feasible = residual.iter().all(|c| c.abs() <= 1e-14);
        let g: Vec<f64> = free.iter().map(|&i| cur.grad[i]).collect();
        let stationary = free.iter().enumerate().all(|(a, &i)| {
            let w = 1.0 / m as f64;
            let jt = -lambda[0] * w * theta[i].sin() + lambda[1] * w * theta[i].cos();
            (g[a] + jt).abs() <= 1e-13 * row_scale[i]
        });
        if free.is_empty() || (feasible && stationary) {
            converged = true;
            break;
        }
        let mut h = energy.reduced_hessian(&theta, &cur, &free, &slot);
        let nf = free.len();
        // the constraint's curvature: ∇²(λ·c) is diagonal
        let w = 1.0 / m as f64;
        for (a, &i) in free.iter().enumerate() {
            h[a * nf + a] += -lambda[0] * w * theta[i].cos() - lambda[1] * w * theta[i].sin();
        }
        // augmented Lagrangian: + γ JᵀJ leaves the KKT step unchanged (the multiplier
        // shifts by γ c) and makes the matrix positive definite whenever the Hessian is on
        // the constraints' tangent space, which is all the step needs
        let top = (0..nf).fold(0.0f64, |a, i| a.max(h[i * nf + i].abs()));
        let gamma = AUGMENT * top * m as f64 * m as f64;
        let rows: [Vec<f64>; 2] = [
            free.iter().map(|&i| -w * theta[i].sin()).collect(),
            free.iter().map(|&i| w * theta[i].cos()).collect(),
        ];
        for r in &rows {
            for b in 0..nf {
                for a in 0..nf {
                    h[b * nf + a] += gamma * r[a] * r[b];
                }
            }
        }
        let Some(factor) = DenseCholesky::factor_shifted(&h, nf, 1)
            .ok()
            .map(|(f, _)| f)
        else {
            break;
        };
        let mut step: Vec<f64> = g.iter().map(|v| -v).collect();
        factor.solve_in_place(&mut step, 1);
        let Some(lam) = kkt_correction(&factor, &theta, &free, m, residual, &mut step) else {
            break;
        };
        lambda = [lam[0] - gamma * residual[0], lam[1] - gamma * residual[1]];
        rho = rho.max(2.0 * lambda[0].abs().max(lambda[1].abs()));
        let mut delta = vec![0.0; m];
        for (a, &i) in free.iter().enumerate() {
            delta[i] = step[a];
        }
        let c_norm = residual[0].abs() + residual[1].abs();
        let slope: f64 = free.iter().map(|&i| cur.grad[i] * delta[i]).sum::<f64>() - rho * c_norm;
        let step_max = delta.iter().fold(0.0f64, |a, d| a.max(d.abs()));
        let alpha_max = gap_limit(&theta, &delta, &floor);
        if alpha_max <= BLOCKED_STEP {
            // a gap sits at its floor and the direction would close it further
            blocked = true;
            break;
        }
        iterations += 1;
        let merit = |t: &[f64]| {
            let c = constraint(t);
            energy.value(t) + rho * (c[0].abs() + c[1].abs())
        };
        let next = if -slope <= QUADRATIC_REGIME * cur.dirichlet.abs() {
            // the predicted decrease is below what the energy resolves: a plain Newton step
            if step_max >= 0.5 * previous_step {
                // no longer contracting: the step is at the noise floor of the gradient
                converged = true;
                break;
            }
            let alpha = alpha_max.min(1.0);
            Some(
                theta
                    .iter()
                    .zip(&delta)
                    .map(|(t, d)| t + alpha * d)
                    .collect(),
            )
        } else {
            armijo(
                &merit,
                &theta,
                &delta,
                merit(&theta),
                slope,
                alpha_max.min(1.0),
            )
        };
        let Some(next) = next else {
            break;
        };
        theta = next;
        cur = energy.eval(&theta);
        previous_step = step_max;
        if step_max <= options.step_tol {
            converged = true;
            break;
        }
    }
    let gradient_max = free.iter().fold(0.0f64, |a, &i| a.max(cur.grad[i].abs()));
    NewtonResult {
        theta,
        iterations,
        converged: converged && !blocked,
        blocked,
        energy: cur.energy,
        gradient_max,
    }
}

/// `Σ_k e^{iθ_k} / m` as `[re, im]`: the constrained vertex mean.
fn centroid(theta: &[f64]) -> [f64; 2] {
    let w = 1.0 / theta.len() as f64;
    let (mut x, mut y) = (0.0, 0.0);
    for t in theta {
        x += w * t.cos();
        y += w * t.sin();
    }
    [x, y]
}

/// Turns the unconstrained Newton step `step = −H⁻¹ g` into the KKT step of
/// [`minimize`]: with `J` the constraint's Jacobian on the free angles, solves
/// `(J H⁻¹ Jᵀ) λ = c − J H⁻¹ g` and sets `step = −H⁻¹ (g + Jᵀ λ)`. Returns `λ`.
fn kkt_correction(
    factor: &DenseCholesky,
    theta: &[f64],
    free: &[usize],
    m: usize,
    c: [f64; 2],
    step: &mut [f64],
) -> Option<[f64; 2]> {
    let w = 1.0 / m as f64;
    let rows: [Vec<f64>; 2] = [
        free.iter().map(|&i| -w * theta[i].sin()).collect(),
        free.iter().map(|&i| w * theta[i].cos()).collect(),
    ];
    let mut hinv = rows.clone();
    for r in &mut hinv {
        factor.solve_in_place(r, 1);
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let a = [
        [dot(&rows[0], &hinv[0]), dot(&rows[0], &hinv[1])],
        [dot(&rows[1], &hinv[0]), dot(&rows[1], &hinv[1])],
    ];
    // J H⁻¹ g = −J step
    let b = [c[0] + dot(&rows[0], step), c[1] + dot(&rows[1], step)];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if !(det.abs() > 1e-300) {
        return None;
    }
    let lambda = [
        (b[0] * a[1][1] - b[1] * a[0][1]) / det,
        (a[0][0] * b[1] - a[1][0] * b[0]) / det,
    ];
    for (k, s) in step.iter_mut().enumerate() {
        *s -= lambda[0] * hinv[0][k] + lambda[1] * hinv[1][k];
    }
    Some(lambda)
}

/// Backtracking from `alpha`: the first `θ + α δ` with sufficient decrease, or `None`.
fn armijo(
    merit: &impl Fn(&[f64]) -> f64,
    theta: &[f64],
    delta: &[f64],
    e0: f64,
    slope: f64,
    mut alpha: f64,
) -> Option<Vec<f64>> {
    for _ in 0..MAX_HALVINGS {
        let trial: Vec<f64> = theta
            .iter()
            .zip(delta)
            .map(|(t, d)| t + alpha * d)
            .collect();
        if merit(&trial) <= e0 + ARMIJO * alpha * slope {
            return Some(trial);
        }
        alpha *= 0.5;
    }
    None
}

/// Largest `α` such that every gap of `θ + α δ` keeps at least `1 − GAP_SHRINK` of its
/// current length and stays above its `floor`.
fn gap_limit(theta: &[f64], delta: &[f64], floor: &[f64]) -> f64 {
    let m = theta.len();
    let mut alpha = f64::INFINITY;
    for (k, gap) in gaps(theta).into_iter().enumerate() {
        let next = (k + 1) % m;
        let closing = delta[k] - delta[next];
        if closing > 0.0 {
            let room = (GAP_SHRINK * gap).min(gap - floor[k]).max(0.0);
            alpha = alpha.min(room / closing);
        }
    }
    alpha
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Schur complement of a ring of `m` boundary vertices around one centre vertex with
    /// equal spoke weight `w` and rim weight `r`: `L_BB = (2r + w) I − r (shift + shiftᵀ)`,
    /// `L_IB = −w 1ᵀ`, `L_II = m w`.
    fn wheel_schur(m: usize, w: f64, r: f64) -> Vec<f64> {
        let mut s = vec![0.0; m * m];
        for i in 0..m {
            s[i * m + i] = 2.0 * r + w;
            s[((i + 1) % m) * m + i] -= r;
            s[((i + m - 1) % m) * m + i] -= r;
            for j in 0..m {
                s[j * m + i] -= w * w / (m as f64 * w);
            }
        }
        s
    }

    #[test]
    fn uniform_wheel_is_a_fixed_point_and_perturbations_return() {
        let m = 12;
        let s = wheel_schur(m, 0.8, 0.3);
        let even: Vec<f64> = (0..m)
            .map(|k| k as f64 * std::f64::consts::TAU / m as f64)
            .collect();
        let opts = NewtonOptions {
            max_iter: 50,
            step_tol: 1e-13,
        };
        let centre = [0.0, 0.0];
        let r = minimize(&s, even.clone(), centre, &opts);
        assert!(r.converged);
        assert!(r.iterations <= 1, "{}", r.iterations);
        assert!(r
            .theta
            .iter()
            .zip(&even)
            .all(|(a, b)| (a - b).abs() < 1e-14));
        // perturb the angles but vertex 0: Newton brings them back (the mean is held at 0)
        let mut bumped = even.clone();
        for (k, t) in bumped.iter_mut().enumerate().skip(1) {
            *t += 0.05 * (k as f64).sin();
        }
        let r = minimize(&s, bumped, centre, &opts);
        assert!(r.converged, "{r:?}");
        let err = r
            .theta
            .iter()
            .zip(&even)
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        assert!(err < 1e-10, "{err}");
        assert!(r.iterations <= 8, "{}", r.iterations);
    }

    #[test]
    fn gradient_matches_finite_differences() {
        let m = 9;
        let mut s = wheel_schur(m, 0.7, 0.2);
        s[2 * m + 5] += 0.1;
        s[5 * m + 2] += 0.1;
        let e = Energy { s: &s, m };
        let theta: Vec<f64> = (0..m)
            .map(|k| 0.1 + 0.68 * k as f64 + 0.05 * (k as f64).cos())
            .collect();
        let ev = e.eval(&theta);
        let all: Vec<usize> = (0..m).collect();
        let h = e.reduced_hessian(&theta, &ev, &all, &all);
        let step = 1e-6;
        for k in 0..m {
            let mut p = theta.clone();
            p[k] += step;
            let mut q = theta.clone();
            q[k] -= step;
            let fd = (e.value(&p) - e.value(&q)) / (2.0 * step);
            assert!(
                (fd - ev.grad[k]).abs() < 1e-8,
                "grad {k}: {fd} vs {}",
                ev.grad[k]
            );
            let (gp, gq) = (e.eval(&p).grad, e.eval(&q).grad);
            for j in 0..m {
                let fd = (gp[j] - gq[j]) / (2.0 * step);
                assert!(
                    (fd - h[k * m + j]).abs() < 1e-7,
                    "hess {j},{k}: {fd} vs {}",
                    h[k * m + j]
                );
            }
        }
    }
}
