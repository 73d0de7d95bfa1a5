//! Charts cut at a neck where that packs denser. One chart that bounds the common scale by
//! itself (spot's single chart: an L of head and body) leaves most of its bounding square
//! empty however it is turned; cut in two where its outline pinches, the two parts pack
//! side by side. The cut is the shortest interior path between two boundary vertices that
//! are near in the layout but far apart along the outline; the parts keep their layout,
//! so every seam, the new one too, keeps its lengths exactly, and the distortion is that
//! of the chart. A cut is kept only when the packing's common scale grows by at least
//! [`NECK_GAIN`].

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use num_complex::Complex64;
use rayon::prelude::*;

use crate::chart::piece::sub_piece;
use crate::chart::split::{shortest_path, sides, PathGraph};
use crate::chart::Piece;
use crate::component::ComponentChart;
use crate::error::AtlasError;
use crate::hull::min_square_rect;
use crate::pack::{fits_at, pack_outlined, trial_pack, Outlined, PackOptions, Packing};

/// Least relative growth of the packing efficiency for a neck cut to be kept: 3 % (a
/// seam is a cost to whoever paints the texture; a cut that buys less is not worth it).
pub const NECK_GAIN: f64 = 0.03;

/// Charts tried: those holding at least this share of the layout area of all charts: 0.3
/// (a smaller chart does not bound the scale alone).
pub const NECK_MIN_SHARE: f64 = 0.3;

/// Charts tried: those whose smallest square spans at least this share of the texture's
/// side in the packing: 0.75 (a chart that sets the common scale by its own size; one
/// that spans less leaves room the others can take).
pub const NECK_MIN_SPAN: f64 = 0.75;

/// Neck candidates tried per chart: 4 (the narrowest, each at least
/// [`NECK_MIN_ARC`] of the outline away from the others along it).
pub const NECK_CANDIDATES: usize = 4;

/// Both parts of the outline a neck cuts off hold at least this share of it: 0.15 (a
/// narrower lobe is a spike, which the profile packer nests already).
pub const NECK_MIN_ARC: f64 = 0.15;

/// Candidates of the second look at a chart where none of the first [`NECK_CANDIDATES`]
/// pays: 16, both parts of the outline holding at least [`NECK_MORE_MIN_ARC`] of it (the
/// pairs of the first look not tried again), in the first round only and below
/// [`NECK_MORE_BELOW`]. Spot polished (`--polish`): no first candidate pays, the second
/// look's packs 0.62 → 0.67 (BFF: 0.65); david_head 0.59 → 0.68. Taken instead of the
/// first look, it chose a different first cut on alligator whose second round packed 0.45
/// instead of 0.63 (the rounds are greedy).
pub const NECK_MORE_CANDIDATES: usize = 16;

/// A second look is only taken while the charts fill less than this share of the square
/// (their layout area at the packing's scale): 0.65. Measured on the shared meshes: it
/// found no cut on armadillo (0.69), chinese_lion (0.76) or human_face (0.76) for 7–20
/// ms more; it packs david_head 0.59 → 0.68 and spot polished 0.62 → 0.67 (fertility,
/// 0.48, and maze, 0.53, look for 5–8 ms and find nothing).
pub const NECK_MORE_BELOW: f64 = 0.65;

/// The least share of the outline on either side of a second look's neck: 0.1.
pub const NECK_MORE_MIN_ARC: f64 = 0.1;

/// Outline points a neck search looks at, at most: 400 (every k-th boundary vertex beyond
/// that; pairs are quadratic in it).
const NECK_SAMPLES: usize = 400;

/// Rounds of cuts: 2 (a part can be cut again once).
const NECK_ROUNDS: usize = 2;

/// A closed polyline of layout points.
type Outline = Vec<[f64; 2]>;

