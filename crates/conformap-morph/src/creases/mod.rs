//! Closed crease loops and their correspondence between surfaces.
//!
//! A closed loop of sharp edges (two faces whose normals turn by more than
//! [`crate::quality::CREASE_ANGLE_DEG`]) is a feature a morph must carry onto the same feature: on the
//! shared faces the three loops are the rims of the zipped eye and mouth hole fills, where
//! the skin, rolled into the eye socket or the mouth (normals facing backwards), meets
//! the fill spanning the opening (normals facing forwards) at 127–178°. Landmarks pin a
//! few points near the rims, not the rims themselves; a rim of S1 that lands a fraction
//! of a fill's width beside the key surface's rim puts S1's long, thin fill triangles
//! across the key surface's crease, and they flip.
//!
//! - [`crease_loops`]: the loops of one mesh.
//! - `match_loops`: which loop of a key surface is which loop of S1, in S1's disk.
//! - `rim_targets`: where every vertex of a matched S1 loop goes on the key surface's
//!   loop (corner to corner, the same share of arc length along each side), exactly on
//!   one of its edges.
//! - [`RimExtension`]: the harmonic extension of those moves to S1's other vertices.
//! - `untangle`: where that extension folds S1's disk (a rim sliding far through small
//!   faces), the free vertices of the folded faces move into the kernel of their ring
//!   polygon, as little as possible ([`UNTANGLE_MAX_ROUNDS`], [`UNTANGLE_MARGIN`]).

mod extend;
pub(crate) mod untangle;

pub use extend::RimExtension;
pub use untangle::{UNTANGLE_MARGIN, UNTANGLE_MAX_ROUNDS};

use std::collections::HashMap;

use num_complex::Complex64;

use conformap_operators::planar::polygon_area;

use crate::Location;

/// A key surface's loop matches an S1 loop only when the mean distance (in S1's disk)
/// from the S1 loop's vertices to it is below this fraction of the S1 loop's diameter in
/// the disk: `0.5` (a rim that far off is another feature; on the shared faces the
/// matched rims lie 0.01–0.1 of their diameter apart after the registration).
pub const CREASE_LOOP_MATCH_REL: f64 = 0.5;

/// The closed loops of crease edges of a mesh: interior edges whose two faces' normals
/// turn by more than `angle_deg` degrees (e.g. [`crate::quality::CREASE_ANGLE_DEG`]), grouped into
/// connected components; a component in which every vertex has exactly two crease edges
/// is a loop (open crease lines and junctions are not). Each loop is listed from its
/// smallest vertex, loops by their smallest vertex (deterministic).
///
/// # Examples
/// ```
/// use conformap_morph::creases::crease_loops;
/// // two coplanar triangles: their shared edge does not turn
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
/// let f = [[0, 1, 2], [1, 3, 2]];
/// assert!(crease_loops(&p, &f, 90.0).is_empty());
/// ```
pub fn crease_loops(positions: &[[f64; 3]], faces: &[[u32; 3]], angle_deg: f64) -> Vec<Vec<u32>> {
    let mut adjacent: HashMap<u32, Vec<u32>> = HashMap::new();
    for (a, b) in crate::quality::crease_edges(positions, faces, angle_deg) {
        adjacent.entry(a).or_default().push(b);
        adjacent.entry(b).or_default().push(a);
    }
    let mut starts: Vec<u32> = adjacent.keys().copied().collect();
    starts.sort_unstable();
    let mut seen: HashMap<u32, bool> = HashMap::new();
    let mut loops = Vec::new();
    for s in starts {
        if seen.contains_key(&s) {
            continue;
        }
        // the component of s, in traversal order when it is a cycle
        let mut component = vec![s];
        let mut stack = vec![s];
        seen.insert(s, true);
        while let Some(v) = stack.pop() {
            for &w in &adjacent[&v] {
                if seen.insert(w, true).is_none() {
                    component.push(w);
                    stack.push(w);
                }
            }
        }
        if component.len() < 3 || component.iter().any(|v| adjacent[v].len() != 2) {
            continue;
        }
        let mut cycle = vec![s];
        let (mut prev, mut cur) = (s, adjacent[&s][0].min(adjacent[&s][1]));
        while cur != s {
            cycle.push(cur);
            let nb = &adjacent[&cur];
            let next = if nb[0] == prev { nb[1] } else { nb[0] };
            (prev, cur) = (cur, next);
        }
        if cycle.len() == component.len() {
            loops.push(cycle);
        }
    }
    loops
}

