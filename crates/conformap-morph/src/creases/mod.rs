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
//!   loop (the same share of arc length between the same two anchors: the points
//!   nearest to the landmarks near the loops, [`CREASE_ANCHOR_REACH`], or a ray towards
//!   the nearest landmark), exactly on one of its edges.
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

/// Which arc length the rim vertices share between anchors ([`rim_targets`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum ArcLength {
    /// Along the rim on each surface, in 3D.
    Surface,
    /// Along the rim in the disk (S1's, and the key's registered disk).
    Disk,
}

/// Cumulative arc length in the disk at every vertex of the closed loop `lp` from
/// `lp[0]`, and the whole length as a last entry (`n + 1` values).
fn disk_arc_lengths(lp: &[u32], disk: &[Complex64]) -> Vec<f64> {
    let n = lp.len();
    let mut s = vec![0.0; n + 1];
    for i in 0..n {
        s[i + 1] = s[i] + (disk[lp[i] as usize] - disk[lp[(i + 1) % n] as usize]).norm();
    }
    s
}

/// Cumulative arc length (in 3D, on the surface `positions`) at every vertex of the
/// closed loop `lp` from `lp[0]`, and the whole length as a last entry (`n + 1` values).
fn arc_lengths(lp: &[u32], positions: &[[f64; 3]]) -> Vec<f64> {
    let n = lp.len();
    let mut s = vec![0.0; n + 1];
    for i in 0..n {
        let (a, b) = (
            positions[lp[i] as usize],
            positions[lp[(i + 1) % n] as usize],
        );
        s[i + 1] =
            s[i] + ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
    }
    s
}

/// A point of a loop that corresponds to a point of the other loop of a matched pair:
/// arc length from the loop's first vertex (in the disk) on each.
#[derive(Debug, Clone, Copy, PartialEq)]
struct AnchorPair {
    /// Arc length on S1's loop.
    on_from: f64,
    /// Arc length on the key surface's loop.
    on_onto: f64,
    /// The anchor on S1's loop, in S1's disk.
    at_from: Complex64,
    /// The key loop's vertex nearest to the anchor on it.
    onto_vertex: u32,
}

/// How a matched pair of loops was anchored (see [`rim_targets`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Anchoring {
    /// At the points nearest to this many landmarks near the loops.
    Landmarks(usize),
    /// At the loops' crossings with the ray from S1's loop's centre towards the landmark
    /// nearest to it (no landmark on both loops).
    Ray,
    /// At the loops' two vertices farthest apart in 3D ([`RimCut::Corners`]).
    Corners,
}

/// Where the matched loops are cut into the pieces whose arc length is shared
/// ([`rim_targets`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum RimCut {
    /// At the anchors the landmarks near the loops give (or a ray towards the nearest
    /// landmark): what a round rim needs, the first choice.
    Landmarks,
    /// At each loop's two vertices farthest apart in 3D (the corners of a slit), S1's
    /// corners paired with the key's by the smaller sum of distances in the disk. A
    /// round rim has no such pair (the pairing can turn it by a quarter), but where the
    /// landmarks lie off a slit's corners (wry's raised mouth corner) the corners are
    /// the better anchors: the carrying tries them where the landmark cut leaves flipped
    /// faces and keeps the cut that flips fewer.
    Corners,
}