/// Every piece's layout points and boundary loops, for the packer.
pub(crate) fn outlines(charts: &[ComponentChart]) -> (Vec<Outline>, Vec<Vec<Outline>>) {
    let pieces: Vec<&Piece> = charts.iter().flat_map(|c| &c.pieces).collect();
    // the hull of a piece is that of its outline: its loops' points are all the packer needs
    let loops: Vec<Vec<Vec<[f64; 2]>>> = pieces.iter().map(|p| piece_loops(p)).collect();
    let points = loops.iter().map(|l| l.concat()).collect();
    (points, loops)
}

/// The points of a piece's outline.
fn points_of(p: &Piece) -> Vec<[f64; 2]> {
    piece_loops(p).concat()
}

fn piece_loops(p: &Piece) -> Vec<Vec<[f64; 2]>> {
    p.mesh
        .boundary_loops()
        .iter()
        .map(|l| {
            l.iter()
                .map(|&v| [p.uv[v as usize].re, p.uv[v as usize].im])
                .collect()
        })
        .collect()
}

/// Cuts the charts of `charts` at necks while that grows the packing's efficiency by
/// [`NECK_GAIN`] (see the module); returns the packing of the pieces then.
///
/// # Errors
/// Those of [`pack_outlined`]; [`AtlasError::Mesh`] should a part fail validation (parts
/// of a valid disk are valid).
pub(crate) fn cut_necks(
    charts: &mut [ComponentChart],
    pack: &PackOptions,
) -> Result<Packing, AtlasError> {
    // the charts as they are packed at one texel (the atlas's packing if no cut pays);
    // cuts judged on the profile packer's coarse grid (a scale at most 2 % lower: a cut
    // must pay that too), the pieces packed at one texel again after a cut
    let (points, loops) = outlines(charts);
    let mut packing = pack_outlined(&points, &loops, pack)?;
    let mut cut = false;
    for round in 0..NECK_ROUNDS {
        let total: f64 = charts.iter().flat_map(|c| &c.pieces).map(piece_area).sum();
        // (component, piece) of the charts large enough to bound the scale alone
        let large: Vec<(usize, usize)> = charts
            .iter()
            .enumerate()
            .flat_map(|(c, ch)| (0..ch.pieces.len()).map(move |k| (c, k)))
            .filter(|&(c, k)| piece_area(&charts[c].pieces[k]) >= NECK_MIN_SHARE * total)
            .filter(|&(c, k)| {
                let r = min_square_rect(&points_of(&charts[c].pieces[k]));
                r.size[0].max(r.size[1]) * packing.scale >= NECK_MIN_SPAN
            })
            .collect();
        if large.is_empty() {
            break;
        }
        // every large piece searched side by side (each search reads the charts and the
        // packing as they are), the first one in order that pays is cut: what the pieces
        // searched one after another, stopping at the first that pays, would give
        let (_, loops) = outlines(charts);
        let uncut = Outlined::new(loops, pack);
        let second = round == 0 && total * packing.scale * packing.scale < NECK_MORE_BELOW;
        let found: Vec<Option<(Packing, Vec<usize>)>> = large
            .par_iter()
            .map(|&(c, k)| {
                let slot = index_of(charts, c, k);
                search_piece(&charts[c].pieces[k], slot, &uncut, &packing, second, pack)
            })
            .collect();
        let mut improved = false;
        for (&(c, k), best) in large.iter().zip(found) {
            let piece = &charts[c].pieces[k];
            let Some((trial, path)) = best else {
                continue;
            };
            let Some(groups) = sides(&piece.mesh, &path).filter(|g| g.len() == 2) else {
                continue;
            };
            let parts = groups
                .iter()
                .map(|g| sub_piece(piece, g))
                .collect::<Result<Vec<_>, _>>()?;
            charts[c].pieces.splice(k..=k, parts);
            packing = trial;
            improved = true;
            cut = true;
            // the indices of this component's later pieces moved: next round
            break;
        }
        if !improved {
            break;
        }
    }
    if cut {
        let (points, loops) = outlines(charts);
        packing = pack_outlined(&points, &loops, pack)?;
    }
    Ok(packing)
}

