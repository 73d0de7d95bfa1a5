//! Planar helpers of the Koebe iteration: best-fit circles of loop images, a point inside a
//! hole, boundary angles of a loop, and the Möbius normalization of a circle domain.

use std::f64::consts::TAU;

pub(crate) use conformap_operators::{circle_residual, fit_circle, Circle};
use num_complex::Complex64;

/// The winding number of the closed polygon `pts` around `p` (rounded total turning / 2π).
pub(crate) fn winding(pts: &[Complex64], p: Complex64) -> i64 {
    let m = pts.len();
    let mut total = 0.0;
    for k in 0..m {
        let (a, b) = (pts[k] - p, pts[(k + 1) % m] - p);
        total += (b * a.conj()).arg();
    }
    (total / TAU).round() as i64
}

/// Grid points per side of the bounding box searched by [`inner_point`]: `24` (576 points;
/// each costs `O(m)`), then [`INNER_REFINE`] rounds of an `8 × 8` grid around the best.
const INNER_GRID: usize = 24;
/// Refinement rounds of [`inner_point`]'s grid search: `3` (each shrinks the cell by 8).
const INNER_REFINE: usize = 3;

/// Distance from `p` to the closed polygon `pts`.
fn depth(pts: &[Complex64], p: Complex64) -> f64 {
    let m = pts.len();
    let mut best = f64::INFINITY;
    for k in 0..m {
        let (a, b) = (pts[k], pts[(k + 1) % m]);
        let ab = b - a;
        let len2 = ab.norm_sqr();
        let t = if len2 > 0.0 {
            (((p - a) * ab.conj()).re / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        best = best.min((p - (a + ab * t)).norm());
    }
    best
}

/// A point around which the polygon `pts` winds `want` times (`−1` for a hole loop, whose
/// surface lies on its left: it runs clockwise around the hole), as far from the polygon as
/// a grid search finds: the inversion `1/(z − c)` of a Koebe step is best conditioned with
/// `c` deep inside the hole (a centre near the loop crowds the rest of the domain onto a
/// tiny region). Candidates: the vertex centroid (CEM Algorithm 2, step 6), the best-fit
/// circle's centre, the area centroid and an [`INNER_GRID`]² grid over the bounding box,
/// refined [`INNER_REFINE`] times around the deepest; for a loop on a circle this is its
/// centre. Falls back to points just inside the longest edges; `None` if nothing
/// qualifies (the loop's image is not a simple polygon).
pub(crate) fn inner_point(pts: &[Complex64], want: i64) -> Option<Complex64> {
    let m = pts.len();
    if m < 3 {
        return None;
    }
    let ok = |p: Complex64| p.is_finite() && winding(pts, p) == want;
    let mean = pts.iter().sum::<Complex64>() / m as f64;
    let mut candidates = vec![mean, fit_circle(pts).center];
    let (mut a2, mut cx) = (0.0, Complex64::new(0.0, 0.0));
    for k in 0..m {
        let (p, q) = (pts[k], pts[(k + 1) % m]);
        let cr = p.re * q.im - q.re * p.im;
        a2 += cr;
        cx += (p + q) * cr;
    }
    if a2 != 0.0 {
        candidates.push(cx / (3.0 * a2));
    }
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for z in pts {
        lo = Complex64::new(lo.re.min(z.re), lo.im.min(z.im));
        hi = Complex64::new(hi.re.max(z.re), hi.im.max(z.im));
    }
    let grid = |centre: Complex64, half: Complex64, n: usize| -> Vec<Complex64> {
        let mut g = Vec::with_capacity(n * n);
        for i in 0..n {
            for j in 0..n {
                let u = (i as f64 + 0.5) / n as f64 * 2.0 - 1.0;
                let v = (j as f64 + 0.5) / n as f64 * 2.0 - 1.0;
                g.push(centre + Complex64::new(u * half.re, v * half.im));
            }
        }
        g
    };
    let mut half = 0.5 * (hi - lo);
    candidates.extend(grid(0.5 * (lo + hi), half, INNER_GRID));
    let mut best: Option<(Complex64, f64)> = None;
    let consider = |cands: &[Complex64], best: &mut Option<(Complex64, f64)>| {
        for &p in cands {
            if ok(p) {
                let d = depth(pts, p);
                if best.is_none_or(|b| d > b.1) {
                    *best = Some((p, d));
                }
            }
        }
    };
    consider(&candidates, &mut best);
    half /= INNER_GRID as f64;
    for _ in 0..INNER_REFINE {
        let Some((c, _)) = best else { break };
        let local = grid(c, half, 8);
        consider(&local, &mut best);
        half /= 8.0;
    }
    if let Some((p, _)) = best {
        return Some(p);
    }
    // just off an edge midpoint, to the side the polygon winds around
    let mut edges: Vec<usize> = (0..m).collect();
    edges.sort_by(|&i, &j| {
        let len = |k: usize| (pts[(k + 1) % m] - pts[k]).norm();
        len(j).total_cmp(&len(i))
    });
    let side = Complex64::new(0.0, want as f64);
    for &k in edges.iter().take(16) {
        let (p, q) = (pts[k], pts[(k + 1) % m]);
        for eps in [0.1, 0.01, 1e-3, 1e-5] {
            let c = 0.5 * (p + q) + side * (q - p) * eps;
            if ok(c) {
                return Some(c);
            }
        }
    }
    None
}

/// The angles of `pts` seen from the origin, unwrapped to increase along the loop, if they
/// do (every step in `(0, π)` and one full turn in all); else `None`.
pub(crate) fn unwrapped_angles(pts: &[Complex64]) -> Option<Vec<f64>> {
    let m = pts.len();
    let mut theta = Vec::with_capacity(m);
    let mut t = pts[0].arg();
    theta.push(t);
    let mut turn = 0.0;
    for k in 0..m {
        let d = (pts[(k + 1) % m] * pts[k].conj()).arg();
        if !(d > 0.0) {
            return None;
        }
        turn += d;
        if k + 1 < m {
            t += d;
            theta.push(t);
        }
    }
    ((turn - TAU).abs() < 1e-6).then_some(theta)
}

/// Angles proportional to arc length along the polygon `pts`, starting at the angle of
/// `pts[0]`: always strictly increasing (a fallback start for a loop that is not star-shaped
/// around the origin).
pub(crate) fn arc_length_angles(pts: &[Complex64]) -> Vec<f64> {
    let m = pts.len();
    let lens: Vec<f64> = (0..m)
        .map(|k| (pts[(k + 1) % m] - pts[k]).norm().max(f64::MIN_POSITIVE))
        .collect();
    let total: f64 = lens.iter().sum();
    let mut t = pts[0].arg();
    let mut theta = Vec::with_capacity(m);
    for len in &lens {
        theta.push(t);
        t += TAU * len / total;
    }
    theta
}

/// The point `p` inside the unit disk such that the disk automorphism
/// `z ↦ (z − p) / (1 − p̄ z)` makes `circle` (inside the unit disk, not meeting it) concentric
/// with the unit circle: the common symmetric point of the two circles (on the ray to the
/// circle's centre, `x = 2d / (1 + d² − r² + √((1 + d² − r²)² − 4d²))`, `d` the centre's
/// distance from 0).
pub(crate) fn concentric_point(circle: Circle) -> Complex64 {
    let d = circle.center.norm();
    if !(d > 0.0) {
        return Complex64::new(0.0, 0.0);
    }
    let b = 1.0 + d * d - circle.radius * circle.radius;
    let disc = (b * b - 4.0 * d * d).max(0.0);
    let x = 2.0 * d / (b + disc.sqrt());
    circle.center * (x / d)
}

/// The disk automorphism `z ↦ (z − p) / (1 − p̄ z)` (`|p| < 1`).
pub(crate) fn disk_automorphism(z: Complex64, p: Complex64) -> Complex64 {
    (z - p) / (1.0 - p.conj() * z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle_pts(c: Complex64, r: f64, n: usize, clockwise: bool) -> Vec<Complex64> {
        (0..n)
            .map(|k| {
                let t = TAU * k as f64 / n as f64 + 0.2 * (k as f64).sin() / n as f64;
                let t = if clockwise { -t } else { t };
                c + Complex64::from_polar(r, t)
            })
            .collect()
    }

    #[test]
    fn fit_and_winding_on_exact_circles() {
        let c = Complex64::new(0.3, -0.2);
        let pts = circle_pts(c, 0.25, 17, true);
        let fit = fit_circle(&pts);
        assert!((fit.center - c).norm() < 1e-14);
        assert!((fit.radius - 0.25).abs() < 1e-14);
        assert!(circle_residual(&pts, fit) < 1e-13);
        assert_eq!(winding(&pts, c), -1);
        assert_eq!(winding(&pts, Complex64::new(2.0, 0.0)), 0);
        let p = inner_point(&pts, -1).expect("inside");
        assert_eq!(winding(&pts, p), -1);
    }

    #[test]
    fn inner_point_of_a_crescent_is_inside() {
        // a C-shaped polygon whose vertex centroid lies outside it
        let mut pts = Vec::new();
        for k in 0..=20 {
            let t = 0.3 + 5.6 * f64::from(k) / 20.0;
            pts.push(Complex64::from_polar(1.0, t));
        }
        for k in (0..=20).rev() {
            let t = 0.3 + 5.6 * f64::from(k) / 20.0;
            pts.push(Complex64::from_polar(0.8, t));
        }
        assert_eq!(winding(&pts, Complex64::new(0.0, 0.0)), 0);
        let p = inner_point(&pts, 1).expect("a point inside");
        assert_eq!(winding(&pts, p), 1);
    }

    #[test]
    fn concentric_point_makes_circles_concentric() {
        let hole = Circle {
            center: Complex64::new(0.4, 0.3),
            radius: 0.2,
        };
        let p = concentric_point(hole);
        let images: Vec<Complex64> = (0..32)
            .map(|k| {
                disk_automorphism(
                    hole.center + Complex64::from_polar(0.2, TAU * f64::from(k) / 32.0),
                    p,
                )
            })
            .collect();
        let fit = fit_circle(&images);
        assert!(fit.center.norm() < 1e-13, "{}", fit.center);
        assert!(circle_residual(&images, fit) < 1e-12);
        // the unit circle stays the unit circle
        let z = disk_automorphism(Complex64::from_polar(1.0, 0.7), p);
        assert!((z.norm() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn angles_unwrap_or_fall_back() {
        let pts = circle_pts(Complex64::new(0.0, 0.0), 1.0, 10, false);
        let t = unwrapped_angles(&pts).expect("star-shaped");
        assert!(t.windows(2).all(|w| w[1] > w[0]));
        let mut bad = pts.clone();
        bad.swap(3, 4);
        assert!(unwrapped_angles(&bad).is_none());
        let t = arc_length_angles(&bad);
        assert!(t.windows(2).all(|w| w[1] > w[0]));
        assert!(t[9] - t[0] < TAU);
    }
}