/// Nearest point of segment `a b` to `p`: distance and fraction along the segment.
fn nearest_on_segment(p: Complex64, a: Complex64, b: Complex64) -> (f64, f64) {
    let e = b - a;
    let len2 = e.norm_sqr();
    let s = if len2 > 0.0 {
        (((p - a).conj() * e).re / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a + e * s - p).norm(), s)
}

/// Nearest point of the closed polygon `poly` to `p`: distance, segment, fraction.
fn nearest_on_polygon(p: Complex64, poly: &[Complex64]) -> (f64, usize, f64) {
    let n = poly.len();
    (0..n)
        .map(|j| {
            let (d, s) = nearest_on_segment(p, poly[j], poly[(j + 1) % n]);
            (d, j, s)
        })
        .fold(
            (f64::INFINITY, 0, 0.0),
            |a, b| if b.0 < a.0 { b } else { a },
        )
}

/// A loop oriented counter-clockwise in the disk coordinates `disk`.
fn ccw(lp: &[u32], disk: &[Complex64]) -> Vec<u32> {
    let z: Vec<Complex64> = lp.iter().map(|&v| disk[v as usize]).collect();
    let mut out = lp.to_vec();
    if polygon_area(&z) < 0.0 {
        out[1..].reverse();
    }
    out
}

