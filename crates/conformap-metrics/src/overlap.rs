//! Does a planar layout cover any point twice? Two checks that need no solver:
//!
//! - [`raster_overlap`]: the texture a user sees. Every triangle is rasterized at the texel
//!   centres of an `N × N` grid with a top-left fill rule (a texel centre on an edge shared by
//!   two triangles belongs to exactly one of them), and the texels covered twice or more are
//!   counted: the number of the issue tables (`overlap = texels covered twice / texels
//!   covered`, at 1024²).
//! - [`boundary_crossings`]: exact for a flip-free map of a connected surface with boundary.
//!   Such a map is a local homeomorphism, and it is one-to-one exactly when the image of its
//!   boundary has no two edges that cross or touch away from a shared vertex; so a layout with
//!   0 flipped faces and 0 boundary crossings has no overlap at any resolution. Segments are
//!   bucketed in a uniform grid (expected linear time).
//!
//! Both take triangles in the layout's own coordinates; [`raster_overlap`] scales the
//! layout's bounding box into the unit square first unless told the layout is already a
//! texture in `[0,1]²` (an atlas).

use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// The texture resolution of the overlap numbers in reports: 1024 texels a side, as the
/// tables of BFF comparisons use.
pub const OVERLAP_RESOLUTION: usize = 1024;

/// How a layout covers an `N × N` raster.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct RasterOverlap {
    /// Texels a side.
    pub resolution: usize,
    /// Texel centres covered by at least one triangle.
    pub covered: u64,
    /// Texel centres covered by two or more triangles.
    pub covered_twice: u64,
    /// `covered_twice / covered` (0 when nothing is covered).
    pub fraction: f64,
}

/// Where the layout lands on the raster.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum RasterFrame {
    /// The layout is a texture: `[0,1]²` is the raster (points outside are clipped).
    UnitSquare,
    /// The layout's bounding box, scaled uniformly (aspect kept) into `[0,1]²`.
    BoundingBox,
}

