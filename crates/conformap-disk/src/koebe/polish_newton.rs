//! The conformal energy minimized over circle domains: every boundary loop constrained to a
//! circle (the outer one the unit circle), each hole's centre and radius free, the interior
//! harmonic with the surface's own Laplacian.
//!
//! With the interior eliminated (the dense Schur complement `S` over the vertices of every
//! loop), the energy of CEM Eq. 7 is `E(f_B) = ½ f_Bᴴ S f_B − A(f_B)`, `A` the signed area of
//! the loops (outer minus holes, CEM Eq. 8), and each boundary vertex of loop `l` sits at
//! `f = c_l + r_l e^{iθ}`. The parameters are the angles, and `(c_l, ln r_l)` per hole. The
//! gauge (the three Möbius degrees of freedom of the disk): the outer loop's first vertex
//! stays at angle 0 and the reference hole's centre at 0 (the normalization of
//! [`crate::koebe`]). Newton's method with the exact Hessian, a Levenberg–Marquardt shift
//! when it is not positive definite, and a line search that keeps every loop in order, every
//! radius within a factor 2 per step, and the circles disjoint inside the unit circle.
//!
//! Koebe's iteration maps to *a* circle domain; which one depends on its path (each planar
//! step is exact for its own image, so the first map's discretization error is frozen in).
//! This minimization picks the circle domain map of least conformal energy measured on the
//! surface, and it converges where the iteration does not (small holes with staircase
//! boundaries, where the inverted steps are dominated by one ring of coarse triangles).

use std::f64::consts::TAU;

use conformap_operators::DenseCholesky;
use num_complex::Complex64;

/// Largest fraction of an angular gap one step may close (every loop stays in order).
const GAP_SHRINK: f64 = 0.5;
/// No angular gap may fall below `1e-3` of its length at the start. On coarse loops with
/// staircase corners (the holes of peaks_7holes: 20 vertices, a right-angle corner at each)
/// the discrete energy keeps falling as a boundary edge shrinks to nothing, a collapse the
/// continuous map does not have; such a gap is held at the floor (both its vertices keep
/// their angles) and the minimization goes on without them.
const GAP_FLOOR: f64 = 1e-3;
/// A gap whose room to close is below `1e-9` of its length blocks the step.
const BLOCKED_ROOM: f64 = 1e-9;
/// Largest change of `ln r` per step: `ln 2` (a radius at most doubles or halves).
const MAX_LOG_RADIUS_STEP: f64 = std::f64::consts::LN_2;
/// Armijo constant.
const ARMIJO: f64 = 1e-4;
/// Step halvings per line search.
const MAX_HALVINGS: usize = 40;
/// Below this predicted decrease relative to `E_D` the energy no longer resolves the line
/// search: whole Newton steps, stopping when a step fails to halve the previous one.
const QUADRATIC_REGIME: f64 = 1e-10;

/// One boundary loop's place in the problem.
#[derive(Debug, Clone)]
pub(crate) struct LoopSpec {
    /// Offset of the loop's first vertex in the boundary vector.
    pub start: usize,
    /// Number of vertices.
    pub len: usize,
    /// `+1` for the outer loop (angles increase along it), `−1` for a hole.
    pub sign: f64,
    /// Whether the centre and radius are free (`false`: outer loop, fixed unit circle).
    pub free_circle: bool,
    /// Whether the centre is held at 0 (the reference hole).
    pub pinned_centre: bool,
}

/// A point of the problem: angles of every boundary vertex, and every loop's circle.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct CircleState {
    pub theta: Vec<f64>,
    pub centre: Vec<Complex64>,
    pub log_radius: Vec<f64>,
}

/// What [`minimize_circles`] found.
#[derive(Debug, Clone)]
pub(crate) struct PolishResult {
    pub state: CircleState,
    pub iterations: usize,
    pub converged: bool,
    pub energy_history: Vec<f64>,
    /// Boundary vertices held at their angle because a gap next to them reached its floor.
    pub held_vertices: usize,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Param {
    Theta(usize),
    CentreRe(usize),
    CentreIm(usize),
    LogRadius(usize),
}

/// The problem: Schur complement, loops and parameters.
pub(crate) struct CircleProblem<'a> {
    s: &'a [f64],
    nb: usize,
    loops: Vec<LoopSpec>,
    /// Loop of every boundary vertex.
    owner: Vec<usize>,
    params: Vec<Param>,
}