/// The best neck cut of `piece` (at `slot` among `uncut`'s charts, a disk with one
/// boundary loop) by its first [`NECK_CANDIDATES`] candidates, then, when `second`, its
/// [`NECK_MORE_CANDIDATES`] narrower ones: the trial packing and the cut's half-edges;
/// `None` when no candidate beats `packing`'s scale by [`NECK_GAIN`].
fn search_piece(
    piece: &Piece,
    slot: usize,
    uncut: &Outlined,
    packing: &Packing,
    second: bool,
    pack: &PackOptions,
) -> Option<(Packing, Vec<usize>)> {
    let lp = match piece.mesh.boundary_loops() {
        [lp] => lp.clone(),
        _ => return None,
    };
    let at = |v: u32| [piece.uv[v as usize].re, piece.uv[v as usize].im];
    let mut on_loop = vec![false; piece.mesh.num_vertices()];
    lp.iter().for_each(|&v| on_loop[v as usize] = true);
    // each candidate judged by its parts' outlines (the loop's two arcs closed by
    // the path), the parts built for the best one only
    let graph = PathGraph::new(&piece.mesh);
    let first_bar = packing.scale * (1.0 + NECK_GAIN).sqrt();
    // each candidate packed on its own core (they are independent), then taken in
    // order: a trial is kept when it beats the bar and every trial kept before it
    let judge = |pairs: &[(usize, usize)]| {
        let trials: Vec<Option<(Packing, Vec<usize>)>> = pairs
            .par_iter()
            .map(|&(i, j)| {
                let path = shortest_path(&piece.mesh, &graph, lp[i], lp[j])?;
                let inner: Vec<u32> = path[..path.len() - 1]
                    .iter()
                    .map(|&h| piece.mesh.halfedge_vertices(h).1)
                    .collect();
                if inner.iter().any(|&v| on_loop[v as usize]) {
                    return None;
                }
                let m = lp.len();
                let first: Vec<[f64; 2]> = (i..=j)
                    .map(|x| at(lp[x]))
                    .chain(inner.iter().rev().map(|&v| at(v)))
                    .collect();
                let second: Vec<[f64; 2]> = (j..=i + m)
                    .map(|x| at(lp[x % m]))
                    .chain(inner.iter().map(|&v| at(v)))
                    .collect();
                let parts = uncut.split(slot, vec![vec![first], vec![second]], pack);
                // one packing at the bar first: most cuts do not reach it
                let turned = parts.turned(pack);
                if !fits_at(&parts, &turned, first_bar, pack) {
                    return None;
                }
                let trial = trial_pack(&parts, &turned, first_bar, pack)?;
                Some((trial, path))
            })
            .collect();
        let mut best: Option<(Packing, Vec<usize>)> = None;
        for (trial, path) in trials.into_iter().flatten() {
            let bar = best.as_ref().map_or(first_bar, |b| b.0.scale);
            if trial.scale > bar {
                best = Some((trial, path));
            }
        }
        best
    };
    let first = candidates(piece, &lp, NECK_CANDIDATES, NECK_MIN_ARC);
    judge(&first).or_else(|| {
        if !second {
            return None;
        }
        let more: Vec<(usize, usize)> =
            candidates(piece, &lp, NECK_MORE_CANDIDATES, NECK_MORE_MIN_ARC)
                .into_iter()
                .filter(|p| !first.contains(p))
                .collect();
        judge(&more)
    })
}

/// Position of piece `k` of component `c` in the flat list of pieces.
fn index_of(charts: &[ComponentChart], c: usize, k: usize) -> usize {
    charts[..c].iter().map(|ch| ch.pieces.len()).sum::<usize>() + k
}

fn piece_area(p: &Piece) -> f64 {
    p.mesh
        .faces()
        .iter()
        .map(|t| {
            let z = t.map(|v| p.uv[v as usize]);
            let (e1, e2) = (z[1] - z[0], z[2] - z[0]);
            0.5 * (e1.re * e2.im - e1.im * e2.re)
        })
        .sum()
}

