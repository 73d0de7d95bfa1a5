//! Best-fit circles of boundary loops: algebraic (Kåsa) fit, refined by Gauss–Newton on the
//! geometric distances.

use num_complex::Complex64;

/// Gauss–Newton refinement steps at most (it converges in a handful for near-circles).
const REFINE_STEPS: usize = 20;

/// A fitted circle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Fit {
    pub(crate) center: Complex64,
    pub(crate) radius: f64,
}

/// The least-squares circle through the map values of loop `lp`.
///
/// 1. Normalize: centre the points on their mean `m` and scale by their RMS distance `s`
///    (all points equal: the circle of radius 0 at `m`).
/// 2. Kåsa fit: minimize `Σ (|z|² + D x + E y + F)²` (linear, exact for points on a circle).
///    If its 2×2 system is singular (collinear points), fall back to centre `m`, radius the
///    mean distance to `m`.
/// 3. Refine `Σ (|z − c| − r)²` (the geometric fit) by Gauss–Newton, accepting only steps
///    that lower it, at most [`REFINE_STEPS`] times.
pub(crate) fn fit_circle(lp: &[u32], map: &[Complex64]) -> Fit {
    let n = lp.len() as f64;
    let at = |v: &u32| map[*v as usize];
    let m = lp.iter().map(at).sum::<Complex64>() / n;
    let s = (lp.iter().map(|v| (at(v) - m).norm_sqr()).sum::<f64>() / n).sqrt();
    if s.is_nan() || s <= 0.0 {
        return Fit {
            center: m,
            radius: 0.0,
        };
    }
    let x = |v: &u32| (at(v) - m) / s;
    // Kåsa on the normalized points: Σx = Σy = 0 and mean |x|² = 1, so F = −1 and
    // [Sxx Sxy; Sxy Syy] [D; E] = −[Σ x q; Σ y q], q = |x|².
    let (mut sxx, mut sxy, mut syy, mut sxq, mut syq) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for v in lp {
        let z = x(v);
        let q = z.norm_sqr();
        sxx += z.re * z.re;
        sxy += z.re * z.im;
        syy += z.im * z.im;
        sxq += z.re * q;
        syq += z.im * q;
    }
    let det = sxx * syy - sxy * sxy;
    // sxx + syy = n, so det is at most n²/4; a relative 1e-12 means collinear points
    let (mut c, mut r) = if det > 1e-12 * n * n {
        let d = -(syy * sxq - sxy * syq) / det;
        let e = -(sxx * syq - sxy * sxq) / det;
        let c = Complex64::new(-0.5 * d, -0.5 * e);
        (c, (c.norm_sqr() + 1.0).sqrt())
    } else {
        let mean_dist = lp.iter().map(|v| x(v).norm()).sum::<f64>() / n;
        (Complex64::new(0.0, 0.0), mean_dist)
    };
    let cost =
        |c: Complex64, r: f64| -> f64 { lp.iter().map(|v| ((x(v) - c).norm() - r).powi(2)).sum() };
    let mut current = cost(c, r);
    for _ in 0..REFINE_STEPS {
        let Some(step) = gauss_newton_step(lp, &x, c, r) else {
            break;
        };
        let (c_new, r_new) = (c + Complex64::new(step[0], step[1]), r + step[2]);
        let trial = cost(c_new, r_new);
        let improves = trial < current && r_new > 0.0;
        if !improves {
            break;
        }
        (c, r, current) = (c_new, r_new, trial);
        if step.iter().map(|d| d.abs()).sum::<f64>() <= 4.0 * f64::EPSILON * (1.0 + r) {
            break;
        }
    }
    Fit {
        center: m + c * s,
        radius: r * s,
    }
}