struct Eval {
    energy: f64,
    dirichlet: f64,
    /// `∂E/∂x + i ∂E/∂y` per boundary vertex.
    g: Vec<Complex64>,
}

impl<'a> CircleProblem<'a> {
    /// `s`: dense symmetric `n_B × n_B`, column-major; `loops` cover `0..n_B` in order. The
    /// first vertex of the (single) loop without a free circle is pinned.
    pub(crate) fn new(s: &'a [f64], loops: Vec<LoopSpec>) -> Self {
        let nb = loops.iter().map(|l| l.len).sum();
        let mut owner = vec![0; nb];
        let mut params = Vec::new();
        for (li, l) in loops.iter().enumerate() {
            for k in l.start..l.start + l.len {
                owner[k] = li;
                if l.free_circle || k != l.start {
                    params.push(Param::Theta(k));
                }
            }
        }
        for (li, l) in loops.iter().enumerate() {
            if l.free_circle {
                if !l.pinned_centre {
                    params.push(Param::CentreRe(li));
                    params.push(Param::CentreIm(li));
                }
                params.push(Param::LogRadius(li));
            }
        }
        Self {
            s,
            nb,
            loops,
            owner,
            params,
        }
    }

    fn next(&self, k: usize) -> usize {
        let l = &self.loops[self.owner[k]];
        if k + 1 == l.start + l.len {
            l.start
        } else {
            k + 1
        }
    }

    fn prev(&self, k: usize) -> usize {
        let l = &self.loops[self.owner[k]];
        if k == l.start {
            l.start + l.len - 1
        } else {
            k - 1
        }
    }

    pub(crate) fn positions(&self, st: &CircleState) -> Vec<Complex64> {
        (0..self.nb)
            .map(|k| {
                let l = self.owner[k];
                st.centre[l] + Complex64::from_polar(st.log_radius[l].exp(), st.theta[k])
            })
            .collect()
    }

    fn eval(&self, st: &CircleState) -> Eval {
        let nb = self.nb;
        let f = self.positions(st);
        let mut sf = vec![Complex64::new(0.0, 0.0); nb];
        for j in 0..nb {
            let col = &self.s[j * nb..(j + 1) * nb];
            let fj = f[j];
            for i in 0..nb {
                sf[i] += fj * col[i];
            }
        }
        let dirichlet = 0.5
            * f.iter()
                .zip(&sf)
                .map(|(a, b)| (a.conj() * b).re)
                .sum::<f64>();
        let mut area = 0.0;
        let mut g = sf;
        for k in 0..nb {
            let (p, q) = (f[k], f[self.next(k)]);
            area += 0.5 * (p.conj() * q).im;
            let d = f[self.next(k)] - f[self.prev(k)];
            g[k] -= Complex64::new(0.0, -0.5) * d;
        }
        Eval {
            energy: dirichlet - area,
            dirichlet,
            g,
        }
    }

    /// `∂f_k / ∂p` as (vertex, coefficient) pairs.
    fn direction(&self, st: &CircleState, p: Param) -> Vec<(usize, Complex64)> {
        let unit = |k: usize| Complex64::from_polar(1.0, st.theta[k]);
        match p {
            Param::Theta(k) => {
                let r = st.log_radius[self.owner[k]].exp();
                vec![(k, Complex64::new(0.0, r) * unit(k))]
            }
            Param::CentreRe(l) | Param::CentreIm(l) => {
                let c = if matches!(p, Param::CentreRe(_)) {
                    Complex64::new(1.0, 0.0)
                } else {
                    Complex64::new(0.0, 1.0)
                };
                let lp = &self.loops[l];
                (lp.start..lp.start + lp.len).map(|k| (k, c)).collect()
            }
            Param::LogRadius(l) => {
                let r = st.log_radius[l].exp();
                let lp = &self.loops[l];
                (lp.start..lp.start + lp.len)
                    .map(|k| (k, unit(k) * r))
                    .collect()
            }
        }
    }

    fn gradient(&self, st: &CircleState, e: &Eval) -> Vec<f64> {
        self.params
            .iter()
            .map(|&p| {
                self.direction(st, p)
                    .iter()
                    .map(|&(k, d)| (e.g[k].conj() * d).re)
                    .sum()
            })
            .collect()
    }