/// Counts the texels of an `resolution × resolution` raster covered twice or more by
/// `triangles` (each given by its three corners, either orientation; degenerate ones cover
/// nothing). See the module docs for the fill rule.
///
/// ```
/// use conformap_metrics::{raster_overlap, RasterFrame};
/// // two triangles tiling the unit square: nothing covered twice
/// let tiles = [[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0]]];
/// let o = raster_overlap(tiles.iter().copied(), 64, RasterFrame::UnitSquare);
/// assert_eq!((o.covered, o.covered_twice), (64 * 64, 0));
/// // a third triangle on top of the first: half the square is covered twice
/// let more = tiles.iter().copied().chain([[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]]);
/// let o = raster_overlap(more, 64, RasterFrame::UnitSquare);
/// assert!((o.fraction - 0.5).abs() < 0.02);
/// ```
pub fn raster_overlap(
    triangles: impl Iterator<Item = [[f64; 2]; 3]> + Clone,
    resolution: usize,
    frame: RasterFrame,
) -> RasterOverlap {
    let n = resolution.max(1);
    let (origin, scale) = match frame {
        RasterFrame::UnitSquare => ([0.0, 0.0], n as f64),
        RasterFrame::BoundingBox => {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for t in triangles.clone() {
                for p in t {
                    for k in 0..2 {
                        lo[k] = lo[k].min(p[k]);
                        hi[k] = hi[k].max(p[k]);
                    }
                }
            }
            let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
            if !(side > 0.0 && side.is_finite()) {
                return RasterOverlap {
                    resolution: n,
                    ..RasterOverlap::default()
                };
            }
            (lo, n as f64 / side)
        }
    };
    let raster: Vec<[[f64; 2]; 3]> = triangles
        .map(|t| t.map(|q| [(q[0] - origin[0]) * scale, (q[1] - origin[1]) * scale]))
        .collect();
    // bands of rows rasterized on all cores, each taking the triangles its rows meet
    // (bucketed by their rows first: every triangle looked at by the bands it meets only)
    let rows = n.div_ceil(BANDS).max(1);
    let bands = n.div_ceil(rows);
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (k, t) in raster.iter().enumerate() {
        let lo = t.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min);
        let hi = t.iter().map(|q| q[1]).fold(f64::NEG_INFINITY, f64::max);
        if !(lo.is_finite() && hi.is_finite()) || hi < 0.0 || lo > n as f64 {
            continue;
        }
        // a texel row j is taken only when its centre j + 0.5 lies in [lo, hi]
        let first = (lo.max(0.0) as usize / rows).min(bands - 1);
        let last = (hi.min(n as f64) as usize / rows).min(bands - 1);
        for b in &mut buckets[first..=last] {
            b.push(k as u32);
        }
    }
    // one band's counters per task, cleared and reused for the next band it takes: a
    // 64-row band (64 KB at 1024) stays in cache, and the 1 MB of a whole raster is
    // never touched (its first writes were a page fault every 4 KB)
    let (covered, covered_twice) = buckets
        .par_iter()
        .enumerate()
        .map_init(Vec::new, |counters: &mut Vec<u8>, (b, bucket)| {
            let from = b * rows;
            let to = (from + rows).min(n);
            counters.clear();
            counters.resize((to - from) * n, 0);
            let band = &mut counters[..];
            for &k in bucket {
                rasterize_rows(raster[k as usize], n, from..to, band);
            }
            // one pass, in row-sized sums (u32 counters the compiler vectorizes)
            band.chunks(n.max(1))
                .fold((0u64, 0u64), |(once, twice), row| {
                    let (a, b) = row.iter().fold((0u32, 0u32), |(a, b), &c| {
                        (a + u32::from(c > 0), b + u32::from(c > 1))
                    });
                    (once + u64::from(a), twice + u64::from(b))
                })
        })
        .reduce(|| (0, 0), |a, b| (a.0 + b.0, a.1 + b.1));
    RasterOverlap {
        resolution: n,
        covered,
        covered_twice,
        fraction: if covered > 0 {
            covered_twice as f64 / covered as f64
        } else {
            0.0
        },
    }
}

/// `(b − a) × (p − a)`.
#[inline]
fn edge(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
}

/// Whether a point exactly on the directed edge `a → b` of a counter-clockwise triangle
/// belongs to it: the edges on its top and left (the usual rasterization rule, so two
/// triangles sharing an edge never both take a centre on it).
#[inline]
fn top_left(a: [f64; 2], b: [f64; 2]) -> bool {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    // counter-clockwise with y up: a left edge goes down, a top edge goes left
    dy < 0.0 || (dy == 0.0 && dx < 0.0)
}

/// Row bands the raster is split into for the cores: 16 (1024 texels: 64 rows each; the
/// bands' work evens out across two or more cores, the bucketing costs a pass over the
/// triangles).
const BANDS: usize = 16;

/// Adds one to every texel whose centre lies in triangle `p` (raster coordinates).
#[cfg(test)]
fn rasterize(p: [[f64; 2]; 3], n: usize, count: &mut [u8]) {
    rasterize_rows(p, n, 0..n, count);
}

