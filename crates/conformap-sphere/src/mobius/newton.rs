//! A small damped Newton minimizer over a ball in ℝᵈ (d = 2 or 3): forward-difference Hessian
//! of an analytic gradient, Levenberg damping, projection onto the ball (Newton on its
//! boundary sphere when the constraint is active), Armijo acceptance.

/// Relative step of the forward differences of the gradient that make the Hessian:
/// `1e-7 (1 + |x|)`. The gradient is analytic (rounding ~1e-16 relative), so the Hessian
/// error is about `h f''' + 1e-16/h ≈ 1e-8` relative: plenty for a Newton direction, at
/// `d` gradient evaluations per iteration instead of the `2d` of central differences.
const FD_STEP: f64 = 1e-7;

/// Armijo constant: a step must achieve this share of the decrease its first-order model
/// promises. The usual 1e-4.
const ARMIJO: f64 = 1e-4;

/// Damping tries per iteration before the iteration gives up (each multiplies λ by 4; 40
/// tries span 24 decades, from the Newton step to a gradient step far below rounding).
const MAX_DAMPING_TRIES: usize = 40;

/// A step whose first-order predicted decrease `−g·Δx` is at most this share of `|f|` is
/// below what an evaluation can resolve (the energies sum ~10⁵ face terms, each rounded at
/// `ε`): the iteration stops there as converged instead of trying it (an undamped Newton
/// step is still taken, unevaluated). `64 ε`: on armadillo's
/// uniform Möbius map the last useful Newton step predicts 3·10⁻¹³ of `f = 2.9·10⁻⁵`, the next
/// one 10⁻¹⁷ of it, which took 28 of the start's 45 evaluations in damped trials before.
const ROUNDING_DECREASE: f64 = 64.0 * f64::EPSILON;

/// An objective: value and gradient at a point.
pub(crate) type EvalFn<'a> = dyn Fn(&[f64]) -> (f64, Vec<f64>) + 'a;

/// An iterate closer than this (Euclidean, in the parameter's units: hyperbolic length) to
/// an optimum already found stops its start as merged into that optimum: 1e-3, well inside
/// Newton's quadratic basin on every mesh measured (it converges from 1 away), and far above
/// the step tolerance, so a start that merges saves most of its iterations.
pub(crate) const MERGE_TOL: f64 = 1e-3;

/// Settings of [`minimize`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct NewtonSettings<'k> {
    /// Iteration cap.
    pub max_iter: usize,
    /// Stop when an accepted step is shorter than this (absolute, in the parameter's units:
    /// hyperbolic length).
    pub step_tol: f64,
    /// Radius of the ball the iterate is kept in.
    pub radius: f64,
    /// Optima found by earlier starts (see [`MERGE_TOL`]).
    pub known: &'k [Vec<f64>],
}

/// Outcome of one local minimization.
#[derive(Debug, Clone)]
pub(crate) struct LocalMin {
    pub x: Vec<f64>,
    pub f: f64,
    pub iterations: usize,
    pub converged: bool,
    pub evaluations: usize,
    /// Index into `known` of the optimum this start ran into, if any.
    pub merged: Option<usize>,
}

/// Projects `x` onto the closed ball of radius `r`.
fn project(x: &mut [f64], r: f64) {
    let n = x.iter().map(|v| v * v).sum::<f64>().sqrt();
    if n > r {
        for v in x.iter_mut() {
            *v *= r / n;
        }
    }
}

/// Solves the small SPD system `a x = b` (row-major `d × d`) by Cholesky; `None` if `a` is
/// not positive definite.
fn solve_spd(a: &[f64], b: &[f64], d: usize) -> Option<Vec<f64>> {
    let mut l = vec![0.0; d * d];
    for i in 0..d {
        for j in 0..=i {
            let mut s = a[i * d + j];
            for k in 0..j {
                s -= l[i * d + k] * l[j * d + k];
            }
            if i == j {
                if !(s > 0.0) {
                    return None;
                }
                l[i * d + i] = s.sqrt();
            } else {
                l[i * d + j] = s / l[j * d + j];
            }
        }
    }
    let mut y = vec![0.0; d];
    for i in 0..d {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * d + k] * y[k];
        }
        y[i] = s / l[i * d + i];
    }
    let mut x = vec![0.0; d];
    for i in (0..d).rev() {
        let mut s = y[i];
        for k in i + 1..d {
            s -= l[k * d + i] * x[k];
        }
        x[i] = s / l[i * d + i];
    }
    Some(x)
}