/// One Gauss–Newton step `(δcx, δcy, δr)` for `Σ (|x_i − c| − r)²`, or `None` if the normal
/// equations are singular.
fn gauss_newton_step(
    lp: &[u32],
    x: &impl Fn(&u32) -> Complex64,
    c: Complex64,
    r: f64,
) -> Option<[f64; 3]> {
    let mut jtj = [[0.0; 3]; 3];
    let mut jtr = [0.0; 3];
    for v in lp {
        let w = x(v) - c;
        let d = w.norm();
        if d.is_nan() || d <= 0.0 {
            continue;
        }
        let row = [-w.re / d, -w.im / d, -1.0];
        let res = d - r;
        for i in 0..3 {
            jtr[i] += row[i] * res;
            for j in 0..3 {
                jtj[i][j] += row[i] * row[j];
            }
        }
    }
    solve3(jtj, [-jtr[0], -jtr[1], -jtr[2]])
}

/// Solves a 3×3 system by Cramer's rule; `None` if it is (numerically) singular.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let det = det3(a);
    let scale = a.iter().flatten().map(|v| v.abs()).fold(0.0, f64::max);
    let regular = det.abs() > 1e-14 * scale * scale * scale;
    if !regular {
        return None;
    }
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let mut m = a;
        for i in 0..3 {
            m[i][k] = b[i];
        }
        *o = det3(m) / det;
    }
    Some(out)
}

/// `max ||f_v| − 1|` over the loop: distance from the unit circle.
pub(crate) fn unit_circle_residual(lp: &[u32], map: &[Complex64]) -> f64 {
    lp.iter()
        .map(|&v| (map[v as usize].norm() - 1.0).abs())
        .fold(0.0, f64::max)
}

/// `max ||f_v − c| − r| / r` over the loop; 1 (a full radius) if the circle has radius 0
/// (the loop collapsed to a point).
pub(crate) fn relative_residual(lp: &[u32], map: &[Complex64], fit: Fit) -> f64 {
    if fit.radius.is_nan() || fit.radius <= 0.0 {
        return 1.0;
    }
    lp.iter()
        .map(|&v| ((map[v as usize] - fit.center).norm() - fit.radius).abs() / fit.radius)
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn on_circle(c: Complex64, r: f64, n: usize, wobble: f64) -> Vec<Complex64> {
        (0..n)
            .map(|k| {
                let t = 0.3 + 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                c + Complex64::from_polar(r * (1.0 + wobble * (3.0 * t).cos()), t)
            })
            .collect()
    }

    #[test]
    fn exact_circle_is_recovered() {
        let c = Complex64::new(1e3, -2e3);
        let map = on_circle(c, 0.25, 40, 0.0);
        let lp: Vec<u32> = (0..40).collect();
        let fit = fit_circle(&lp, &map);
        assert!((fit.center - c).norm() < 1e-12 * 1e3);
        assert!((fit.radius - 0.25).abs() < 1e-9);
        assert!(relative_residual(&lp, &map, fit) < 1e-9);
    }

    #[test]
    fn geometric_refinement_beats_kasa_on_a_wobbly_loop() {
        let map = on_circle(Complex64::new(0.0, 0.0), 1.0, 60, 0.1);
        let lp: Vec<u32> = (0..60).collect();
        let fit = fit_circle(&lp, &map);
        // symmetric wobble: centre stays put, radius is the mean radius
        assert!(fit.center.norm() < 1e-12);
        assert!((fit.radius - 1.0).abs() < 1e-3);
        let res = relative_residual(&lp, &map, fit);
        assert!((res - 0.1).abs() < 2e-3, "{res}");
    }

    #[test]
    fn degenerate_loops_do_not_produce_nan() {
        let lp: Vec<u32> = (0..4).collect();
        let point = vec![Complex64::new(0.5, 0.5); 4];
        let fit = fit_circle(&lp, &point);
        assert_eq!(fit.radius, 0.0);
        assert_eq!(relative_residual(&lp, &point, fit), 1.0);
        let line: Vec<Complex64> = (0..4).map(|k| Complex64::new(f64::from(k), 0.0)).collect();
        let fit = fit_circle(&lp, &line);
        assert!(fit.radius.is_finite() && fit.center.is_finite());
        assert!(relative_residual(&lp, &line, fit).is_finite());
    }
}