/// [`rasterize`] restricted to the texel rows `rows`, whose counters are `band` (row
/// `rows.start` first).
fn rasterize_rows(mut p: [[f64; 2]; 3], n: usize, rows: std::ops::Range<usize>, band: &mut [u8]) {
    let area = edge(p[0], p[1], p[2]);
    if !(area.abs() > 0.0) || !area.is_finite() {
        return;
    }
    if area < 0.0 {
        p.swap(1, 2);
    }
    let lo = |k: usize| p.iter().map(|q| q[k]).fold(f64::INFINITY, f64::min);
    let hi = |k: usize| p.iter().map(|q| q[k]).fold(f64::NEG_INFINITY, f64::max);
    // texel i has its centre at i + 0.5
    let first = |x: f64| (ceil(x - 0.5).max(0.0) as usize).min(n);
    let last = |x: f64| ((floor(x - 0.5) + 1.0).max(0.0) as usize).min(n);
    let (i0, i1) = (first(lo(0)), last(hi(0)));
    let (j0, j1) = (first(lo(1)).max(rows.start), last(hi(1)).min(rows.end));
    let rules = [
        top_left(p[0], p[1]),
        top_left(p[1], p[2]),
        top_left(p[2], p[0]),
    ];
    for j in j0..j1 {
        let y = j as f64 + 0.5;
        // the row's span from the edges' crossings of this row, widened by a texel each
        // side against rounding; the exact test below decides every texel in it
        let (mut xl, mut xr) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..3 {
            let (a, b) = (p[k], p[(k + 1) % 3]);
            let dy = b[1] - a[1];
            if dy == 0.0 {
                continue;
            }
            // edge(a, b, (x, y)) = (b−a)ₓ (y − a_y) − dy (x − aₓ) ≥ 0
            let x = a[0] + (b[0] - a[0]) * (y - a[1]) / dy;
            if dy < 0.0 {
                xl = xl.max(x);
            } else {
                xr = xr.min(x);
            }
        }
        let (mut s0, mut s1) = (i0, i1);
        if xl.is_finite() {
            s0 = s0.max(first(xl - 1.0));
        }
        if xr.is_finite() {
            s1 = s1.min(last(xr + 1.0));
        }
        let s1 = s1.max(s0);
        let take = |i: usize| {
            let c = [i as f64 + 0.5, y];
            (0..3).all(|k| {
                let e = edge(p[k], p[(k + 1) % 3], c);
                e > 0.0 || (e == 0.0 && rules[k])
            })
        };
        let r = j - rows.start;
        let row = &mut band[r * n..(r + 1) * n];
        // texels well inside the span are taken without the test when the test is sure to
        // take both ends of their run: each edge function is linear along the row, so its
        // computed value exceeds its rounding bound at every texel between two where it
        // exceeds it twice over
        let (c0, c1) = (
            s0.max(first(xl + INNER_MARGIN)),
            s1.min(last(xr - INNER_MARGIN)),
        );
        let sure = c1 > c0 + 1
            && (0..3).all(|k| {
                let (a, b) = (p[k], p[(k + 1) % 3]);
                let ends = [c0 as f64 + 0.5, (c1 - 1) as f64 + 0.5];
                let reach = ends
                    .map(|x| (x - a[0]).abs())
                    .iter()
                    .fold(0.0f64, |m, &d| m.max(d));
                let bound = 16.0
                    * f64::EPSILON
                    * ((b[0] - a[0]).abs() * (y - a[1]).abs() + (b[1] - a[1]).abs() * reach);
                ends.iter().all(|&x| edge(a, b, [x, y]) > 2.0 * bound)
            });
        let (c0, c1) = if sure { (c0, c1) } else { (s1, s1) };
        for i in (s0..c0).chain(c1..s1) {
            if take(i) {
                row[i] = row[i].saturating_add(1);
            }
        }
        for cell in &mut row[c0..c1] {
            *cell = cell.saturating_add(1);
        }
    }
}

/// `x.floor()` without a call into the math library (the default x86-64 target has no
/// rounding instruction, and the raster takes four per row): truncation, one down for a
/// negative fraction. Equal to `floor` for `|x|` below 2⁶³ (from 2⁵² on every `f64` is an
/// integer, truncated exactly); beyond, the cast saturates and only the clamps to
/// `[0, n]` that follow read it, as they would `floor`'s; NaN gives 0, as
/// `NaN.floor().max(0.0)` does after them.
#[inline]
fn floor(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t > x {
        t - 1.0
    } else {
        t
    }
}