/// The positions in `lp` of its two vertices farthest apart in 3D, the first one first.
fn farthest_pair(lp: &[u32], positions: &[[f64; 3]]) -> (usize, usize) {
    let d2 = |a: [f64; 3], b: [f64; 3]| {
        (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
    };
    let mut best = (0, 0, -1.0);
    for i in 0..lp.len() {
        for j in i + 1..lp.len() {
            let d = d2(positions[lp[i] as usize], positions[lp[j] as usize]);
            if d > best.2 {
                best = (i, j, d);
            }
        }
    }
    (best.0, best.1)
}

/// The anchors of [`RimCut::Corners`] for the counter-clockwise loops `a` (of `from`, arc
/// lengths `la`) and `b` (of `onto`, `lb`): each loop's two vertices farthest apart in
/// 3D, paired by the smaller sum of distances in the disk, in order along `a`.
fn corner_anchors(
    a: &[u32],
    from: &LoopOn<'_>,
    la: &[f64],
    b: &[u32],
    onto: &LoopOn<'_>,
    lb: &[f64],
) -> Vec<AnchorPair> {
    let (a0, a1) = farthest_pair(a, from.positions);
    let (b0, b1) = farthest_pair(b, onto.positions);
    let near = |i: usize, j: usize| (from.disk[a[i] as usize] - onto.disk[b[j] as usize]).norm();
    let pairs = if near(a0, b0) + near(a1, b1) <= near(a0, b1) + near(a1, b0) {
        [(a0, b0), (a1, b1)]
    } else {
        [(a0, b1), (a1, b0)]
    };
    // a0 < a1: the pairs are in order along `a`; two anchors are always in the same
    // cyclic order on both loops
    pairs
        .iter()
        .map(|&(i, j)| AnchorPair {
            on_from: la[i],
            on_onto: lb[j],
            at_from: from.disk[a[i] as usize],
            onto_vertex: b[j],
        })
        .collect()
}

/// The first crossing of the ray `o + t u` (`t > 0`) with the closed polygon `poly`:
/// segment and fraction along it.
fn ray_crossing(poly: &[Complex64], o: Complex64, u: Complex64) -> Option<(usize, f64)> {
    let n = poly.len();
    let cross = |a: Complex64, b: Complex64| a.re * b.im - a.im * b.re;
    let mut best: Option<(f64, usize, f64)> = None;
    for j in 0..n {
        let (p, q) = (poly[j], poly[(j + 1) % n]);
        let e = q - p;
        let den = cross(u, e);
        if den == 0.0 {
            continue;
        }
        // o + t u = p + s e
        let t = cross(p - o, e) / den;
        let s = cross(p - o, u) / den;
        if t > 0.0 && (0.0..=1.0).contains(&s) && best.is_none_or(|b| t < b.0) {
            best = Some((t, j, s));
        }
    }
    best.map(|(_, j, s)| (j, s))
}

/// A landmark anchors a loop when it lies within this fraction of the loop's diameter
/// (in S1's disk) of it: `0.4`. On the neutral shared face, in its disk: the outer eye
/// corners lie on the eye rims (0.03 of the rim's diameter), the inner ones 0.17 off,
/// the mouth corners 0.31 off the mouth rim (a ring of faces in 3D, but the disk map
/// widens the slit's ends), the upper lip 0.47 and the chin 0.94 off it, every other
/// landmark more than 1.5 diameters off a rim.
pub const CREASE_ANCHOR_REACH: f64 = 0.4;

/// The anchors of the counter-clockwise loops `a` (of `from`, arc lengths `la`) and `b`
/// (of `onto`, `lb`), in order along `a`, at least one:
///
/// - every landmark within [`CREASE_ANCHOR_REACH`] of `a` (in S1's disk): the points of
///   `a` and `b` nearest to it (S1's landmark, and the key's, which the registration has
///   put at the same place), as long as they come in the same cyclic order on both loops
///   (an anchor out of order with those kept before it is dropped): the mouth and eye
///   corners of the shared faces lie on or a ring of faces off their holes' rims;
/// - without such a landmark, the first crossings of both loops with the ray from the
///   mean of `a`'s vertices (in the disk) towards S1's landmark nearest to that point;
///   should the ray miss a loop (a loop not star-shaped from that point), the loops'
///   points nearest to that landmark.
///
/// Unlike the loops' two vertices farthest apart (the corners of a slit), which a round
/// rim does not have, these anchors depend only on the landmarks and the registration.
fn anchors(
    a: &[u32],
    from: &LoopOn<'_>,
    la: &[f64],
    b: &[u32],
    onto: &LoopOn<'_>,
    lb: &[f64],
) -> (Vec<AnchorPair>, Anchoring) {
    let (na, nb) = (a.len(), b.len());
    let za: Vec<Complex64> = a.iter().map(|&v| from.disk[v as usize]).collect();
    let zb: Vec<Complex64> = b.iter().map(|&v| onto.disk[v as usize]).collect();
    let diameter = za
        .iter()
        .flat_map(|&p| za.iter().map(move |&q| (p - q).norm()))
        .fold(0.0, f64::max);
    // distance to the polygon, arc length and disk point of the polygon's point nearest
    // to `z`
    let along = |poly: &[Complex64], lengths: &[f64], z: Complex64| {
        let (d, j, s) = nearest_on_polygon(z, poly);
        let m = poly.len();
        let point = poly[j] + (poly[(j + 1) % m] - poly[j]) * s;
        (d, lengths[j] + s * (lengths[j + 1] - lengths[j]), point)
    };
    let nearest_vertex = |z: Complex64| {
        b[(0..nb)
            .min_by(|&i, &j| (zb[i] - z).norm().total_cmp(&(zb[j] - z).norm()))
            .unwrap_or(0)]
    };
    // the landmarks near the loop (S1's, the key's)
    let near: Vec<(u32, u32)> = from
        .landmarks
        .iter()
        .zip(onto.landmarks)
        .filter(|(&l1, _)| {
            along(&za, la, from.disk[l1 as usize]).0 < CREASE_ANCHOR_REACH * diameter
        })
        .map(|(&l1, &lk)| (l1, lk))
        .collect();
    let mut found: Vec<AnchorPair> = near
        .iter()
        .map(|&(l1, lk)| {
            let (_, on_from, at_from) = along(&za, la, from.disk[l1 as usize]);
            let (_, on_onto, at_onto) = along(&zb, lb, onto.disk[lk as usize]);
            AnchorPair {
                on_from,
                on_onto,
                at_from,
                onto_vertex: nearest_vertex(at_onto),
            }
        })
        .collect();
    found.sort_by(|p, q| p.on_from.total_cmp(&q.on_from));
    if let Some(&first) = found.first() {
        // keep the anchors whose places on b, counted from the first one's, increase,
        // as do their places on a
        let after = |p: &AnchorPair| (p.on_onto - first.on_onto).rem_euclid(lb[nb]);
        let mut kept = vec![first];
        for p in &found[1..] {
            let last = kept[kept.len() - 1];
            if p.on_from > last.on_from && after(p) > after(&last) {
                kept.push(*p);
            }
        }
        let n = kept.len();
        return (kept, Anchoring::Landmarks(n));
    }
    let o = za.iter().sum::<Complex64>() / na as f64;
    let towards = from
        .landmarks
        .iter()
        .map(|&l| from.disk[l as usize])
        .min_by(|p, q| (p - o).norm().total_cmp(&(q - o).norm()))
        .unwrap_or(o + 1.0);
    let at = |poly: &[Complex64], lengths: &[f64]| match ray_crossing(poly, o, towards - o) {
        Some((j, s)) => {
            let m = poly.len();
            let point = poly[j] + (poly[(j + 1) % m] - poly[j]) * s;
            (lengths[j] + s * (lengths[j + 1] - lengths[j]), point)
        }
        None => {
            let (_, arc, point) = along(poly, lengths, towards);
            (arc, point)
        }
    };
    let ((on_from, at_from), (on_onto, at_onto)) = (at(&za, la), at(&zb, lb));
    let anchor = AnchorPair {
        on_from,
        on_onto,
        at_from,
        onto_vertex: nearest_vertex(at_onto),
    };
    (vec![anchor], Anchoring::Ray)
}

/// The anchors of matched loops, as [`rim_targets`] cuts them: the anchor on S1's loop
/// (a point of S1's disk) and the key loop's vertex nearest to the matching anchor.
pub(crate) fn anchor_points(
    from: &LoopOn<'_>,
    onto: &LoopOn<'_>,
    cut: RimCut,
) -> Vec<(Complex64, u32)> {
    let a = ccw(from.vertices, from.disk);
    let b = ccw(onto.vertices, onto.disk);
    let (la, lb) = (
        arc_lengths(&a, from.positions),
        arc_lengths(&b, onto.positions),
    );
    cut_anchors(&a, from, &la, &b, onto, &lb, cut)
        .0
        .into_iter()
        .map(|p| (p.at_from, p.onto_vertex))
        .collect()
}

/// The anchors of `cut`: [`anchors`] or [`corner_anchors`].
fn cut_anchors(
    a: &[u32],
    from: &LoopOn<'_>,
    la: &[f64],
    b: &[u32],
    onto: &LoopOn<'_>,
    lb: &[f64],
    cut: RimCut,
) -> (Vec<AnchorPair>, Anchoring) {
    match cut {
        RimCut::Landmarks => anchors(a, from, la, b, onto, lb),
        RimCut::Corners => (corner_anchors(a, from, la, b, onto, lb), Anchoring::Corners),
    }
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
/// onto it) and landmarks.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LoopOn<'a> {
    /// The loop's vertices, in order.
    pub vertices: &'a [u32],
    /// The surface's disk map (in S1's disk).
    pub disk: &'a [Complex64],
    /// The surface's landmark vertices (S1's and the key's in the same order).
    pub landmarks: &'a [u32],
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
/// the disk, and how they were anchored: the loops are cut at their anchors (`cut`:
/// [`RimCut::Landmarks`], the points nearest to the landmarks near the loops, else the
/// crossings of a ray from the loop's centre towards the nearest landmark; or
/// [`RimCut::Corners`], the loops' two vertices farthest apart), and every vertex of S1's loop goes
/// to the same share of arc length (`arc`) between the same two anchors on the key loop
/// (with one anchor: the same share of the whole loop from it). Order along the loop is
/// kept and no two vertices meet. `edge_face` gives, for a key-surface edge `(min, max)`,
/// a face holding it.
///
/// 3D arc length ([`ArcLength::Surface`], first choice) is each surface's own length
/// along the rim (a lip stretched evenly keeps its points at the same shares). Shares of
/// arc length in the disk crowd S1's rim vertices towards the round mouth's sides (the
/// disk map widens the ends of S1's slit): 0.24 of the opening off the exact
/// correspondence against 0.06; but on wry's raised mouth corner they fold fewer faces
/// of S1's moved disk, so the carrying takes them where they fold fewer.
/// The loops were earlier cut at their two vertices farthest apart in 3D, paired by
/// distance in the disk: the corners of a slit, which a round rim (a mouth pursed into
/// an "O") does not have; there the pairing turned S1's mouth by a quarter turn.
pub(crate) fn rim_targets(
    from: &LoopOn<'_>,
    onto: &LoopOn<'_>,
    facesk: &[[u32; 3]],
    edge_face: &HashMap<(u32, u32), u32>,
    arc: ArcLength,
    cut: RimCut,
) -> (Vec<RimTarget>, Anchoring) {
    let (disk1, diskk) = (from.disk, onto.disk);
    let a = ccw(from.vertices, disk1);
    let b = ccw(onto.vertices, diskk);
    let (la, ub) = match arc {
        ArcLength::Surface => (
            arc_lengths(&a, from.positions),
            arc_lengths(&b, onto.positions),
        ),
        ArcLength::Disk => (disk_arc_lengths(&a, disk1), disk_arc_lengths(&b, diskk)),
    };
    let (na, m) = (a.len(), b.len());
    let (whole_a, whole_b) = (la[na], ub[m]);
    let (anchor, how) = cut_anchors(&a, from, &la, &b, onto, &ub, cut);
    let n_anchors = anchor.len();
    // the span from anchor `p` to the next one `q` (the whole loop with one anchor)
    let span = |from_s: f64, to_s: f64, whole: f64| {
        let d = (to_s - from_s).rem_euclid(whole);
        if n_anchors == 1 || d <= 0.0 {
            whole
        } else {
            d
        }
    };
    let targets = a
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            // the anchors before and after vertex i along the loop
            let next = anchor.partition_point(|p| p.on_from <= la[i]);
            let (p, q) = (
                anchor[(next + n_anchors - 1) % n_anchors],
                anchor[next % n_anchors],
            );
            let share =
                (la[i] - p.on_from).rem_euclid(whole_a) / span(p.on_from, q.on_from, whole_a);
            let t = (p.on_onto + share * span(p.on_onto, q.on_onto, whole_b)).rem_euclid(whole_b);
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
        .collect();
    (targets, how)
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

    /// A closed polygon loop `0..n` in the plane with its disk coordinates, and a fan
    /// around its centre (vertex `n`) as the faces holding its edges.
    fn ring(pts: &[(f64, f64)]) -> (Vec<Complex64>, Vec<[u32; 3]>) {
        let n = pts.len() as u32;
        let mut z: Vec<Complex64> = pts.iter().map(|&(x, y)| Complex64::new(x, y)).collect();
        z.push(z.iter().sum::<Complex64>() / n as f64);
        let faces = (0..n).map(|k| [k, (k + 1) % n, n]).collect();
        (z, faces)
    }

    /// The plane points `z` as 3D positions (the loops' surfaces are their disks).
    fn lifted(z: &[Complex64]) -> Vec<[f64; 3]> {
        z.iter().map(|p| [p.re, p.im, 0.0]).collect()
    }

    /// The targets of `from`'s loop on `onto`'s (fan faces `faces`), by S1 vertex.
    fn targets_of(
        from: &LoopOn<'_>,
        onto: &LoopOn<'_>,
        faces: &[[u32; 3]],
    ) -> (HashMap<u32, Complex64>, Anchoring) {
        let (t, how) = rim_targets(
            from,
            onto,
            faces,
            &edge_faces(faces),
            ArcLength::Surface,
            RimCut::Landmarks,
        );
        (t.into_iter().map(|t| (t.vertex, t.disk)).collect(), how)
    }

    /// Two slits (hexagons long in x), the second shifted and listed from its other end,
    /// with landmarks at both ends: each end goes onto the same landmark's end (not the
    /// end nearer to it in the numbering), and the vertices between to the same share of
    /// arc length.
    #[test]
    fn landmarks_on_both_loops_anchor_them() {
        let slit = [
            (-3.0, 0.0),
            (-1.0, -0.5),
            (1.0, -0.5),
            (3.0, 0.0),
            (1.0, 0.5),
            (-1.0, 0.5),
        ];
        let (d1, _) = ring(&slit);
        let mut shifted: Vec<(f64, f64)> = slit.iter().map(|&(x, y)| (x + 0.2, y)).collect();
        shifted.rotate_left(3);
        let (d2, f2) = ring(&shifted);
        let (p1, p2) = (lifted(&d1), lifted(&d2));
        let lp: Vec<u32> = (0..6).collect();
        // landmarks: S1's left end (0) is the second's vertex 3, its right end (3) is 0
        let from = LoopOn {
            vertices: &lp,
            disk: &d1,
            landmarks: &[0, 3],
            positions: &p1,
        };
        let onto = LoopOn {
            vertices: &lp,
            disk: &d2,
            landmarks: &[3, 0],
            positions: &p2,
        };
        let (t, how) = targets_of(&from, &onto, &f2);
        assert_eq!(how, Anchoring::Landmarks(2));
        // every vertex goes to its own copy shifted by 0.2 (the sides have equal lengths)
        for (v, z) in &t {
            let expect = d1[*v as usize] + 0.2;
            assert!((z - expect).norm() < 1e-12, "{v}: {z} vs {expect}");
        }
        // a landmark pair out of order with the others is dropped: one anchor is kept
        let onto_crossed = LoopOn {
            landmarks: &[3, 0, 1, 4],
            ..onto
        };
        let from_crossed = LoopOn {
            landmarks: &[0, 3, 1, 4],
            ..from
        };
        let (_, how) = targets_of(&from_crossed, &onto_crossed, &f2);
        assert!(matches!(how, Anchoring::Landmarks(n) if n < 4), "{how:?}");
    }

    /// A round loop of 12 vertices onto a round loop of 17 (another radius, numbered from
    /// another angle), no landmark on them: the ray from the centre towards the landmark
    /// above anchors both at their tops, and every S1 vertex goes to its own angle on the
    /// other circle. (The two vertices farthest apart of a regular 12-gon are any of 6
    /// opposite pairs: the earlier corner pairing could turn the loop by 30–90°.)
    #[test]
    fn round_loops_without_landmarks_are_anchored_by_a_ray() {
        use std::f64::consts::TAU;
        let circle = |n: usize, r: f64, phase: f64| -> Vec<(f64, f64)> {
            (0..n)
                .map(|k| {
                    let t = phase + TAU * k as f64 / n as f64;
                    (r * t.cos(), r * t.sin())
                })
                .collect()
        };
        let (mut d1, _) = ring(&circle(12, 1.0, 0.0));
        let (mut d2, f2) = ring(&circle(17, 1.1, 2.0));
        // the landmark (vertex 13 / 18, the fan centres are 12 / 17) straight above
        d1.push(Complex64::new(0.0, 3.0));
        d2.push(Complex64::new(0.0, 3.0));
        let (p1, p2) = (lifted(&d1), lifted(&d2));
        let (l1, l2): (Vec<u32>, Vec<u32>) = ((0..12).collect(), (0..17).collect());
        let from = LoopOn {
            vertices: &l1,
            disk: &d1,
            landmarks: &[13],
            positions: &p1,
        };
        let onto = LoopOn {
            vertices: &l2,
            disk: &d2,
            landmarks: &[18],
            positions: &p2,
        };
        let (t, how) = targets_of(&from, &onto, &f2);
        assert_eq!(how, Anchoring::Ray);
        assert_eq!(t.len(), 12);
        for (v, z) in &t {
            let want = d1[*v as usize].arg();
            let turn = (z.arg() - want + 0.5 * TAU).rem_euclid(TAU) - 0.5 * TAU;
            // the polygons' arc length differs from the angle by under a few degrees
            assert!(turn.abs() < 0.05, "{v}: turned {turn:.3} rad");
            assert!((z.norm() - 1.1).abs() < 0.03, "{v}: {z}");
        }
        // S1's top vertex (3, at 90°) goes exactly to the other polygon's top (on a chord)
        assert!(t[&3].re.abs() < 1e-12 && t[&3].im > 1.08, "{}", t[&3]);
    }

    #[test]
    fn arc_lengths_of_a_quadrilateral() {
        let z = [(0.0, 0.0), (3.0, 0.0), (3.0, 1.0), (0.0, 1.2)].map(|(x, y)| Complex64::new(x, y));
        let s = arc_lengths(&[0, 1, 2, 3], &lifted(&z));
        assert_eq!(s[..3], [0.0, 3.0, 4.0]);
        assert!((s[4] - (5.2 + 3.0f64.hypot(0.2))).abs() < 1e-12, "{s:?}");
        // a ray from inside crosses the square once, a ray from outside maybe not
        let c = ray_crossing(&z, Complex64::new(1.5, 0.5), Complex64::new(0.0, 1.0));
        assert!(c.is_some_and(|(j, _)| j == 2), "{c:?}");
        assert!(ray_crossing(&z, Complex64::new(5.0, 0.5), Complex64::new(1.0, 0.0)).is_none());
    }
}