    /// The exact Hessian, column-major `P × P`.
    fn hessian(&self, st: &CircleState, e: &Eval) -> Vec<f64> {
        let np = self.params.len();
        let nb = self.nb;
        let dirs: Vec<Vec<(usize, Complex64)>> =
            self.params.iter().map(|&p| self.direction(st, p)).collect();
        // dense S D_q for the loop parameters (the angle ones are columns of S)
        let mut h = vec![0.0; np * np];
        let mut dense_sd: Vec<Option<Vec<Complex64>>> = vec![None; np];
        for (q, d) in dirs.iter().enumerate() {
            if d.len() > 1 {
                let mut v = vec![Complex64::new(0.0, 0.0); nb];
                for &(j, c) in d {
                    let col = &self.s[j * nb..(j + 1) * nb];
                    for i in 0..nb {
                        v[i] += c * col[i];
                    }
                }
                dense_sd[q] = Some(v);
            }
        }
        for q in 0..np {
            for p in 0..=q {
                let dirichlet = match (&dense_sd[q], &dense_sd[p]) {
                    (Some(sdq), _) => dirs[p].iter().map(|&(k, c)| (c.conj() * sdq[k]).re).sum(),
                    (None, Some(sdp)) => dirs[q].iter().map(|&(k, c)| (c.conj() * sdp[k]).re).sum(),
                    (None, None) => {
                        let (k, a) = dirs[p][0];
                        let (j, b) = dirs[q][0];
                        self.s[j * nb + k] * (a.conj() * b).re
                    }
                };
                let value = dirichlet - self.area_hessian(&dirs[p], &dirs[q]);
                h[q * np + p] = value;
                h[p * np + q] = value;
            }
        }
        // second derivatives of f times the gradient
        for (a, &p) in self.params.iter().enumerate() {
            match p {
                Param::Theta(k) => {
                    let l = self.owner[k];
                    let rf = Complex64::from_polar(st.log_radius[l].exp(), st.theta[k]);
                    h[a * np + a] += (e.g[k].conj() * -rf).re;
                    if let Some(b) = self.params.iter().position(|&q| q == Param::LogRadius(l)) {
                        let v = (e.g[k].conj() * Complex64::new(0.0, 1.0) * rf).re;
                        h[b * np + a] += v;
                        h[a * np + b] += v;
                    }
                }
                Param::LogRadius(l) => {
                    let lp = &self.loops[l];
                    let r = st.log_radius[l].exp();
                    let v: f64 = (lp.start..lp.start + lp.len)
                        .map(|k| (e.g[k].conj() * Complex64::from_polar(r, st.theta[k])).re)
                        .sum();
                    h[a * np + a] += v;
                }
                _ => {}
            }
        }
        h
    }

    /// The Hessian of the area, `½ Σ_edges Im(ū_k v_k' + v̄_k u_k')`, for two sparse
    /// directions.
    fn area_hessian(&self, u: &[(usize, Complex64)], v: &[(usize, Complex64)]) -> f64 {
        if u.is_empty() || v.is_empty() || self.owner[u[0].0] != self.owner[v[0].0] {
            return 0.0;
        }
        let lp = &self.loops[self.owner[u[0].0]];
        let dense = |w: &[(usize, Complex64)]| {
            let mut d = vec![Complex64::new(0.0, 0.0); lp.len];
            for &(k, c) in w {
                d[k - lp.start] = c;
            }
            d
        };
        if u.len() == 1 && v.len() == 1 {
            let ((k, a), (j, b)) = (u[0], v[0]);
            let mut s = 0.0;
            if self.next(k) == j {
                s += 0.5 * (a.conj() * b).im;
            }
            if self.next(j) == k {
                s += 0.5 * (b.conj() * a).im;
            }
            return s;
        }
        let (du, dv) = (dense(u), dense(v));
        let m = lp.len;
        (0..m)
            .map(|k| {
                let kn = (k + 1) % m;
                0.5 * ((du[k].conj() * dv[kn]).im + (dv[k].conj() * du[kn]).im)
            })
            .sum()
    }

    fn apply(&self, st: &CircleState, step: &[f64], alpha: f64) -> CircleState {
        let mut out = st.clone();
        for (&p, &d) in self.params.iter().zip(step) {
            match p {
                Param::Theta(k) => out.theta[k] += alpha * d,
                Param::CentreRe(l) => out.centre[l].re += alpha * d,
                Param::CentreIm(l) => out.centre[l].im += alpha * d,
                Param::LogRadius(l) => out.log_radius[l] += alpha * d,
            }
        }
        out
    }

