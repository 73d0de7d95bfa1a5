//! The harmonic-measure start of CCEM and its Möbius alignment.
//!
//! **Harmonic measure.** The conformal map `φ` of a disk-like surface onto the unit disk
//! with `φ(p) = 0` is `φ = exp(−(G + i G*))`, `G` the Green's function with its pole at
//! `p`; on the boundary `|φ| = 1` and `d(arg φ) = ∂G/∂n ds`: the boundary angles of the
//! conformal map are `2π` times the cumulative **harmonic measure** seen from `p`. Its
//! discrete form costs one solve with `L_II`: `L_II x = e_p`, and the flux of `x` through
//! boundary vertex `j` is `ω_j = −(L_BI x)_j` (`Σ ω_j = 1`), so `θ_j = 2π (Σ_{k<j} ω_k +
//! ω_j / 2)`. With the dense Schur complement the solve rides along in the pass that forms
//! `A` (its right-hand side `e_p` is the sparse right-hand side of
//! [`crate::ccem::schur::Schur::with_rhs`]); no dense solve is needed (Angenent's start needs
//! one of `n_B³ / 3` flops).
//!
//! **Möbius alignment.** The continuous conformal energy is invariant under the disk's
//! automorphisms `z ↦ e^{iφ}(z − b)/(1 − b̄ z)`; the discrete `E_C` is not, but nearly: its
//! Hessian has two very small eigenvalues along the orbit (tangents `2 sin θ` and `−2 cos
//! θ`), and the orbit is curved in `θ`. A quasi-Newton method creeps along that curved
//! valley (a 250k-face square: 49 iterations, 30 of them moving the map's centre by
//! `|b| ≈ 0.12`). So before the descent the start is moved along the orbit itself: Newton
//! on the two real parameters of `b`: the exact chart gradient, a 2 × 2 model by finite
//! differences of it in the first round and BFGS updates after, backtracking on the curved
//! path; 5–11 products with `A` in all. After it, the descent needs 1–7 iterations on the
//! generated squares and disks and on hand.obj (see the crate README).

use num_complex::Complex64;

use crate::ccem::descent::ROUNDING_ULPS;
use crate::ccem::energy::{evaluate, Eval};
use crate::ccem::schur::Schur;

/// Rounds of Newton on the Möbius parameter at most (measured: 2–4 reach the tolerance).
pub(crate) const MOBIUS_ALIGN_ROUNDS: usize = 8;
/// Finite-difference step of the chart Hessian (in `|b|`, the disk's radius being 1):
/// the Hessian is then accurate to about `1e-5` relative, far more than Newton needs,
/// while the gradient differences (`~ H h`) stay ten orders of magnitude above their
/// rounding.
const FD_STEP: f64 = 1e-5;
/// Largest `|b|` of one round: a move of the centre by half the radius is already far
/// outside where a 2 × 2 quadratic model is trusted.
const MAX_ROUND_STEP: f64 = 0.5;
/// Halvings of a round's step before the round gives up.
const MAX_HALVINGS: usize = 10;
/// Sufficient-decrease constant of the backtracking (Armijo).
const ARMIJO: f64 = 1e-4;

/// What the alignment did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Alignment {
    /// Accepted rounds.
    pub rounds: usize,
    /// Products with `A` spent.
    pub products: usize,
    /// Sum of the rounds' `|b|`.
    pub moved: f64,
    /// `E_C` before and after.
    pub energy_before: f64,
    pub energy_after: f64,
}

/// `θ` moved by the disk automorphism `z ↦ (z − b)/(1 − b̄ z)`, continuously: for `|b| < 1`
/// both `1 − b z̄` and `1 − b̄ z` have positive real part, so the change of every angle is
/// in `(−π, π)` and the order of the angles is kept.
pub(crate) fn mobius_theta(theta: &[f64], b: Complex64) -> Vec<f64> {
    let one = Complex64::new(1.0, 0.0);
    theta
        .iter()
        .map(|&t| {
            let z = Complex64::from_polar(1.0, t);
            t + (one - b * z.conj()).arg() - (one - b.conj() * z).arg()
        })
        .collect()
}

/// The gradient of `b ↦ E_C(M_b θ_c)` in `(Re b, Im b)`, from the gradient at
/// `e = M_b θ_c`: `∂θ_j/∂b_x = Im(−z̄/u₁) − Im(−z/u₂)`, `∂θ_j/∂b_y = Im(−i z̄/u₁) −
/// Im(i z/u₂)`, `z = e^{iθ_c,j}`, `u₁ = 1 − b z̄`, `u₂ = 1 − b̄ z` (at `b = 0`: `2 sin θ`,
/// `−2 cos θ`).
fn chart_gradient(theta_c: &[f64], b: Complex64, e: &Eval) -> [f64; 2] {
    let one = Complex64::new(1.0, 0.0);
    let i = Complex64::new(0.0, 1.0);
    let mut g = [0.0; 2];
    for (&t, &gj) in theta_c.iter().zip(&e.grad) {
        let z = Complex64::from_polar(1.0, t);
        let u1 = one - b * z.conj();
        let u2 = one - b.conj() * z;
        g[0] += gj * ((-z.conj() / u1).im - (-z / u2).im);
        g[1] += gj * ((-i * z.conj() / u1).im - (i * z / u2).im);
    }
    g
}

