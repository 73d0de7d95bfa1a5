//! The least-squares circle through planar points (Kåsa fit refined by Gauss–Newton on the
//! geometric distances): Koebe's circle domains fit their loops with it and the metrics
//! judge a map's boundary loops with it, so both use this one copy.

use num_complex::Complex64;
use serde::{Deserialize, Serialize};

/// Gauss–Newton refinement steps of [`fit_circle`] at most (a handful suffice on
/// near-circles; the cap only guards a non-convergent refinement).
pub const FIT_REFINE_STEPS: usize = 20;

/// A circle in the plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Centre.
    pub center: Complex64,
    /// Radius (0 for coincident points).
    pub radius: f64,
}

impl Circle {
    /// The unit circle.
    pub const UNIT: Self = Self {
        center: Complex64::new(0.0, 0.0),
        radius: 1.0,
    };
}

/// The least-squares circle through `pts`.
///
/// 1. Normalize: centre the points on their mean `m` and scale by their RMS distance `s`
///    (all points equal, or none: the circle of radius 0 at `m`).
/// 2. Kåsa fit: minimize `Σ (|z|² + D x + E y + F)²` (linear, exact for points on a circle).
///    If its 2×2 system is singular (collinear points), fall back to centre `m`, radius the
///    mean distance to `m`.
/// 3. Refine `Σ (|z − c| − r)²` (the geometric fit) by Gauss–Newton, accepting only steps
///    that lower it, at most [`FIT_REFINE_STEPS`] times.
///
/// # Examples
/// ```
/// use conformap_operators::{fit_circle, circle_residual};
/// use num_complex::Complex64;
/// let c = Complex64::new(2.0, -1.0);
/// let pts: Vec<Complex64> = (0..12)
///     .map(|k| c + Complex64::from_polar(0.5, f64::from(k) * 0.5))
///     .collect();
/// let fit = fit_circle(&pts);
/// assert!((fit.center - c).norm() < 1e-12 && (fit.radius - 0.5).abs() < 1e-12);
/// assert!(circle_residual(&pts, fit) < 1e-12);
/// ```
pub fn fit_circle(pts: &[Complex64]) -> Circle {
    let n = pts.len().max(1) as f64;
    let mean = pts.iter().sum::<Complex64>() / n;
    let scale = (pts.iter().map(|z| (z - mean).norm_sqr()).sum::<f64>() / n).sqrt();
    if !(scale > 0.0 && scale.is_finite()) {
        return Circle {
            center: mean,
            radius: 0.0,
        };
    }
    let x: Vec<Complex64> = pts.iter().map(|z| (z - mean) / scale).collect();
    let (mut sxx, mut sxy, mut syy, mut sxq, mut syq) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for z in &x {
        let q = z.norm_sqr();
        sxx += z.re * z.re;
        sxy += z.re * z.im;
        syy += z.im * z.im;
        sxq += z.re * q;
        syq += z.im * q;
    }
    let det = sxx * syy - sxy * sxy;
    let (mut c, mut r) = if det > 1e-12 * n * n {
        let d = -(syy * sxq - sxy * syq) / det;
        let e = -(sxx * syq - sxy * sxq) / det;
        let c = Complex64::new(-0.5 * d, -0.5 * e);
        (c, (c.norm_sqr() + 1.0).sqrt())
    } else {
        (
            Complex64::new(0.0, 0.0),
            x.iter().map(|z| z.norm()).sum::<f64>() / n,
        )
    };
    let cost = |c: Complex64, r: f64| x.iter().map(|z| ((z - c).norm() - r).powi(2)).sum::<f64>();
    let mut current = cost(c, r);
    for _ in 0..FIT_REFINE_STEPS {
        let mut jtj = [[0.0; 3]; 3];
        let mut jtr = [0.0; 3];
        for z in &x {
            let w = z - c;
            let d = w.norm();
            if !(d > 0.0) {
                continue;
            }
            let row = [-w.re / d, -w.im / d, -1.0];
            for i in 0..3 {
                jtr[i] += row[i] * (d - r);
                for j in 0..3 {
                    jtj[i][j] += row[i] * row[j];
                }
            }
        }
        let Some(step) = solve3(jtj, [-jtr[0], -jtr[1], -jtr[2]]) else {
            break;
        };
        let (c2, r2) = (c + Complex64::new(step[0], step[1]), r + step[2]);
        let trial = cost(c2, r2);
        if !(trial < current && r2 > 0.0) {
            break;
        }
        (c, r, current) = (c2, r2, trial);
    }
    Circle {
        center: mean + c * scale,
        radius: r * scale,
    }
}