/// Pairs of positions `i < j` on the boundary loop `lp` of a disk piece where its outline
/// pinches: near in the layout, both arcs between them at least `min_arc` of the outline
/// ([`NECK_MIN_ARC`] at first), the segment between them inside the chart; narrowest
/// (layout distance over the shorter arc) first, at most `count` ([`NECK_CANDIDATES`] at
/// first), each pair apart from the ones before along the outline (by half `min_arc`).
fn candidates(piece: &Piece, lp: &[u32], count: usize, min_arc: f64) -> Vec<(usize, usize)> {
    let z: Vec<Complex64> = lp.iter().map(|&v| piece.uv[v as usize]).collect();
    let m = z.len();
    let mut arc = vec![0.0; m + 1];
    for i in 0..m {
        arc[i + 1] = arc[i] + (z[(i + 1) % m] - z[i]).norm();
    }
    let perimeter = arc[m];
    if !(perimeter > 0.0) {
        return Vec::new();
    }
    let stride = m.div_ceil(NECK_SAMPLES).max(1);
    let samples: Vec<usize> = (0..m).step_by(stride).collect();
    let mut pairs = Vec::with_capacity(samples.len() * samples.len().saturating_sub(1) / 2);
    for (x, &i) in samples.iter().enumerate() {
        for &j in &samples[x + 1..] {
            let along = arc[j] - arc[i];
            let short = along.min(perimeter - along);
            if short < min_arc * perimeter {
                continue;
            }
            // the squared ratio ranks as the ratio does, without a `hypot` call per pair
            pairs.push(((z[j] - z[i]).norm_sqr() / (short * short), i, j));
        }
    }
    // narrowest first, ties by position (the order a stable sort of the generated pairs
    // gives), popped from a heap: a first look's candidates come from the narrowest few
    // hundred of up to 80,000 pairs, a second look's sixteen from tens of thousands (the
    // narrowest crowd round the candidates taken), and neither sorts all of them
    let apart = |a: usize, b: usize| {
        let d = (arc[a] - arc[b]).abs();
        d.min(perimeter - d) >= 0.5 * min_arc * perimeter
    };
    let mut heap: BinaryHeap<Reverse<Pair>> = pairs.into_iter().map(|p| Reverse(Pair(p))).collect();
    let mut out: Vec<(usize, usize)> = Vec::new();
    while out.len() < count {
        let Some(Reverse(Pair((_, i, j)))) = heap.pop() else {
            break;
        };
        if !out
            .iter()
            .all(|&(p, q)| (apart(i, p) || apart(j, q)) && (apart(i, q) || apart(j, p)))
        {
            continue;
        }
        if inside(&z, 0.5 * (z[i] + z[j])) {
            out.push((i, j));
        }
    }
    out
}

/// A pair of outline positions with its narrowness, ordered narrowest first, then by
/// position.
struct Pair((f64, usize, usize));

impl PartialEq for Pair {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other).is_eq()
    }
}
impl Eq for Pair {}
impl PartialOrd for Pair {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Pair {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        let (a, b) = (self.0, other.0);
        a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2))
    }
}

/// Whether `p` lies inside the closed polygon `z` (winding number, non-zero).
fn inside(z: &[Complex64], p: Complex64) -> bool {
    let Some(&last) = z.last() else {
        return false;
    };
    let mut winding = 0i32;
    // every edge (a, b) of the loop once, the closing one first (the count does not
    // depend on the order)
    let mut a = last;
    for &b in z {
        let cross = (b.re - a.re) * (p.im - a.im) - (p.re - a.re) * (b.im - a.im);
        if a.im <= p.im {
            if b.im > p.im && cross > 0.0 {
                winding += 1;
            }
        } else if b.im <= p.im && cross < 0.0 {
            winding -= 1;
        }
        a = b;
    }
    winding != 0
}