    /// The angular gap after every boundary vertex (to the next one along its loop,
    /// positive when in order).
    fn gaps(&self, st: &CircleState) -> Vec<f64> {
        (0..self.nb)
            .map(|k| {
                let l = &self.loops[self.owner[k]];
                let kn = self.next(k);
                let gap = l.sign * (st.theta[kn] - st.theta[k]);
                if kn == l.start {
                    gap + TAU
                } else {
                    gap
                }
            })
            .collect()
    }

    /// Largest `α ≤ 1` keeping every loop's gaps above half their length and above their
    /// `floor`, and every radius within a factor 2; with the gaps (by their first vertex)
    /// whose floor allows no step at all.
    fn step_limit(&self, st: &CircleState, step: &[f64], floor: &[f64]) -> (f64, Vec<usize>) {
        let mut delta = vec![0.0; self.nb];
        let mut alpha: f64 = 1.0;
        for (&p, &d) in self.params.iter().zip(step) {
            match p {
                Param::Theta(k) => delta[k] = d,
                Param::LogRadius(_) if d.abs() > 0.0 => {
                    alpha = alpha.min(MAX_LOG_RADIUS_STEP / d.abs());
                }
                _ => {}
            }
        }
        let mut blocked = Vec::new();
        for (k, gap) in self.gaps(st).into_iter().enumerate() {
            let l = &self.loops[self.owner[k]];
            let closing = l.sign * (delta[k] - delta[self.next(k)]);
            if closing > 0.0 {
                let room = (GAP_SHRINK * gap).min(gap - floor[k]).max(0.0);
                if room <= BLOCKED_ROOM * gap {
                    blocked.push(k);
                } else {
                    alpha = alpha.min(room / closing);
                }
            }
        }
        (alpha, blocked)
    }

    /// Whether the hole circles are disjoint and inside the unit circle.
    fn circles_valid(&self, st: &CircleState) -> bool {
        let holes: Vec<usize> = (0..self.loops.len())
            .filter(|&l| self.loops[l].free_circle)
            .collect();
        for (a, &i) in holes.iter().enumerate() {
            let ri = st.log_radius[i].exp();
            if !(st.centre[i].norm() + ri < 1.0) {
                return false;
            }
            for &j in &holes[a + 1..] {
                let rj = st.log_radius[j].exp();
                if !((st.centre[i] - st.centre[j]).norm() > ri + rj) {
                    return false;
                }
            }
        }
        true
    }
}