/// Newton on the Möbius parameter from `cur` until the predicted decrease of a freshly
/// differenced model is below `tol · |E_C|` or the rounding level of `E_C` (or [`MOBIUS_ALIGN_ROUNDS`] accepted rounds, or
/// a fresh model finds no decrease or is not positive definite: then the last point is
/// returned).
pub(crate) fn align(schur: &Schur<'_, '_>, mut cur: Eval, tol: f64) -> (Eval, Alignment) {
    let mut out = Alignment {
        energy_before: cur.energy,
        ..Alignment::default()
    };
    let zero = Complex64::new(0.0, 0.0);
    // the 2 × 2 Hessian: by finite differences in the first round (or after a failed
    // round), then by the BFGS update from each accepted step, whose end point's chart
    // gradient is exact secant information (the charts of consecutive rounds differ by a
    // small automorphism): one product per round instead of three to four
    let mut model: Option<[[f64; 2]; 2]> = None;
    let mut fresh = false;
    let mut round = 0;
    while round < MOBIUS_ALIGN_ROUNDS {
        let base = cur.theta.clone();
        let g0 = chart_gradient(&base, zero, &cur);
        if !(g0[0].is_finite() && g0[1].is_finite()) || g0 == [0.0, 0.0] {
            break;
        }
        let hess = match model {
            Some(h) => h,
            None => {
                let mut h = [[0.0; 2]; 2];
                for (k, db) in [Complex64::new(FD_STEP, 0.0), Complex64::new(0.0, FD_STEP)]
                    .into_iter()
                    .enumerate()
                {
                    let e = evaluate(schur, mobius_theta(&base, db));
                    out.products += 1;
                    let g = chart_gradient(&base, db, &e);
                    h[0][k] = (g[0] - g0[0]) / FD_STEP;
                    h[1][k] = (g[1] - g0[1]) / FD_STEP;
                }
                let s = 0.5 * (h[0][1] + h[1][0]);
                h[0][1] = s;
                h[1][0] = s;
                fresh = true;
                h
            }
        };
        let (a, c, s) = (hess[0][0], hess[1][1], hess[0][1]);
        let det = a * c - s * s;
        if !(a > 0.0 && det > 0.0) {
            if fresh {
                break;
            }
            model = None;
            continue;
        }
        let mut step = [
            -(c * g0[0] - s * g0[1]) / det,
            -(a * g0[1] - s * g0[0]) / det,
        ];
        let slope = g0[0] * step[0] + g0[1] * step[1];
        // a predicted decrease below the rounding level of E_C cannot be measured: the
        // backtracking would spend its halvings on noise (a re-alignment at the end of a
        // 2M-face square spent 29 products so, E_C ≈ 7e-6 against a rounding of ~4e-14)
        let floor = (tol * cur.energy.abs()).max(ROUNDING_ULPS * f64::EPSILON * cur.scale);
        if !(-0.5 * slope > floor) {
            if fresh {
                break;
            }
            // a stale model's small step is no proof: confirm with a fresh one
            model = None;
            continue;
        }
        let len = step[0].hypot(step[1]);
        if len > MAX_ROUND_STEP {
            step = [
                step[0] * MAX_ROUND_STEP / len,
                step[1] * MAX_ROUND_STEP / len,
            ];
        }
        let mut alpha = 1.0;
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let b = Complex64::new(alpha * step[0], alpha * step[1]);
            let e = evaluate(schur, mobius_theta(&base, b));
            out.products += 1;
            if e.energy.is_finite() && e.energy <= cur.energy + ARMIJO * alpha * slope {
                accepted = Some((e, b));
                break;
            }
            alpha *= 0.5;
        }
        match accepted {
            Some((e, b)) => {
                // BFGS update of the 2 × 2 model from the secant pair in this round's chart
                let g1 = chart_gradient(&base, b, &e);
                let sv = [b.re, b.im];
                let y = [g1[0] - g0[0], g1[1] - g0[1]];
                let ys = y[0] * sv[0] + y[1] * sv[1];
                let bs = [a * sv[0] + s * sv[1], s * sv[0] + c * sv[1]];
                let sbs = sv[0] * bs[0] + sv[1] * bs[1];
                model = (ys > 0.0 && sbs > 0.0).then(|| {
                    let mut h = hess;
                    for i in 0..2 {
                        for j in 0..2 {
                            h[i][j] += y[i] * y[j] / ys - bs[i] * bs[j] / sbs;
                        }
                    }
                    h
                });
                fresh = false;
                cur = e;
                out.rounds += 1;
                out.moved += b.norm();
                round += 1;
            }
            None if !fresh => model = None,
            None => break,
        }
    }
    out.energy_after = cur.energy;
    (cur, out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mobius_keeps_order_and_composes_to_the_identity() {
        let n = 50;
        let theta: Vec<f64> = (0..n)
            .map(|j| std::f64::consts::TAU * (j as f64 + 0.3 * (j as f64).sin()) / n as f64)
            .collect();
        let b = Complex64::new(0.3, -0.4);
        let moved = mobius_theta(&theta, b);
        for w in moved.windows(2) {
            assert!(w[1] > w[0]);
        }
        // the inverse automorphism is z ↦ (z + b)/(1 + b̄ z)
        let back = mobius_theta(&moved, -b);
        for (x, y) in back.iter().zip(&theta) {
            assert!((x - y).abs() < 1e-13, "{x} vs {y}");
        }
        // and it is the automorphism: |w| = 1, w = (z − b)/(1 − b̄ z)
        for (&t, &m) in theta.iter().zip(&moved) {
            let z = Complex64::from_polar(1.0, t);
            let w = (z - b) / (Complex64::new(1.0, 0.0) - b.conj() * z);
            assert!((w - Complex64::from_polar(1.0, m)).norm() < 1e-13);
        }
    }
}
