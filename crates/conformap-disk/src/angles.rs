//! Boundary angles kept strictly increasing around the circle: conversion from boundary
//! values, the gaps between neighbours, and the step limit that keeps their cyclic order
//! (the bijectivity guard of CCEM).
//!
//! Angles are stored unwrapped: `θ_0 < θ_1 < … < θ_{n−1} < θ_0 + 2π`. The gap after vertex
//! `j` is `θ_{j+1} − θ_j`, and the last one wraps around: `θ_0 + 2π − θ_{n−1}`. The gaps
//! sum to `2π` exactly in exact arithmetic; along `θ + α d` each gap changes linearly,
//! `gap_j(α) = gap_j + α (d_{j+1} − d_j)`, so the largest step that keeps every gap above a
//! floor is a minimum of ratios.

use std::f64::consts::{PI, TAU};

use num_complex::Complex64;

/// Each time the map folds with gaps at the floor, the floor is multiplied by this.
pub(crate) const GAP_FLOOR_STEP: f64 = 1e3;
/// The floor is never raised above this (radians), nor above a tenth of the mean gap
/// `2π / n_B`: beyond it, the floor would distort the whole boundary. Four floors are
/// tried from the default `1e-13`: `1e-13, 1e-10, 1e-7, 1e-4`.
pub(crate) const GAP_FLOOR_MAX: f64 = 1e-4;

/// Default first floor on the angle between consecutive boundary vertices when the
/// boundary has to be put back in order: `1e-13` radians, about 140 units in the last place
/// of an angle near `2π`, the smallest gap f64 angles resolve with margin (the same value
/// as CCEM's `min_gap`).
pub(crate) const UNFOLD_MIN_GAP: f64 = 1e-13;

/// Increasing angles of boundary values on the circle, and how many gaps had to be repaired.
#[derive(Debug, Clone)]
pub(crate) struct Unwrapped {
    /// `θ`, strictly increasing, spanning less than `2π`.
    pub theta: Vec<f64>,
    /// Gaps that were not above `min_gap` in the input (backward steps or collisions), now
    /// set to `min_gap`, the others scaled down to keep the total `2π`.
    pub repaired: usize,
}

/// A counter-clockwise step of more than `2π − BACKWARD_STEP` between consecutive
/// boundary values is read as a step backwards (clockwise, by less than `π/2`); anything
/// shorter is a step forwards, so that a legitimate gap above `π` (a boundary crowded
/// into a few arcs) is kept.
const BACKWARD_STEP: f64 = PI / 2.0;

/// The angles of `fb` (values on, or near, the unit circle), unwrapped to increase along the
/// boundary. Input that does not wind once counter-clockwise with all gaps above `min_gap`
/// (e.g. CEM's boundary on igea_open, where vertices step backwards past their neighbours)
/// is repaired: every gap that steps backwards or is `≤ min_gap` becomes `min_gap` and the
/// forward gaps are scaled so that the total stays `2π`. Returns `None` if nothing usable is
/// left (the forward gaps cover less than half or more than one and a half turns).
pub(crate) fn unwrap_boundary(fb: &[Complex64], min_gap: f64) -> Option<Unwrapped> {
    let n = fb.len();
    if n < 3 {
        return None;
    }
    let arg: Vec<f64> = fb.iter().map(|z| z.im.atan2(z.re)).collect();
    if arg.iter().any(|a| !a.is_finite()) {
        return None;
    }
    let ccw: Vec<f64> = (0..n)
        .map(|j| (arg[(j + 1) % n] - arg[j]).rem_euclid(TAU))
        .collect();
    let forward = |g: f64| g > min_gap && g < TAU - BACKWARD_STEP;
    let bad = ccw.iter().filter(|&&g| !forward(g)).count();
    let good: f64 = ccw.iter().filter(|&&g| forward(g)).sum();
    let floor = min_gap * bad as f64;
    if !(good > 0.5 * TAU && good < 1.5 * TAU) || floor >= TAU {
        return None;
    }
    let scale = (TAU - floor) / good;
    let gaps: Vec<f64> = ccw
        .iter()
        .map(|&g| if forward(g) { g * scale } else { min_gap })
        .collect();
    if gaps.iter().any(|&g| !(g >= min_gap)) {
        return None;
    }
    let mut theta = Vec::with_capacity(n);
    let mut t = arg[0];
    for g in &gaps {
        theta.push(t);
        t += g;
    }
    // a start that only needed the rounding of its sum rescaled is not "repaired"
    let repaired = if bad == 0 && (good - TAU).abs() < 1e-6 {
        0
    } else {
        bad.max(1)
    };
    Some(Unwrapped { theta, repaired })
}

