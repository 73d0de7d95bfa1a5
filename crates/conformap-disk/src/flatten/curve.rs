//! The boundary curve of boundary first flattening (Sawhney & Crane 2017, §4.3): edge
//! lengths from the boundary scale factors, tangent directions from the running sum of the
//! target curvature, the smallest length change that closes it, and a check that it does
//! not touch itself.

use conformap_mesh::TriMesh;
use num_complex::Complex64;

/// Directions within this many radians of a multiple of `π/2` are snapped to it exactly,
/// so rectangle sides come out axis-parallel to the last bit.
pub const AXIS_SNAP_RAD: f64 = 1e-12;

/// 3D lengths of the boundary edges `loop[k] → loop[k + 1]`.
pub(crate) fn edge_lengths(mesh: &TriMesh, lp: &[u32]) -> Vec<f64> {
    let p = mesh.positions();
    let m = lp.len();
    (0..m)
        .map(|k| {
            let (a, b) = (p[lp[k] as usize], p[lp[(k + 1) % m] as usize]);
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        })
        .collect()
}

/// Target lengths `l̃_k = e^{(u_k + u_{k+1})/2} l_k` (the paper's Eq. 12).
pub(crate) fn scaled_lengths(lengths: &[f64], u_b: &[f64]) -> Vec<f64> {
    let m = lengths.len();
    (0..m)
        .map(|k| ((u_b[k] + u_b[(k + 1) % m]) / 2.0).exp() * lengths[k])
        .collect()
}

/// Unit tangents of the edges: edge `k` turns by the cumulative `κ̃` of vertices
/// `start + 1 ..= k` (cyclically) relative to edge `start`, which points along `+x`.
pub(crate) fn tangents(kappa: &[f64], start: usize) -> Vec<Complex64> {
    let m = kappa.len();
    let mut t = vec![Complex64::new(1.0, 0.0); m];
    let mut phi = 0.0;
    for s in 1..m {
        let k = (start + s) % m;
        phi += kappa[k];
        t[k] = snapped(phi);
    }
    t
}

fn snapped(phi: f64) -> Complex64 {
    let q = phi / std::f64::consts::FRAC_PI_2;
    let r = q.round();
    if (phi - r * std::f64::consts::FRAC_PI_2).abs() < AXIS_SNAP_RAD {
        match (r as i64).rem_euclid(4) {
            0 => Complex64::new(1.0, 0.0),
            1 => Complex64::new(0.0, 1.0),
            2 => Complex64::new(-1.0, 0.0),
            _ => Complex64::new(0.0, -1.0),
        }
    } else {
        Complex64::from_polar(1.0, phi)
    }
}

/// The closed curve: the lengths changed as little as possible, `min Σ (l*_k − l̃_k)² / w_k`
/// (the norm of the inverse boundary mass matrix `N⁻¹`, `N = diag(w)`), subject to
/// `Σ l*_k T_k = 0` (the paper's Eq. 13): `l* = l̃ − N Tᵀ λ` with the 2 × 2 system
/// `(T N Tᵀ) λ = T l̃`.
///
/// [`super::flatten`] weights by the target lengths, `w = l̃` (the mass matrix of the
/// flattened boundary, the paper's with `u = 0`): every edge then changes by the same
/// *relative* amount along a direction, `l*_k = l̃_k (1 − T_k · λ)`, so the tiny edges of a
/// crowded boundary (a rectangle's corners on a long limb, `e^u ≪ 1`) are not pushed to
/// negative lengths, as weighting by the 3D lengths does.
#[derive(Debug, Clone)]
pub(crate) struct ClosedCurve {
    /// Vertex positions in loop order, `points[start] = 0`.
    pub points: Vec<Complex64>,
    /// The closed lengths `l*`.
    pub lengths: Vec<f64>,
    /// `|Σ l̃ T|` before closing, relative to the perimeter.
    pub gap_before: f64,
    /// `|Σ l* T|` after closing, relative to the perimeter (the closure residual).
    pub residual: f64,
    /// `max |l*_k / l̃_k − 1|`.
    pub max_length_change: f64,
}