/// The Hessian at `x` (gradient `g`) by forward differences of the gradient with step `h`,
/// symmetrized (row-major `d × d`; `d` evaluations).
fn fd_hessian(eval: &EvalFn<'_>, x: &[f64], g: &[f64], h: f64) -> Vec<f64> {
    let d = x.len();
    let mut hess = vec![0.0; d * d];
    for j in 0..d {
        let mut xp = x.to_vec();
        xp[j] += h;
        let (_, gp) = eval(&xp);
        for i in 0..d {
            hess[i * d + j] = (gp[i] - g[i]) / h;
        }
    }
    for i in 0..d {
        for j in 0..i {
            let s = 0.5 * (hess[i * d + j] + hess[j * d + i]);
            hess[i * d + j] = s;
            hess[j * d + i] = s;
        }
    }
    hess
}

/// Minimizes `eval` (value and gradient) from `x0` inside the ball of radius
/// `settings.radius`.
pub(crate) fn minimize(eval: &EvalFn<'_>, x0: &[f64], settings: &NewtonSettings<'_>) -> LocalMin {
    let d = x0.len();
    let mut x = x0.to_vec();
    project(&mut x, settings.radius);
    let (mut f, mut g) = eval(&x);
    let mut evaluations = 1;
    let mut lambda = 0.0f64;
    let mut converged = false;
    let mut iterations = 0;
    let mut merged = None;
    for _ in 0..settings.max_iter {
        iterations += 1;
        let xn = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        let hess = fd_hessian(eval, &x, &g, FD_STEP * (1.0 + xn));
        evaluations += d;
        // on the ball's boundary with the descent pointing outwards, Newton on the sphere
        // |x| = R: reduced gradient Bᵀg and Riemannian Hessian Bᵀ H B − (g·x̂/R) I in a
        // tangent basis B, steps retracted onto the sphere
        let radial: f64 = g.iter().zip(&x).map(|(a, b)| a * b).sum::<f64>() / xn.max(1e-300);
        let active = xn >= settings.radius * (1.0 - 1e-10) && radial < 0.0;
        let basis: Vec<Vec<f64>> = if active {
            tangent_basis(&x)
        } else {
            (0..d)
                .map(|i| (0..d).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
                .collect()
        };
        let m = basis.len();
        let gr: Vec<f64> = basis
            .iter()
            .map(|b| b.iter().zip(&g).map(|(p, q)| p * q).sum())
            .collect();
        let mut hr = vec![0.0; m * m];
        for i in 0..m {
            for j in 0..m {
                let mut sum = 0.0;
                for k in 0..d {
                    for l in 0..d {
                        sum += basis[i][k] * hess[k * d + l] * basis[j][l];
                    }
                }
                hr[i * m + j] = sum;
            }
            if active {
                hr[i * m + i] -= radial / settings.radius;
            }
        }
        let scale = (0..m).map(|i| hr[i * m + i].abs()).fold(0.0, f64::max);
        let floor = 1e-8
            * scale
                .max(gr.iter().map(|v| v.abs()).fold(0.0, f64::max))
                .max(1e-300);
        let mut accepted = false;
        let mut step_len = 0.0;
        for _ in 0..MAX_DAMPING_TRIES {
            let mut a = hr.clone();
            for i in 0..m {
                a[i * m + i] += lambda;
            }
            let neg: Vec<f64> = gr.iter().map(|v| -v).collect();
            let Some(step) = solve_spd(&a, &neg, m) else {
                lambda = (4.0 * lambda).max(floor);
                continue;
            };
            let mut xt = x.clone();
            for (b, s) in basis.iter().zip(&step) {
                for k in 0..d {
                    xt[k] += b[k] * s;
                }
            }
            if active {
                let nt = xt.iter().map(|v| v * v).sum::<f64>().sqrt();
                for v in xt.iter_mut() {
                    *v *= settings.radius / nt;
                }
            } else {
                project(&mut xt, settings.radius);
            }
            let pred: f64 = if active {
                gr.iter().zip(&step).map(|(a, b)| a * b).sum()
            } else {
                g.iter()
                    .zip(xt.iter().zip(&x))
                    .map(|(gi, (a, b))| gi * (a - b))
                    .sum()
            };
            if -pred <= ROUNDING_DECREASE * f.abs() {
                // the step's predicted decrease is below the rounding of `f`: no trial can
                // show a decrease any more (each would be damped again, up to
                // MAX_DAMPING_TRIES evaluations). An undamped Newton step is taken without
                // a trial (it only polishes the gradient, by rounding-level changes of
                // `f`), a damped one is not; either way `x` is the optimum to rounding
                if lambda == 0.0 {
                    x = xt;
                }
                break;
            }
            let (ft, gt) = eval(&xt);
            evaluations += 1;
            if ft.is_finite() && ft <= f + ARMIJO * pred.min(0.0) && ft <= f {
                step_len = xt
                    .iter()
                    .zip(&x)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>()
                    .sqrt();
                x = xt;
                f = ft;
                g = gt;
                lambda *= 0.25;
                if lambda < floor {
                    lambda = 0.0;
                }
                accepted = true;
                break;
            }
            lambda = (4.0 * lambda).max(floor);
        }
        if !accepted || step_len < settings.step_tol {
            // no decrease possible at rounding level, or the step has become negligible
            converged = true;
            break;
        }
        merged = settings.known.iter().position(|k| {
            k.iter()
                .zip(&x)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
                < MERGE_TOL
        });
        if merged.is_some() {
            converged = true;
            break;
        }
    }
    LocalMin {
        x,
        f,
        iterations,
        converged,
        evaluations,
        merged,
    }
}

/// An orthonormal basis of the plane orthogonal to `x` (d − 1 vectors; d ≤ 3).
fn tangent_basis(x: &[f64]) -> Vec<Vec<f64>> {
    let d = x.len();
    let n = x.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut basis: Vec<Vec<f64>> = vec![x.iter().map(|v| v / n).collect()];
    for i in 0..d {
        let mut e: Vec<f64> = (0..d).map(|j| if i == j { 1.0 } else { 0.0 }).collect();
        for b in &basis {
            let p: f64 = b.iter().zip(&e).map(|(a, c)| a * c).sum();
            for k in 0..d {
                e[k] -= p * b[k];
            }
        }
        let len = e.iter().map(|v| v * v).sum::<f64>().sqrt();
        // a standard axis nearly parallel to the span so far adds nothing
        if len > 0.3 {
            basis.push(e.iter().map(|v| v / len).collect());
        }
        if basis.len() == d {
            break;
        }
    }
    basis.remove(0);
    basis
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimizes_a_rosenbrock_valley_and_respects_the_ball() {
        let rosen = |x: &[f64]| {
            let (a, b) = (x[0], x[1]);
            let f = (1.0 - a).powi(2) + 100.0 * (b - a * a).powi(2);
            let g = vec![
                -2.0 * (1.0 - a) - 400.0 * a * (b - a * a),
                200.0 * (b - a * a),
            ];
            (f, g)
        };
        let s = NewtonSettings {
            max_iter: 200,
            step_tol: 1e-12,
            radius: 10.0,
            known: &[],
        };
        let r = minimize(&rosen, &[-1.2, 1.0], &s);
        assert!(r.converged);
        assert!(
            (r.x[0] - 1.0).abs() < 1e-8 && (r.x[1] - 1.0).abs() < 1e-8,
            "{:?}",
            r.x
        );
        // with the optimum outside the ball, the result is on the ball's boundary
        let lin = |x: &[f64]| (x[0] + 2.0 * x[1], vec![1.0, 2.0]);
        let s = NewtonSettings { radius: 1.0, ..s };
        let r = minimize(&lin, &[0.0, 0.0], &s);
        let n = (r.x[0] * r.x[0] + r.x[1] * r.x[1]).sqrt();
        assert!((n - 1.0).abs() < 1e-9);
        assert!((r.x[1] / r.x[0] - 2.0).abs() < 1e-6, "{:?}", r.x);
    }
}