/// Cramer's rule for a 3×3 system; `None` when (numerically) singular.
fn solve3(a: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det3 = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let det = det3(a);
    let scale = a.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    if !(det.abs() > 1e-14 * scale * scale * scale) {
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

/// `max ||z − c| − r| / r` over `pts`; 1 for a circle of radius 0 (a collapsed loop).
pub fn circle_residual(pts: &[Complex64], circle: Circle) -> f64 {
    if !(circle.radius > 0.0) {
        return 1.0;
    }
    pts.iter()
        .map(|z| ((z - circle.center).norm() - circle.radius).abs() / circle.radius)
        .fold(0.0, f64::max)
}

/// How well one boundary loop's image lies on a circle: the circle of a loop as a disk
/// map with holes reports it and as the metrics judge any map's loops.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct LoopCircle {
    /// Index into `mesh.boundary_loops()`.
    pub loop_index: usize,
    /// Number of vertices on the loop.
    pub vertices: usize,
    /// Whether this is the outer loop.
    pub outer: bool,
    /// Centre `(u, v)` of the circle, in the coordinates of the map as given (before any
    /// orientation fix): the loop's best-fit circle ([`fit_circle`]), or `(0, 0)` for an
    /// outer loop judged against the unit circle.
    pub center: [f64; 2],
    /// Radius of the circle (1 for an outer loop judged against the unit circle).
    pub radius: f64,
    /// `max ||f − c| − r| / r` over the loop's vertices (relative; for the unit circle the
    /// same as absolute). 1 for a loop collapsed to a point.
    pub residual_max: f64,
}

impl LoopCircle {
    /// Loop `loop_index` with `vertices` vertices on `circle`, its largest relative
    /// distance from it `residual_max`.
    ///
    /// ```
    /// use conformap_operators::{Circle, LoopCircle};
    /// use num_complex::Complex64;
    /// let unit = Circle { center: Complex64::new(0.0, 0.0), radius: 1.0 };
    /// let c = LoopCircle::new(0, 12, true, unit, 1e-9);
    /// assert_eq!((c.center, c.radius, c.residual_max), ([0.0, 0.0], 1.0, 1e-9));
    /// ```
    pub fn new(
        loop_index: usize,
        vertices: usize,
        outer: bool,
        circle: Circle,
        residual_max: f64,
    ) -> Self {
        Self {
            loop_index,
            vertices,
            outer,
            center: [circle.center.re, circle.center.im],
            radius: circle.radius,
            residual_max,
        }
    }
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
    fn exact_circle_is_recovered_far_from_the_origin() {
        let c = Complex64::new(1e3, -2e3);
        let pts = on_circle(c, 0.25, 40, 0.0);
        let fit = fit_circle(&pts);
        assert!((fit.center - c).norm() < 1e-12 * 1e3);
        assert!((fit.radius - 0.25).abs() < 1e-9);
        assert!(circle_residual(&pts, fit) < 1e-9);
    }

    #[test]
    fn geometric_refinement_on_a_wobbly_loop() {
        let pts = on_circle(Complex64::new(0.0, 0.0), 1.0, 60, 0.1);
        let fit = fit_circle(&pts);
        // symmetric wobble: centre stays put, radius is the mean radius
        assert!(fit.center.norm() < 1e-12);
        assert!((fit.radius - 1.0).abs() < 1e-3);
        let res = circle_residual(&pts, fit);
        assert!((res - 0.1).abs() < 2e-3, "{res}");
    }

    #[test]
    fn degenerate_point_sets_do_not_produce_nan() {
        let point = vec![Complex64::new(0.5, 0.5); 4];
        let fit = fit_circle(&point);
        assert_eq!(fit.radius, 0.0);
        assert_eq!(circle_residual(&point, fit), 1.0);
        let line: Vec<Complex64> = (0..4).map(|k| Complex64::new(f64::from(k), 0.0)).collect();
        let fit = fit_circle(&line);
        assert!(fit.radius.is_finite() && fit.center.is_finite());
        assert!(circle_residual(&line, fit).is_finite());
        let fit = fit_circle(&[]);
        assert_eq!(fit.radius, 0.0);
    }
}