/// Cumulative arc length (in the disk) at every vertex of the closed loop `lp` from
/// `lp[0]`, and the whole length as a last entry (`n + 1` values).
fn arc_lengths(lp: &[u32], disk: &[Complex64]) -> Vec<f64> {
    let n = lp.len();
    let mut s = vec![0.0; n + 1];
    for i in 0..n {
        s[i + 1] = s[i] + (disk[lp[i] as usize] - disk[lp[(i + 1) % n] as usize]).norm();
    }
    s
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The positions in `lp` of its two vertices farthest apart in 3D (the corners of a slit:
/// the mouth and eye corners of the shared faces, the ends of their hole fills' zips),
/// the first one first.
fn corners(lp: &[u32], positions: &[[f64; 3]]) -> (usize, usize) {
    let mut best = (0, 0, -1.0);
    for i in 0..lp.len() {
        for j in i + 1..lp.len() {
            let d = distance(positions[lp[i] as usize], positions[lp[j] as usize]);
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    (best.0, best.1)
}

/// The corners of the counter-clockwise loops `a` (of `from`) and `b` (of `onto`),
/// paired: `[(a0, b0), (a1, b1)]`, positions in `a` and `b`, `a0` S1's first corner
/// ([`corners`]), each S1 corner with the key corner nearer to it in the disk (the
/// pairing with the smaller sum of distances).
fn paired_corners(
    a: &[u32],
    from: &LoopOn<'_>,
    b: &[u32],
    onto: &LoopOn<'_>,
) -> [(usize, usize); 2] {
    let (a0, a1) = corners(a, from.positions);
    let (b0, b1) = corners(b, onto.positions);
    let near = |i: usize, j: usize| (from.disk[a[i] as usize] - onto.disk[b[j] as usize]).norm();
    if near(a0, b0) + near(a1, b1) <= near(a0, b1) + near(a1, b0) {
        [(a0, b0), (a1, b1)]
    } else {
        [(a0, b1), (a1, b0)]
    }
}

/// The corners of matched loops as vertex pairs `(S1 vertex, key vertex)`, as
/// [`rim_targets`] pairs them: the ends of the slits (mouth and eye corners on the
/// shared faces).
pub(crate) fn corner_vertices(from: &LoopOn<'_>, onto: &LoopOn<'_>) -> [(u32, u32); 2] {
    let a = ccw(from.vertices, from.disk);
    let b = ccw(onto.vertices, onto.disk);
    paired_corners(&a, from, &b, onto).map(|(i, j)| (a[i], b[j]))
}

/// `lp` rotated to start at position `k`.
fn rotated(lp: &[u32], k: usize) -> Vec<u32> {
    lp[k..].iter().chain(&lp[..k]).copied().collect()
}

/// The loops of S1 and of a key surface matched in S1's disk: pairs `(i, j)` of S1 loop
/// `i` and key loop `j`, each the other's nearest (mean distance from the S1 loop's
/// vertices to the key loop's polygon) and nearer than [`CREASE_LOOP_MATCH_REL`] of the
/// S1 loop's diameter. `disk1`: S1's disk map; `diskk`: the key surface's registered
/// disk (in S1's disk).
pub(crate) fn match_loops(
    loops1: &[Vec<u32>],
    disk1: &[Complex64],
    loopsk: &[Vec<u32>],
    diskk: &[Complex64],
) -> Vec<(usize, usize)> {
    let polys: Vec<Vec<Complex64>> = loopsk
        .iter()
        .map(|lp| lp.iter().map(|&v| diskk[v as usize]).collect())
        .collect();
    let dist: Vec<Vec<f64>> = loops1
        .iter()
        .map(|lp| {
            polys
                .iter()
                .map(|poly| {
                    lp.iter()
                        .map(|&v| nearest_on_polygon(disk1[v as usize], poly).0)
                        .sum::<f64>()
                        / lp.len() as f64
                })
                .collect()
        })
        .collect();
    let argmin = |row: &mut dyn Iterator<Item = (usize, f64)>| {
        row.fold(
            (usize::MAX, f64::INFINITY),
            |a, b| if b.1 < a.1 { b } else { a },
        )
    };
    let mut out = Vec::new();
    for (i, lp) in loops1.iter().enumerate() {
        let (j, d) = argmin(&mut dist[i].iter().copied().enumerate());
        if j == usize::MAX {
            continue;
        }
        let (back, _) = argmin(&mut dist.iter().map(|r| r[j]).enumerate());
        let diameter = lp
            .iter()
            .flat_map(|&a| {
                lp.iter()
                    .map(move |&b| (disk1[a as usize] - disk1[b as usize]).norm())
            })
            .fold(0.0, f64::max);
        if back == i && d < CREASE_LOOP_MATCH_REL * diameter {
            out.push((i, j));
        }
    }
    out
}

/// At most this many rounds (`8`: a move cut down to 1/256 at most) of halving the moves
/// of the loop vertices near faces of S1's moved disk that would fold; if faces still
/// fold then, no loop is moved and the report says so.
pub const RIM_MOVE_HALVINGS: usize = 8;

/// A round of [`RIM_MOVE_HALVINGS`] halves the moves of the loop vertices within this
/// distance (in the unit disk) of a face that would fold: `0.05`, about twice the largest
/// loop move on the shared faces (0.028), so that the vertices driving a fold are among
/// them, and a small part of a loop's length (the mouth loop spans about 0.3).
pub const RIM_HALVING_RADIUS: f64 = 0.05;

/// A loop of a surface with that surface's disk (S1's, or a key surface's registered
/// onto it) and 3D positions.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LoopOn<'a> {
    /// The loop's vertices, in order.
    pub vertices: &'a [u32],
    /// The surface's disk map (in S1's disk).
    pub disk: &'a [Complex64],
    /// The surface's vertex positions.
    pub positions: &'a [[f64; 3]],
}

/// Where one S1 loop vertex goes on the key surface's loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RimTarget {
    /// The S1 vertex.
    pub vertex: u32,
    /// Its place in the key surface's registered disk.
    pub disk: Complex64,
    /// Its place on the key surface (a face holding the key loop's edge).
    pub location: Location,
}

/// The targets of S1 loop `from` on key loop `onto`, both oriented counter-clockwise in
/// the disk: each loop is split at its corners (its two vertices farthest apart in 3D),
/// each corner of S1's goes to the key loop's corner nearer to it in the disk, and the
/// vertices between go to the same share of arc length along the matching side, arc
/// length measured in the disk (the spacing the disk maps give, so the moves vary slowly
/// along the loop: on the shared faces, shares of 3D arc length would fold 34 faces of
/// S1's moved disk on wry, shares in the disk 12). Order along the loop is kept and no
/// two vertices meet. `edge_face` gives, for a
/// key-surface edge `(min, max)`, a face holding it.
pub(crate) fn rim_targets(
    from: &LoopOn<'_>,
    onto: &LoopOn<'_>,
    facesk: &[[u32; 3]],
    edge_face: &HashMap<(u32, u32), u32>,
) -> Vec<RimTarget> {
    let (disk1, diskk) = (from.disk, onto.disk);
    let a = ccw(from.vertices, disk1);
    let b = ccw(onto.vertices, diskk);
    let [(a0, b_start), (a1, b_other)] = paired_corners(&a, from, &b, onto);
    let a = rotated(&a, a0);
    let b = rotated(&b, b_start);
    let a_mid = (a1 + a.len() - a0) % a.len();
    let b_mid = (b_other + b.len() - b_start) % b.len();
    let (la, ub) = (arc_lengths(&a, disk1), arc_lengths(&b, diskk));
    let (na, m) = (a.len(), b.len());
    a.iter()
        .enumerate()
        .map(|(i, &v)| {
            // the same share of the matching side, in the key loop's arc length
            let t = if i <= a_mid {
                (la[i] / la[a_mid]) * ub[b_mid]
            } else {
                ub[b_mid] + (la[i] - la[a_mid]) / (la[na] - la[a_mid]) * (ub[m] - ub[b_mid])
            };
            // the key segment j with ub[j] <= t < ub[j + 1]
            let j = ub[..m].partition_point(|&u| u <= t).saturating_sub(1);
            let f = ((t - ub[j]) / (ub[j + 1] - ub[j])).clamp(0.0, 1.0);
            let (p, q) = (b[j], b[(j + 1) % m]);
            let face = edge_face[&(p.min(q), p.max(q))];
            let tri = facesk[face as usize];
            let mut bary = [0.0; 3];
            for (c, &w) in tri.iter().enumerate() {
                if w == p {
                    bary[c] = 1.0 - f;
                } else if w == q {
                    bary[c] = f;
                }
            }
            RimTarget {
                vertex: v,
                disk: diskk[p as usize] * (1.0 - f) + diskk[q as usize] * f,
                location: Location {
                    face,
                    bary,
                    outside: 0.0,
                },
            }
        })
        .collect()
}

/// For every edge `(min, max)` of `faces`, the first face holding it.
pub(crate) fn edge_faces(faces: &[[u32; 3]]) -> HashMap<(u32, u32), u32> {
    let mut out = HashMap::new();
    for (k, t) in faces.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            out.entry((a.min(b), a.max(b))).or_insert(k as u32);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quality::CREASE_ANGLE_DEG;

    /// A flat annulus whose inner edge rolls under (a lip) to a wider ring below, capped
    /// by a flat fan: the lip edge and the rim of the cap are sharp (about 117°).
    #[test]
    fn a_rolled_lip_and_its_cap_give_two_loops() {
        let n = 12;
        let ring = |r: f64, z: f64| -> Vec<[f64; 3]> {
            (0..n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    [r * t.cos(), r * t.sin(), z]
                })
                .collect()
        };
        let mut p = ring(3.0, 0.0);
        p.extend(ring(1.0, 0.0));
        p.extend(ring(1.5, -1.0));
        p.push([0.0, 0.0, -1.0]);
        let n = n as u32;
        let mut f = Vec::new();
        for (o, i) in [(0, n), (n, 2 * n)] {
            for k in 0..n {
                let k1 = (k + 1) % n;
                f.push([o + k, o + k1, i + k1]);
                f.push([o + k, i + k1, i + k]);
            }
        }
        for k in 0..n {
            f.push([2 * n + k, 2 * n + (k + 1) % n, 3 * n]);
        }
        let loops = crease_loops(&p, &f, CREASE_ANGLE_DEG);
        assert_eq!(loops.len(), 2, "{loops:?}");
        for (lp, first) in loops.iter().zip([n, 2 * n]) {
            let mut sorted = lp.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (first..first + n).collect::<Vec<u32>>());
            // consecutive vertices of a loop are neighbours on the ring
            for w in lp.windows(2) {
                let d = (w[0] as i64 - w[1] as i64).rem_euclid(n as i64);
                assert!(d == 1 || d == n as i64 - 1, "{lp:?}");
            }
        }
        // with a sharper threshold the 117° edges are not creases
        assert!(crease_loops(&p, &f, 130.0).is_empty());
    }

    /// Two slits (hexagons long in x) in the plane, the second shifted and turned by 180°
    /// in its numbering: each corner of the first pairs with the corner of the second
    /// that lies near it, whatever the order in which the loops list them.
    #[test]
    fn corners_pair_with_the_nearer_corner() {
        let slit = |dx: f64| -> Vec<[f64; 3]> {
            [
                (-3.0, 0.0),
                (-1.0, -0.5),
                (1.0, -0.5),
                (3.0, 0.0),
                (1.0, 0.5),
                (-1.0, 0.5),
            ]
            .iter()
            .map(|&(x, y)| [x + dx, y, 0.0])
            .collect()
        };
        let p1 = slit(0.0);
        // the second slit's vertices listed from its right corner
        let mut p2 = slit(0.2);
        p2.rotate_left(3);
        let disk = |p: &[[f64; 3]]| -> Vec<Complex64> {
            p.iter().map(|q| Complex64::new(q[0], q[1])).collect()
        };
        let (d1, d2) = (disk(&p1), disk(&p2));
        let lp: Vec<u32> = (0..6).collect();
        let from = LoopOn {
            vertices: &lp,
            disk: &d1,
            positions: &p1,
        };
        let onto = LoopOn {
            vertices: &lp,
            disk: &d2,
            positions: &p2,
        };
        // S1's left corner 0 goes to the second's left corner, vertex 3 there
        let mut pairs = corner_vertices(&from, &onto);
        pairs.sort_unstable();
        assert_eq!(pairs, [(0, 3), (3, 0)]);
    }

    #[test]
    fn arc_lengths_and_corners_of_a_quadrilateral() {
        let p = [
            [0.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
            [0.0, 1.2, 0.0],
        ];
        let z: Vec<Complex64> = p.iter().map(|q| Complex64::new(q[0], q[1])).collect();
        let s = arc_lengths(&[0, 1, 2, 3], &z);
        assert_eq!(s[..3], [0.0, 3.0, 4.0]);
        assert!((s[4] - (5.2 + 3.0f64.hypot(0.2))).abs() < 1e-12, "{s:?}");
        // the farthest pair is 1 and 3 (3² + 1.2²)
        assert_eq!(corners(&[0, 1, 2, 3], &p), (1, 3));
        assert_eq!(rotated(&[5, 6, 7, 8], 1), vec![6, 7, 8, 5]);
    }
}