/// `x.ceil()` as [`floor`] does it.
#[inline]
fn ceil(x: f64) -> f64 {
    let t = x as i64 as f64;
    if t < x {
        t + 1.0
    } else {
        t
    }
}

/// Texels within this distance of a row's span ends are always given the full test: 0.01.
const INNER_MARGIN: f64 = 0.01;

/// Pairs of boundary edges of a planar layout that cross or touch anywhere but at a vertex
/// they share, at most `limit` of them (found in a deterministic order, each pair once).
///
/// `loops` are the boundary loops as vertex indices into `map` (each loop closed implicitly:
/// its last vertex joins its first); a pair is reported as the indices of the loops and of
/// the edges' first vertices within them, `((loop_a, k_a), (loop_b, k_b))`. With 0 flipped
/// faces, an empty result proves the layout one-to-one (module docs).
///
/// ```
/// use conformap_metrics::boundary_crossings;
/// use num_complex::Complex64;
/// let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
/// let map: Vec<Complex64> = square.iter().map(|&(x, y)| Complex64::new(x, y)).collect();
/// assert!(boundary_crossings(&map, &[vec![0, 1, 2, 3]], 10).is_empty());
/// // a bow tie: edges 0→1 and 2→3 cross
/// assert_eq!(boundary_crossings(&map, &[vec![0, 1, 3, 2]], 10).len(), 1);
/// ```
pub fn boundary_crossings(
    map: &[Complex64],
    loops: &[Vec<u32>],
    limit: usize,
) -> Vec<((usize, usize), (usize, usize))> {
    let segs: Vec<(usize, usize, u32, u32)> = loops
        .iter()
        .enumerate()
        .flat_map(|(l, lp)| (0..lp.len()).map(move |k| (l, k, lp[k], lp[(k + 1) % lp.len()])))
        .filter(|s| (s.2 as usize) < map.len() && (s.3 as usize) < map.len())
        .collect();
    if segs.len() < 2 {
        return Vec::new();
    }
    let pt = |v: u32| map[v as usize];
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for s in &segs {
        let z = pt(s.2);
        lo = [lo[0].min(z.re), lo[1].min(z.im)];
        hi = [hi[0].max(z.re), hi[1].max(z.im)];
    }
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if !(side > 0.0 && side.is_finite()) {
        return Vec::new();
    }
    // about one segment per cell along the boundary
    let cells = ((segs.len() as f64).sqrt().ceil() as usize).clamp(1, 4096);
    let h = side / cells as f64;
    let cell_of = |x: f64, o: f64| (((x - o) / h).floor().max(0.0) as usize).min(cells - 1);
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); cells * cells];
    for (s, seg) in segs.iter().enumerate() {
        let (a, b) = (pt(seg.2), pt(seg.3));
        let (i0, i1) = minmax(cell_of(a.re, lo[0]), cell_of(b.re, lo[0]));
        let (j0, j1) = minmax(cell_of(a.im, lo[1]), cell_of(b.im, lo[1]));
        for j in j0..=j1 {
            for i in i0..=i1 {
                grid[j * cells + i].push(s as u32);
            }
        }
    }
    let mut found = Vec::new();
    let mut pairs: Vec<(u32, u32)> = Vec::new();
    for bucket in &grid {
        for (x, &s) in bucket.iter().enumerate() {
            for &t in &bucket[x + 1..] {
                let (a, b) = (&segs[s as usize], &segs[t as usize]);
                if segments_meet(pt(a.2), pt(a.3), pt(b.2), pt(b.3), [a.2, a.3], [b.2, b.3]) {
                    pairs.push((s.min(t), s.max(t)));
                }
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    for (s, t) in pairs.into_iter().take(limit) {
        let (a, b) = (&segs[s as usize], &segs[t as usize]);
        found.push(((a.0, a.1), (b.0, b.1)));
    }
    found
}

fn minmax(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// Whether segments `p0 p1` and `q0 q1` (their end vertices' indices `pv`, `qv`) share a
/// point other than a vertex they share by index (consecutive boundary edges meet at their
/// common vertex; that is no crossing, unless the two fold back along one line). Exact
/// orientation tests on the given coordinates; touching counts as meeting.
pub fn segments_meet(
    p0: Complex64,
    p1: Complex64,
    q0: Complex64,
    q1: Complex64,
    pv: [u32; 2],
    qv: [u32; 2],
) -> bool {
    let shared = pv.iter().filter(|v| qv.contains(v)).count();
    let orient = |a: Complex64, b: Complex64, c: Complex64| {
        let v = (b - a).re * (c - a).im - (b - a).im * (c - a).re;
        if v > 0.0 {
            1
        } else if v < 0.0 {
            -1
        } else {
            0
        }
    };
    if shared == 2 {
        // the same edge twice (a loop of two vertices): not a crossing
        return false;
    }
    if shared == 1 {
        // adjacent edges: they meet wrongly only if they overlap along a line (fold back)
        let (common, p_other, q_other) = if pv[0] == qv[0] {
            (p0, p1, q1)
        } else if pv[0] == qv[1] {
            (p0, p1, q0)
        } else if pv[1] == qv[0] {
            (p1, p0, q1)
        } else {
            (p1, p0, q0)
        };
        let (u, w) = (p_other - common, q_other - common);
        let cross = u.re * w.im - u.im * w.re;
        let dot = u.re * w.re + u.im * w.im;
        return cross == 0.0 && dot > 0.0;
    }
    let (o1, o2) = (orient(p0, p1, q0), orient(p0, p1, q1));
    let (o3, o4) = (orient(q0, q1, p0), orient(q0, q1, p1));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    let on = |a: Complex64, b: Complex64, c: Complex64| {
        c.re >= a.re.min(b.re)
            && c.re <= a.re.max(b.re)
            && c.im >= a.im.min(b.im)
            && c.im <= a.im.max(b.im)
    };
    (o1 == 0 && on(p0, p1, q0))
        || (o2 == 0 && on(p0, p1, q1))
        || (o3 == 0 && on(q0, q1, p0))
        || (o4 == 0 && on(q0, q1, p1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every texel of the bounding box tested, as the rasterizer did before it bounded
    /// each row by the edges' crossings.
    fn rasterize_box(mut p: [[f64; 2]; 3], n: usize, count: &mut [u8]) {
        let area = edge(p[0], p[1], p[2]);
        if !(area.abs() > 0.0) || !area.is_finite() {
            return;
        }
        if area < 0.0 {
            p.swap(1, 2);
        }
        let rules = [0, 1, 2].map(|k| top_left(p[k], p[(k + 1) % 3]));
        for j in 0..n {
            for i in 0..n {
                let c = [i as f64 + 0.5, j as f64 + 0.5];
                if (0..3).all(|k| {
                    let e = edge(p[k], p[(k + 1) % 3], c);
                    e > 0.0 || (e == 0.0 && rules[k])
                }) {
                    count[j * n + i] += 1;
                }
            }
        }
    }

    /// Uniform numbers in [0, 1) from a xorshift generator seeded with `seed`.
    fn xorshift(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The raster's own floor and ceiling agree with the math library's on the values
    /// a raster sees, on the halves and integers where they differ most, and on the
    /// extremes after the clamps that follow them.
    #[test]
    fn floor_and_ceil_are_the_math_librarys() {
        let mut xs = vec![
            0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 1023.5, 1024.0, 1e-300, -1e-300,
        ];
        xs.extend((-2000..2000).map(|i| i as f64 * 0.37 + 1e-9 * i as f64));
        xs.extend([4503599627370497.0, -4503599627370497.0, 9.2e18, -9.2e18]);
        for x in xs {
            assert_eq!(floor(x), x.floor(), "{x}");
            assert_eq!(ceil(x), x.ceil(), "{x}");
        }
        let n = 1024usize;
        for x in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN, 1e300, -1e300] {
            let clamp = |y: f64| (y.max(0.0) as usize).min(n);
            assert_eq!(clamp(floor(x)), clamp(x.floor()), "{x}");
            assert_eq!(clamp(ceil(x)), clamp(x.ceil()), "{x}");
        }
    }

    #[test]
    fn row_spans_take_exactly_the_texels_of_the_full_test() {
        // random triangles, slivers, triangles with vertices on texel centres and edges
        // through them (the tie rule), partly outside the raster
        let n = 48;
        let mut rnd = xorshift(0x9e37_79b9_7f4a_7c15);
        let mut differ = 0;
        for t in 0..3000 {
            let mut p = [[0.0; 2]; 3];
            for q in &mut p {
                *q = [rnd() * 60.0 - 6.0, rnd() * 60.0 - 6.0];
                if t % 3 == 0 {
                    *q = q.map(|x| x.round() + 0.5);
                }
            }
            if t % 5 == 0 {
                // a sliver: the third point near the first edge
                let s = rnd();
                p[2] = [
                    p[0][0] + s * (p[1][0] - p[0][0]) + 1e-9,
                    p[0][1] + s * (p[1][1] - p[0][1]),
                ];
            }
            let (mut a, mut b) = (vec![0u8; n * n], vec![0u8; n * n]);
            rasterize(p, n, &mut a);
            rasterize_box(p, n, &mut b);
            differ += usize::from(a != b);
        }
        assert_eq!(differ, 0, "triangles rasterized differently");
    }

    #[test]
    fn bands_count_what_one_pass_over_the_whole_raster_counts() {
        // triangles across band borders, on texel centres, partly outside the square
        let n = 100;
        let mut rnd = xorshift(0x2545_f491_4f6c_dd1d);
        let tris: Vec<[[f64; 2]; 3]> = (0..400)
            .map(|t| {
                let c = [rnd() * 1.2 - 0.1, rnd() * 1.2 - 0.1];
                let s = if t % 7 == 0 { 0.5 } else { 0.08 };
                let mut p = [[0.0; 2]; 3];
                for q in &mut p {
                    *q = [c[0] + s * (rnd() - 0.5), c[1] + s * (rnd() - 0.5)];
                    if t % 3 == 0 {
                        *q = q.map(|x| ((x * n as f64).round() + 0.5) / n as f64);
                    }
                }
                p
            })
            .collect();
        let mut count = vec![0u8; n * n];
        for t in &tris {
            rasterize(t.map(|q| q.map(|x| x * n as f64)), n, &mut count);
        }
        let once = count.iter().filter(|&&c| c > 0).count() as u64;
        let twice = count.iter().filter(|&&c| c > 1).count() as u64;
        assert!(twice > 100 && once > 2000, "{once} {twice}");
        let o = raster_overlap(tris.iter().copied(), n, RasterFrame::UnitSquare);
        assert_eq!((o.covered, o.covered_twice), (once, twice));
    }

    /// A fan of `k` triangles around the origin covering the disk of radius 0.4 at 0.5.
    fn fan(k: usize, turns: usize) -> Vec<[[f64; 2]; 3]> {
        let p = |i: usize| {
            let t = std::f64::consts::TAU * (turns * i) as f64 / k as f64;
            [0.5 + 0.4 * t.cos(), 0.5 + 0.4 * t.sin()]
        };
        (0..k).map(|i| [[0.5, 0.5], p(i), p(i + 1)]).collect()
    }

    #[test]
    fn a_fan_covers_its_disk_once_and_a_double_fan_twice() {
        let once = raster_overlap(fan(37, 1).into_iter(), 256, RasterFrame::UnitSquare);
        assert_eq!(once.covered_twice, 0);
        // the disk of radius 0.4 is about π 0.16 of the square
        let share = once.covered as f64 / (256.0 * 256.0);
        assert!(
            (share - std::f64::consts::PI * 0.16).abs() < 0.01,
            "{share}"
        );
        let twice = raster_overlap(fan(37, 2).into_iter(), 256, RasterFrame::UnitSquare);
        // the chords of the double fan skip a vertex: a thin rim is covered once
        assert!(twice.fraction > 0.97, "{twice:?}");
    }

    #[test]
    fn a_grid_of_right_triangles_has_no_shared_texel() {
        // edges through texel centres: the fill rule must give each centre to one triangle
        let m = 8;
        let mut tris = Vec::new();
        for j in 0..m {
            for i in 0..m {
                let (x0, y0, x1, y1) = (
                    i as f64 / m as f64,
                    j as f64 / m as f64,
                    (i + 1) as f64 / m as f64,
                    (j + 1) as f64 / m as f64,
                );
                tris.push([[x0, y0], [x1, y0], [x1, y1]]);
                tris.push([[x0, y0], [x1, y1], [x0, y1]]);
            }
        }
        // 16 texels per cell side: many centres lie on the diagonals; none twice, all once
        let o = raster_overlap(tris.iter().copied(), 128, RasterFrame::UnitSquare);
        assert_eq!((o.covered, o.covered_twice), (128 * 128, 0));
        // half-texel offsets put centres exactly on every edge
        let shifted: Vec<_> = tris
            .iter()
            .map(|t| t.map(|p| [p[0] * 0.75 + 0.5 / 128.0, p[1] * 0.75 + 0.5 / 128.0]))
            .collect();
        let o = raster_overlap(shifted.iter().copied(), 128, RasterFrame::UnitSquare);
        assert_eq!(o.covered_twice, 0);
        assert_eq!(o.covered, 96 * 96);
    }

    #[test]
    fn bounding_box_frame_and_degenerate_input() {
        let tris = [[[10.0, 10.0], [30.0, 10.0], [30.0, 20.0]]];
        let o = raster_overlap(tris.iter().copied(), 100, RasterFrame::BoundingBox);
        // half of the top half of the square (the box is 20 × 10)
        assert!((o.covered as f64 / 2500.0 - 1.0).abs() < 0.03, "{o:?}");
        let flat = [[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]];
        let o = raster_overlap(flat.iter().copied(), 16, RasterFrame::BoundingBox);
        assert_eq!(o.covered, 0);
    }

    #[test]
    fn crossings_of_a_folded_boundary() {
        // a star polygon {5/2}: every edge crosses two others
        let map: Vec<Complex64> = (0..5)
            .map(|k| Complex64::from_polar(1.0, std::f64::consts::TAU * (2 * k) as f64 / 5.0))
            .collect();
        let star = vec![0u32, 1, 2, 3, 4];
        assert_eq!(boundary_crossings(&map, &[star], 100).len(), 5);
        // two nested squares, then the inner moved across the outer's edge
        let mut pts: Vec<Complex64> = [(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0)]
            .iter()
            .chain(&[(1.0, 1.0), (1.0, 2.0), (2.0, 2.0), (2.0, 1.0)])
            .map(|&(x, y)| Complex64::new(x, y))
            .collect();
        let loops = vec![vec![0, 1, 2, 3], vec![4, 5, 6, 7]];
        assert!(boundary_crossings(&pts, &loops, 10).is_empty());
        pts[6] = Complex64::new(5.0, 2.0);
        let c = boundary_crossings(&pts, &loops, 10);
        assert_eq!(c.len(), 2, "{c:?}");
        assert!(c.iter().all(|&((la, _), (lb, _))| la == 0 && lb == 1));
        // an edge folded back onto its neighbour (a spike) touches it along a line
        let spike: Vec<Complex64> = [(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (0.0, 1.0)]
            .iter()
            .map(|&(x, y)| Complex64::new(x, y))
            .collect();
        assert!(!boundary_crossings(&spike, &[vec![0, 1, 2, 3]], 10).is_empty());
    }
}
