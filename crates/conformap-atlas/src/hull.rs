//! Convex hull of a planar point set and its minimum-area bounding rectangle.

/// The convex hull of `points`, counter-clockwise, without collinear points (Andrew's
/// monotone chain, `O(n log n)`). Fewer than three distinct points give those points.
///
/// ```
/// let hull = conformap_atlas::hull::convex_hull(&[[0.0, 0.0], [1.0, 0.0], [0.5, 0.2],
///     [1.0, 1.0], [0.0, 1.0]]);
/// assert_eq!(hull, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
/// ```
pub fn convex_hull(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut p: Vec<[f64; 2]> = points.to_vec();
    p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// A rectangle around a chart: turn the chart by `angle` (radians, counter-clockwise about
/// the origin), and it lies in `[min[0], min[0] + size[0]] × [min[1], min[1] + size[1]]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundingRect {
    /// The rotation that makes the rectangle axis-aligned.
    pub angle: f64,
    /// Its lower-left corner after the rotation.
    pub min: [f64; 2],
    /// Width and height after the rotation (width ≥ height).
    pub size: [f64; 2],
}

/// Rotates `p` by `angle` about the origin.
#[inline]
pub fn rotate(p: [f64; 2], angle: f64) -> [f64; 2] {
    let (s, c) = angle.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

/// The bounding rectangle of least area over every orientation (it has a side on a hull
/// edge, so the hull's edge directions are the candidates: rotating calipers in `O(h²)` on
/// the hull's `h` points, few for a chart's outline after hulling), turned so that its width
/// is at least its height. An empty input gives an empty rectangle at the origin.
pub fn min_area_rect(points: &[[f64; 2]]) -> BoundingRect {
    let hull = convex_hull(points);
    let mut best = bounds(&hull, 0.0);
    let mut best_area = best.size[0] * best.size[1];
    for k in 0..hull.len() {
        let (a, b) = (hull[k], hull[(k + 1) % hull.len()]);
        let angle = -(b[1] - a[1]).atan2(b[0] - a[0]);
        let r = bounds(&hull, angle);
        let area = r.size[0] * r.size[1];
        if area < best_area * (1.0 - 1e-12) {
            best = r;
            best_area = area;
        }
    }
    if best.size[1] > best.size[0] {
        best = bounds(&hull, best.angle + std::f64::consts::FRAC_PI_2);
    }
    best
}

/// Angles sampled over a quarter turn by [`min_square_rect`] before its refinement.
pub const SQUARE_SAMPLES: usize = 128;

/// The bounding rectangle of `points` whose longer side is shortest over all rotations:
/// the smallest square that holds them, which bounds the scale of a chart packed alone.
/// Sampled at [`SQUARE_SAMPLES`] angles over a quarter turn, then refined by golden-section
/// search around the best sample (the longer side is a maximum of sinusoids: piecewise
/// smooth, one minimum per sampling interval at this density).
pub fn min_square_rect(points: &[[f64; 2]]) -> BoundingRect {
    let hull = convex_hull(points);
    let side = |a: f64| {
        let r = bounds(&hull, a);
        r.size[0].max(r.size[1])
    };
    let step = std::f64::consts::FRAC_PI_2 / SQUARE_SAMPLES as f64;
    let mut best = 0.0;
    let mut best_side = side(0.0);
    for k in 1..SQUARE_SAMPLES {
        let a = k as f64 * step;
        let s = side(a);
        if s < best_side {
            (best, best_side) = (a, s);
        }
    }
    // golden section on [best − step, best + step]
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (best - step, best + step);
    for _ in 0..40 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if side(x1) < side(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let a = 0.5 * (lo + hi);
    let angle = if side(a) < best_side { a } else { best };
    bounds(&hull, angle)
}

/// The bounding rectangle of `points` in their own axes, or turned a quarter so that its
/// width is at least its height: the only turns a seamless atlas allows (a seam's rotation
/// must stay a multiple of π/2).
pub fn quarter_rect(points: &[[f64; 2]]) -> BoundingRect {
    let hull = convex_hull(points);
    let r = bounds(&hull, 0.0);
    if r.size[1] > r.size[0] {
        bounds(&hull, std::f64::consts::FRAC_PI_2)
    } else {
        r
    }
}

/// The axis-aligned bounds of `points` turned by `angle`.
fn bounds(points: &[[f64; 2]], angle: f64) -> BoundingRect {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for &p in points {
        let q = rotate(p, angle);
        for k in 0..2 {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
        }
    }
    if points.is_empty() {
        return BoundingRect {
            angle,
            min: [0.0; 2],
            size: [0.0; 2],
        };
    }
    BoundingRect {
        angle,
        min: lo,
        size: [hi[0] - lo[0], hi[1] - lo[1]],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turned_rectangle_is_found_at_its_own_size() {
        let rect = [[0.0, 0.0], [3.0, 0.0], [3.0, 1.0], [0.0, 1.0], [1.5, 0.5]];
        let turned: Vec<[f64; 2]> = rect.iter().map(|&p| rotate(p, 0.7)).collect();
        let r = min_area_rect(&turned);
        assert!(
            (r.size[0] - 3.0).abs() < 1e-12 && (r.size[1] - 1.0).abs() < 1e-12,
            "{r:?}"
        );
        // every point inside after the rotation
        for &p in &turned {
            let q = rotate(p, r.angle);
            assert!(q[0] >= r.min[0] - 1e-12 && q[0] <= r.min[0] + r.size[0] + 1e-12);
            assert!(q[1] >= r.min[1] - 1e-12 && q[1] <= r.min[1] + r.size[1] + 1e-12);
        }
    }

    #[test]
    fn a_square_is_held_by_itself_and_a_thin_diamond_by_its_diagonal() {
        let square: Vec<[f64; 2]> = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
            .iter()
            .map(|&p| rotate(p, 0.3))
            .collect();
        let r = min_square_rect(&square);
        assert!((r.size[0].max(r.size[1]) - 1.0).abs() < 1e-9, "{r:?}");
        // a long thin diamond (3 × 0.4) fits a square of side 3/√2 ≈ 2.12 on its
        // diagonal; lying in its smallest-area rectangle it needs 3
        let diamond = [[0.0, 0.0], [1.5, 0.2], [3.0, 0.0], [1.5, -0.2]];
        let r = min_square_rect(&diamond);
        let area = min_area_rect(&diamond);
        assert!(
            r.size[0].max(r.size[1]) < 0.75 * area.size[0],
            "{r:?} {area:?}"
        );
    }

    #[test]
    fn a_standing_rectangle_lies_down_and_degenerate_input_is_handled() {
        let r = min_area_rect(&[[0.0, 0.0], [1.0, 0.0], [1.0, 4.0], [0.0, 4.0]]);
        assert!((r.size[0] - 4.0).abs() < 1e-12 && (r.size[1] - 1.0).abs() < 1e-12);
        assert_eq!(min_area_rect(&[]).size, [0.0, 0.0]);
        let seg = min_area_rect(&[[0.0, 0.0], [1.0, 1.0]]);
        assert!((seg.size[0] - 2f64.sqrt()).abs() < 1e-12 && seg.size[1].abs() < 1e-12);
    }
}