/// Closes and lays out the curve of lengths `target` (`weights` = the mass `l_k`) and unit
/// tangents `t`, starting at vertex `start`.
///
/// `groups[k]` names the group of edge `k`: edges of one group change their lengths by the
/// same relative amount (the two sides of a seam of a cut surface stay equal), so the
/// closing solves for one change per group: `Δl_k = w_k s_g` minimizing `Σ_g W_g s_g²`
/// (`W_g = Σ_{k∈g} w_k`) subject to `Σ_g s_g a_g = −gap` (`a_g = Σ_{k∈g} w_k T_k`), a 2 × 2
/// system `M μ = gap` with `M = Σ_g a_g a_gᵀ / W_g` and `s_g = −a_g·μ / W_g`. With every
/// edge its own group this is the plain closing.
pub(crate) fn close_curve(
    target: &[f64],
    weights: &[f64],
    t: &[Complex64],
    start: usize,
    groups: &[u32],
) -> ClosedCurve {
    let sum = |l: &[f64]| -> Complex64 { l.iter().zip(t).map(|(&a, &d)| d * a).sum() };
    let perimeter: f64 = target.iter().sum();
    let gap = sum(target);
    let ng = groups.iter().map(|&g| g as usize + 1).max().unwrap_or(0);
    let mut a_g = vec![Complex64::new(0.0, 0.0); ng];
    let mut w_g = vec![0.0; ng];
    for ((&g, &w), d) in groups.iter().zip(weights).zip(t) {
        a_g[g as usize] += d * w;
        w_g[g as usize] += w;
    }
    // M, symmetric 2 × 2
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for (d, &w) in a_g.iter().zip(&w_g) {
        if w > 0.0 {
            a += d.re * d.re / w;
            b += d.re * d.im / w;
            c += d.im * d.im / w;
        }
    }
    let det = a * c - b * b;
    let lengths: Vec<f64> = if det > f64::EPSILON * (a + c).powi(2) {
        let lx = (c * gap.re - b * gap.im) / det;
        let ly = (a * gap.im - b * gap.re) / det;
        let s: Vec<f64> = a_g
            .iter()
            .zip(&w_g)
            .map(|(d, &w)| {
                if w > 0.0 {
                    (d.re * lx + d.im * ly) / w
                } else {
                    0.0
                }
            })
            .collect();
        target
            .iter()
            .zip(weights.iter().zip(groups))
            .map(|(&l, (&w, &g))| l - w * s[g as usize])
            .collect()
    } else {
        // all tangents parallel: nothing closes it; keep the lengths, report the gap
        target.to_vec()
    };
    let m = target.len();
    let mut points = vec![Complex64::new(0.0, 0.0); m];
    for s in 0..m.saturating_sub(1) {
        let k = (start + s) % m;
        points[(k + 1) % m] = points[k] + t[k] * lengths[k];
    }
    let max_length_change = lengths
        .iter()
        .zip(target)
        .map(|(l, t)| (l / t - 1.0).abs())
        .fold(0.0, f64::max);
    ClosedCurve {
        residual: sum(&lengths).norm() / perimeter,
        gap_before: gap.norm() / perimeter,
        points,
        lengths,
        max_length_change,
    }
}

/// Pairs of non-adjacent boundary edges of `map` that intersect or touch, over all loops of
/// `mesh` (a sweep over the edges sorted by their smallest `x`): 0 for a simple boundary.
pub(crate) fn boundary_touches(mesh: &TriMesh, map: &[Complex64]) -> usize {
    let mut segs: Vec<(Complex64, Complex64, u32, u32)> = Vec::new();
    for lp in mesh.boundary_loops() {
        for k in 0..lp.len() {
            let (i, j) = (lp[k], lp[(k + 1) % lp.len()]);
            segs.push((map[i as usize], map[j as usize], i, j));
        }
    }
    segs.sort_by(|a, b| a.0.re.min(a.1.re).total_cmp(&b.0.re.min(b.1.re)));
    let mut count = 0;
    for (n, s) in segs.iter().enumerate() {
        let xmax = s.0.re.max(s.1.re);
        for r in &segs[n + 1..] {
            if r.0.re.min(r.1.re) > xmax {
                break;
            }
            let shared = s.2 == r.2 || s.2 == r.3 || s.3 == r.2 || s.3 == r.3;
            if !shared && segments_meet(s.0, s.1, r.0, r.1) {
                count += 1;
            }
        }
    }
    count
}