/// The cyclic gaps `θ_{j+1} − θ_j` (the last one `θ_0 + 2π − θ_{n−1}`).
pub(crate) fn gaps(theta: &[f64]) -> Vec<f64> {
    let n = theta.len();
    (0..n)
        .map(|j| {
            if j + 1 < n {
                theta[j + 1] - theta[j]
            } else {
                theta[0] + TAU - theta[j]
            }
        })
        .collect()
}

/// Smallest gap and the boundary position (index into the loop) after which it lies.
pub(crate) fn min_gap(theta: &[f64]) -> (f64, usize) {
    gaps(theta)
        .into_iter()
        .enumerate()
        .fold(
            (f64::INFINITY, 0),
            |acc, (j, g)| if g < acc.0 { (g, j) } else { acc },
        )
}

/// Largest `α ≥ 0` with every gap of `θ + α d` at least `floor` (infinite when no gap
/// shrinks); 0 when a gap already at the floor would shrink.
pub(crate) fn max_step(gaps: &[f64], d: &[f64], floor: f64) -> f64 {
    let n = d.len();
    let mut best = f64::INFINITY;
    for j in 0..n {
        let dd = d[(j + 1) % n] - d[j];
        if dd < 0.0 {
            best = best.min(((gaps[j] - floor) / -dd).max(0.0));
        }
    }
    best
}

/// Gaps within this many units in the last place of the angles above the floor count as at
/// the floor: a step that lands a gap exactly on the floor leaves it there only up to the
/// rounding of `θ_{j+1} − θ_j` (about `ulp(2π) = 8.9e-16`).
const AT_FLOOR_ULPS: f64 = 16.0;

/// Removes the components of `d` that would shrink gaps already at (or within rounding
/// of) `floor`: every maximal run of vertices joined by such gaps moves rigidly, with
/// the mean of `d` over the run (an orthogonal projection, so `−P∇E` is still a descent
/// direction). Repeats until no gap at the floor shrinks. Returns the number of gaps held.
pub(crate) fn hold_gaps_at_floor(gaps: &[f64], d: &mut [f64], floor: f64) -> usize {
    let n = d.len();
    let slack = AT_FLOOR_ULPS * f64::EPSILON * 2.0 * TAU;
    let at_floor: Vec<bool> = gaps.iter().map(|&g| g <= floor + slack).collect();
    let mut held = vec![false; n];
    for _ in 0..n {
        let mut changed = false;
        for j in 0..n {
            if at_floor[j] && !held[j] && d[(j + 1) % n] - d[j] < 0.0 {
                held[j] = true;
                changed = true;
            }
        }
        if !changed {
            break;
        }
        average_runs(&held, d);
    }
    held.iter().filter(|&&h| h).count()
}

/// Sets `d` to its mean over every maximal cyclic run of vertices joined by held gaps
/// (gap `j` joins vertices `j` and `j + 1`).
fn average_runs(held: &[bool], d: &mut [f64]) {
    let n = d.len();
    if held.iter().all(|&h| h) {
        let m = d.iter().sum::<f64>() / n as f64;
        d.iter_mut().for_each(|x| *x = m);
        return;
    }
    // start right after a gap that is not held, so no run wraps past the start
    let start = match (0..n).find(|&j| !held[j]) {
        Some(j) => (j + 1) % n,
        None => return,
    };
    let mut k = 0;
    while k < n {
        let first = (start + k) % n;
        let mut len = 1;
        while k + len < n && held[(start + k + len - 1) % n] {
            len += 1;
        }
        if len > 1 {
            let idx: Vec<usize> = (0..len).map(|i| (first + i) % n).collect();
            let m = idx.iter().map(|&i| d[i]).sum::<f64>() / len as f64;
            for i in idx {
                d[i] = m;
            }
        }
        k += len;
    }
}