/// Minimizes the energy from `start` by damped Newton steps (see the module docs).
pub(crate) fn minimize_circles(
    problem: &CircleProblem<'_>,
    start: CircleState,
    max_iter: usize,
    step_tol: f64,
) -> PolishResult {
    let mut st = start;
    let mut cur = problem.eval(&st);
    let mut history = vec![cur.energy];
    let mut converged = false;
    let mut iterations = 0;
    let mut previous_step = f64::INFINITY;
    let np = problem.params.len();
    let floor: Vec<f64> = problem.gaps(&st).iter().map(|g| GAP_FLOOR * g).collect();
    // parameters still free (angles whose gap reached its floor are held)
    let mut active: Vec<bool> = vec![true; np];
    let slot_of_theta: Vec<Option<usize>> = {
        let mut v = vec![None; problem.nb];
        for (a, &p) in problem.params.iter().enumerate() {
            if let Param::Theta(k) = p {
                v[k] = Some(a);
            }
        }
        v
    };
    let mut held = 0;
    while iterations < max_iter {
        let g_all = problem.gradient(&st, &cur);
        let h_all = problem.hessian(&st, &cur);
        let idx: Vec<usize> = (0..np).filter(|&a| active[a]).collect();
        let na = idx.len();
        let mut h = vec![0.0; na * na];
        for (b, &q) in idx.iter().enumerate() {
            for (a, &p) in idx.iter().enumerate() {
                h[b * na + a] = h_all[q * np + p];
            }
        }
        let g: Vec<f64> = idx.iter().map(|&a| g_all[a]).collect();
        let Some(factor) = DenseCholesky::factor_shifted(&h, na, 1)
            .ok()
            .map(|(f, _)| f)
        else {
            break;
        };
        let mut reduced: Vec<f64> = g.iter().map(|v| -v).collect();
        factor.solve_in_place(&mut reduced, 1);
        let mut step = vec![0.0; np];
        for (a, &p) in idx.iter().enumerate() {
            step[p] = reduced[a];
        }
        let slope: f64 = g.iter().zip(&reduced).map(|(a, b)| a * b).sum();
        let step_max = reduced.iter().fold(0.0f64, |a, d| a.max(d.abs()));
        let (limit, blocked) = problem.step_limit(&st, &step, &floor);
        if !blocked.is_empty() {
            // hold both ends of every gap at its floor, and solve again without them
            for k in blocked {
                for v in [k, problem.next(k)] {
                    if let Some(a) = slot_of_theta[v] {
                        if active[a] {
                            active[a] = false;
                            held += 1;
                        }
                    }
                }
            }
            continue;
        }
        iterations += 1;
        let mut alpha = limit;
        let quadratic = -slope <= QUADRATIC_REGIME * cur.dirichlet.abs();
        if quadratic && step_max >= 0.5 * previous_step {
            converged = true;
            break;
        }
        let mut accepted = None;
        for _ in 0..MAX_HALVINGS {
            let trial = problem.apply(&st, &step, alpha);
            if problem.circles_valid(&trial) {
                let e = problem.eval(&trial);
                if quadratic || e.energy <= cur.energy + ARMIJO * alpha * slope {
                    accepted = Some((trial, e));
                    break;
                }
            }
            alpha *= 0.5;
        }
        let Some((next, e)) = accepted else {
            converged = step_max <= 1e3 * step_tol;
            break;
        };
        st = next;
        cur = e;
        history.push(cur.energy);
        previous_step = step_max;
        if step_max <= step_tol {
            converged = true;
            break;
        }
    }
    PolishResult {
        state: st,
        iterations,
        converged,
        energy_history: history,
        held_vertices: held,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A random-ish symmetric positive semidefinite `S` with zero row sums.
    fn test_schur(nb: usize) -> Vec<f64> {
        let mut s = vec![0.0; nb * nb];
        for i in 0..nb {
            for j in 0..nb {
                if i != j {
                    let w = 0.05 + 0.04 * (((i * 7 + j * 13) % 11) as f64 / 11.0);
                    s[j * nb + i] = -w;
                }
            }
        }
        for i in 0..nb {
            for j in i + 1..nb {
                let a = 0.5 * (s[j * nb + i] + s[i * nb + j]);
                s[j * nb + i] = a;
                s[i * nb + j] = a;
            }
            let sum: f64 = (0..nb).filter(|&j| j != i).map(|j| s[j * nb + i]).sum();
            s[i * nb + i] = -sum;
        }
        s
    }

    #[test]
    fn gradient_and_hessian_match_finite_differences() {
        let loops = vec![
            LoopSpec {
                start: 0,
                len: 6,
                sign: 1.0,
                free_circle: false,
                pinned_centre: false,
            },
            LoopSpec {
                start: 6,
                len: 4,
                sign: -1.0,
                free_circle: true,
                pinned_centre: true,
            },
            LoopSpec {
                start: 10,
                len: 5,
                sign: -1.0,
                free_circle: true,
                pinned_centre: false,
            },
        ];
        let s = test_schur(15);
        let problem = CircleProblem::new(&s, loops);
        let theta: Vec<f64> = (0..15)
            .map(|k| match k {
                0..=5 => k as f64 * 1.0 + 0.1 * (k as f64).sin(),
                6..=9 => -(k as f64 - 6.0) * 1.5,
                _ => -(k as f64 - 10.0) * 1.2 + 0.3,
            })
            .collect();
        let st = CircleState {
            theta,
            centre: vec![
                Complex64::new(0.0, 0.0),
                Complex64::new(0.0, 0.0),
                Complex64::new(0.4, -0.3),
            ],
            log_radius: vec![0.0, (0.2f64).ln(), (0.15f64).ln()],
        };
        let e = problem.eval(&st);
        let g = problem.gradient(&st, &e);
        let h = problem.hessian(&st, &e);
        let np = problem.params.len();
        let eps = 1e-6;
        for a in 0..np {
            let mut d = vec![0.0; np];
            d[a] = 1.0;
            let (p, m) = (problem.apply(&st, &d, eps), problem.apply(&st, &d, -eps));
            let fd = (problem.eval(&p).energy - problem.eval(&m).energy) / (2.0 * eps);
            assert!((fd - g[a]).abs() < 1e-7, "grad {a}: {fd} vs {}", g[a]);
            let (gp, gm) = (
                problem.gradient(&p, &problem.eval(&p)),
                problem.gradient(&m, &problem.eval(&m)),
            );
            for b in 0..np {
                let fd = (gp[b] - gm[b]) / (2.0 * eps);
                assert!(
                    (fd - h[a * np + b]).abs() < 1e-6,
                    "hess {a},{b}: {fd} vs {}",
                    h[a * np + b]
                );
            }
        }
    }
}