fn cross(a: Complex64, b: Complex64) -> f64 {
    a.re * b.im - a.im * b.re
}

/// Whether the closed segments `pq` and `rs` have a point in common.
fn segments_meet(p: Complex64, q: Complex64, r: Complex64, s: Complex64) -> bool {
    let d1 = cross(q - p, r - p);
    let d2 = cross(q - p, s - p);
    let d3 = cross(s - r, p - r);
    let d4 = cross(s - r, q - r);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |a: Complex64, b: Complex64, c: Complex64, d: f64| {
        d == 0.0
            && c.re >= a.re.min(b.re)
            && c.re <= a.re.max(b.re)
            && c.im >= a.im.min(b.im)
            && c.im <= a.im.max(b.im)
    };
    on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_closes_and_an_open_one_is_closed_with_the_least_change() {
        let pi2 = std::f64::consts::FRAC_PI_2;
        let kappa = [pi2; 4];
        let t = tangents(&kappa, 0);
        let c = close_curve(&[1.0, 1.0, 1.0, 1.0], &[1.0; 4], &t, 0, &[0, 1, 2, 3]);
        assert!(c.residual < 1e-15 && c.gap_before < 1e-15);
        assert_eq!(c.points[2], Complex64::new(1.0, 1.0));
        // one side too long by 0.2: the two horizontal sides share the change
        let c = close_curve(&[1.2, 1.0, 1.0, 1.0], &[1.0; 4], &t, 0, &[0, 1, 2, 3]);
        assert!(c.residual < 1e-15);
        assert!((c.lengths[0] - 1.1).abs() < 1e-15 && (c.lengths[2] - 1.1).abs() < 1e-15);
    }

    #[test]
    fn grouped_edges_change_alike() {
        // a rectangle 2 × 1 of six unit edges, the bottom's first edge 0.1 too long; the
        // bottom's second edge and the right side must keep equal lengths (a seam)
        let pi2 = std::f64::consts::FRAC_PI_2;
        let kappa = [pi2, 0.0, pi2, pi2, 0.0, pi2];
        let t = tangents(&kappa, 0);
        let target = [1.1, 1.0, 1.0, 1.0, 1.0, 1.0];
        let free = close_curve(&target, &target, &t, 0, &[0, 1, 2, 3, 4, 5]);
        assert!((free.lengths[1] - free.lengths[2]).abs() > 1e-3);
        let tied = close_curve(&target, &target, &t, 0, &[0, 1, 2, 3, 4, 1]);
        assert!(tied.residual < 1e-15, "{}", tied.residual);
        assert!((tied.lengths[1] / target[1] - tied.lengths[5] / target[5]).abs() < 1e-15);
    }

    #[test]
    fn a_boundary_pulled_across_the_disk_touches_itself() {
        let mesh = conformap_testkit::flat_disk(3, 6);
        let mut map: Vec<Complex64> = mesh
            .positions()
            .iter()
            .map(|p| Complex64::new(p[0], p[1]))
            .collect();
        assert_eq!(boundary_touches(&mesh, &map), 0);
        let lp = &mesh.boundary_loops()[0];
        // one boundary vertex dragged to the far side: its two edges cross the loop
        let v = lp[0] as usize;
        map[v] = -1.5 * map[v];
        assert!(boundary_touches(&mesh, &map) >= 2);
    }

    #[test]
    fn crossing_segments_are_found() {
        let z = Complex64::new;
        assert!(segments_meet(z(0., 0.), z(1., 1.), z(0., 1.), z(1., 0.)));
        assert!(!segments_meet(z(0., 0.), z(1., 0.), z(0., 1.), z(1., 1.)));
        assert!(segments_meet(z(0., 0.), z(2., 0.), z(1., 0.), z(1., 1.)));
    }
}