/// The angles nearest to `y` (least squares) whose gaps are all at least `floor`, except
/// the gap after position `cut`, which is only checked: the chain of constraints is cut
/// there and the projection is an isotonic regression (pool-adjacent-violators) of
/// `y_k − k·floor` along the loop starting after `cut`. `y` must be unwrapped like `θ`
/// (`y_0 ≤ … ≤ y_{n−1} ≤ y_0 + 2π` need not hold: that is what is repaired). Returns `None`
/// if the cut gap ends below the floor (the whole loop would not fit).
pub(crate) fn project_to_floor(y: &[f64], floor: f64, cut: usize) -> Option<Vec<f64>> {
    let n = y.len();
    let start = (cut + 1) % n;
    // position k of the chain is loop index (start + k) mod n, lifted by 2π after wrapping
    let lift = |k: usize| if start + k >= n { TAU } else { 0.0 };
    let idx = |k: usize| (start + k) % n;
    // blocks of the pool-adjacent-violators algorithm: (sum, count)
    let mut blocks: Vec<(f64, usize)> = Vec::with_capacity(n);
    for k in 0..n {
        let w = y[idx(k)] + lift(k) - k as f64 * floor;
        blocks.push((w, 1));
        while blocks.len() > 1 {
            let (s1, c1) = blocks[blocks.len() - 1];
            let (s0, c0) = blocks[blocks.len() - 2];
            if s0 / c0 as f64 > s1 / c1 as f64 {
                blocks.pop();
                let last = blocks.len() - 1;
                blocks[last] = (s0 + s1, c0 + c1);
            } else {
                break;
            }
        }
    }
    let mut x = vec![0.0; n];
    let mut k = 0;
    for (s, c) in blocks {
        let z = s / c as f64;
        for _ in 0..c {
            x[idx(k)] = z + k as f64 * floor - lift(k);
            k += 1;
        }
    }
    // the cut gap: from the chain's last vertex (loop index `cut`) to its first plus 2π
    let last = x[cut] + lift(n - 1);
    let first = x[start] + TAU;
    (first - last >= floor).then_some(x)
}

/// Position of the largest gap (the natural place to cut the chain of constraints).
pub(crate) fn largest_gap(theta: &[f64]) -> usize {
    gaps(theta)
        .into_iter()
        .enumerate()
        .fold(
            (f64::NEG_INFINITY, 0),
            |acc, (j, g)| if g > acc.0 { (g, j) } else { acc },
        )
        .1
}

/// Subtracts the mean: `E_C` is invariant under `θ ↦ θ + c 1`, so the component along `1`
/// of a direction changes nothing but the drift of the angles.
pub(crate) fn remove_mean(d: &mut [f64]) {
    let m = d.iter().sum::<f64>() / d.len().max(1) as f64;
    d.iter_mut().for_each(|x| *x -= m);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unwraps_and_repairs() {
        let t = [0.1, 1.0, 3.0, 5.0];
        let fb: Vec<Complex64> = t.iter().map(|&x| Complex64::from_polar(1.0, x)).collect();
        let u = unwrap_boundary(&fb, 1e-12).unwrap();
        assert_eq!(u.repaired, 0);
        for (a, b) in u.theta.iter().zip(t) {
            assert!((a - b).abs() < 1e-12);
        }
        // vertex 2 steps backwards past vertex 1
        let t = [0.1, 1.0, 0.9, 5.0];
        let fb: Vec<Complex64> = t.iter().map(|&x| Complex64::from_polar(1.0, x)).collect();
        let u = unwrap_boundary(&fb, 1e-3).unwrap();
        assert_eq!(u.repaired, 1);
        // the gap 0.9 → 5.0 (> π) is a forward gap, kept in proportion
        assert!((u.theta[3] - u.theta[2] - 4.1 * (TAU - 1e-3) / (TAU + 0.1)).abs() < 1e-12);
        let g = gaps(&u.theta);
        assert!(g.iter().all(|&x| x >= 1e-3 * (1.0 - 1e-12)));
        assert!((g.iter().sum::<f64>() - TAU).abs() < 1e-12);
    }

    #[test]
    fn projection_keeps_order() {
        let floor = 0.05;
        // vertex 2 crossed vertex 1
        let y = [0.0, 1.0, 0.9, 4.0];
        let cut = 2; // the gap 0.9 → 4.0 is the largest
        let x = project_to_floor(&y, floor, cut).unwrap();
        let g = gaps(&x);
        assert!(g.iter().all(|&v| v >= floor - 1e-12), "{g:?}");
        // the pair moved symmetrically around its mean 0.95
        assert!((x[1] - (0.95 - 0.025)).abs() < 1e-12 && (x[2] - (0.95 + 0.025)).abs() < 1e-12);
        assert_eq!((x[0], x[3]), (0.0, 4.0));
        // already feasible: unchanged
        let y = [0.0, 1.0, 2.0, 4.0];
        assert_eq!(project_to_floor(&y, floor, 3).unwrap(), y.to_vec());
    }

    #[test]
    fn step_limit_and_hold() {
        let theta = [0.0, 1.0, 1.5, 4.0];
        let g = gaps(&theta);
        let d = [0.0, 1.0, 0.0, 0.0];
        // gap 1 (1.0 → 1.5) shrinks at rate 1: reaches 0.1 at α = 0.4
        assert!((max_step(&g, &d, 0.1) - 0.4).abs() < 1e-15);
        let mut d2 = d;
        let g2 = [1.0, 0.1, 2.5, TAU - 3.6];
        assert_eq!(hold_gaps_at_floor(&g2, &mut d2, 0.1), 1);
        assert_eq!(d2, [0.0, 0.5, 0.5, 0.0]);
    }
}
