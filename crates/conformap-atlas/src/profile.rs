//! A profile packer: each chart (turned a quarter at a time) described per texel column by
//! the lowest and highest point of its outline there, dropped from above onto the packed
//! charts' upper profile at the column where it comes to rest lowest. Unlike a rectangle,
//! a chart's real outline nests into the dents of the charts below it: the spikes and
//! bays of a cut surface's layout interlock instead of each claiming its bounding box.

use crate::hull::rotate;

/// One chart turned one way: its outline loops rotated (layout units, not yet scaled).
#[derive(Debug, Clone)]
pub(crate) struct Turned {
    /// Rotation from the layout, radians counter-clockwise.
    pub angle: f64,
    /// The outline's points after the rotation, loop after loop.
    points: Vec<[f64; 2]>,
    /// Where each loop ends in `points` (each loop closed: its last point joins its first).
    loop_ends: Vec<usize>,
    /// Lowest x after the rotation.
    min_x: f64,
    /// Width after the rotation.
    width: f64,
    /// Lowest and highest y after the rotation.
    min_y: f64,
    max_y: f64,
}

impl Turned {
    /// `loops` (closed polylines of layout points) turned by `angle`.
    pub fn new(loops: &[Vec<[f64; 2]>], angle: f64) -> Self {
        let mut points = Vec::with_capacity(loops.iter().map(Vec::len).sum());
        let mut loop_ends = Vec::with_capacity(loops.len());
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut min_y, mut max_y) = (f64::INFINITY, f64::NEG_INFINITY);
        for lp in loops.iter().filter(|lp| !lp.is_empty()) {
            for &p in lp {
                let a = rotate(p, angle);
                points.push(a);
                lo = lo.min(a[0]);
                hi = hi.max(a[0]);
                min_y = min_y.min(a[1]);
                max_y = max_y.max(a[1]);
            }
            loop_ends.push(points.len());
        }
        if !min_y.is_finite() {
            (min_y, max_y) = (0.0, 0.0);
        }
        if !lo.is_finite() {
            (lo, hi) = (0.0, 0.0);
        }
        Self {
            angle,
            points,
            loop_ends,
            min_x: lo,
            width: hi - lo,
            min_y,
            max_y,
        }
    }
}

/// A chart's profile at one scale: per column of its (margin-dilated) footprint, the
/// lowest and highest y, in texels relative to the rotated chart's own origin.
struct Profile {
    lo: Vec<f64>,
    hi: Vec<f64>,
    /// Texels from the footprint's left column to the rotated chart's x = min_x.
    left: f64,
}

impl Profile {
    /// The profile of `t` at `scale` texels per layout unit with `half` texels of margin
    /// on every side (the footprint is the chart grown by a square of that half-side, which
    /// holds the disk of that radius).
    fn new(t: &Turned, scale: f64, half: f64) -> Self {
        let w = t.width * scale;
        let columns = (w + 2.0 * half).ceil().max(1.0) as usize;
        // the chart's own extremes per unit column of x − min_x + half
        let mut lo = vec![f64::INFINITY; columns];
        let mut hi = vec![f64::NEG_INFINITY; columns];
        // x ≥ 0 (every point lies right of min_x), so a cast takes the floor
        let x_of = |p: [f64; 2]| (p[0] - t.min_x) * scale + half;
        let col = |x: f64| (x as usize).min(columns - 1);
        // plain comparisons, not `f64::min`/`max`: the points are finite (the packer
        // refuses others), and the NaN handling of those was most of the packer's time
        let mut put = |k: usize, y: f64| {
            if y < lo[k] {
                lo[k] = y;
            }
            if y > hi[k] {
                hi[k] = y;
            }
        };
        let mut from = 0;
        for &to in &t.loop_ends {
            let pts = &t.points[from..to];
            from = to;
            // a segment's extremes over a column are at its ends there: its own ends (each
            // point put once, for both segments it ends) and its crossings of the columns'
            // sides
            let Some(&last) = pts.last() else { continue };
            let (mut xa, mut ya) = (x_of(last), last[1] * scale);
            for &b in pts {
                let (xb, yb) = (x_of(b), b[1] * scale);
                put(col(xb), yb);
                let (x0, y0, x1, y1) = if xa <= xb {
                    (xa, ya, xb, yb)
                } else {
                    (xb, yb, xa, ya)
                };
                let (f0, f1) = (x0 as i64, x1 as i64);
                if f1 > f0 {
                    let slope = (y1 - y0) / (x1 - x0);
                    for side in (f0 + 1)..=f1 {
                        let y = y0 + slope * (side as f64 - x0);
                        let k = side.clamp(1, columns as i64 - 1) as usize;
                        put(k - 1, y);
                        put(k, y);
                    }
                }
                (xa, ya) = (xb, yb);
            }
        }
        // grown by the margin: column c holds every chart point within `half` of it
        let reach = half.ceil() as usize;
        let mut glo = vec![f64::INFINITY; columns];
        let mut ghi = vec![f64::NEG_INFINITY; columns];
        for c in 0..columns {
            let from = c.saturating_sub(reach);
            let to = (c + reach).min(columns - 1);
            for k in from..=to {
                if lo[k] < glo[c] {
                    glo[c] = lo[k];
                }
                if hi[k] > ghi[c] {
                    ghi[c] = hi[k];
                }
            }
            glo[c] -= half;
            ghi[c] += half;
        }
        Self {
            lo: glo,
            hi: ghi,
            left: half,
        }
    }
}

/// Relative slack of the orientation pruning in [`pack`]: 1e-9 (rounding of the bound's
/// terms is 1e-16 relative; an orientation within the slack is profiled as before).
const PRUNE_SLACK: f64 = 1e-9;

/// Where a chart went: texture texel = `scale · rotate(p, angle) + offset`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Place {
    /// The orientation chosen (index into the chart's `Turned` list).
    pub turn: usize,
    /// Offset in texels.
    pub offset: [f64; 2],
}

/// `max(start, max_c sky[c] − lo[c])`: where a profile comes to rest on the skyline `sky`
/// (its columns under the chart), or any value of at least `limit` once the rest height
/// reaches it (the position is then no better than the best so far). Columns are taken
/// [`REST_BLOCK`] at a time in four lanes the compiler vectorizes, the limit checked
/// after each block: the maximum is exact, so the result below the limit is the one a
/// column-by-column scan gives.
fn rest_height(sky: &[f64], lo: &[f64], start: f64, limit: f64) -> f64 {
    // `if a > b` rather than `f64::max`: no NaN reaches here (the skyline is finite, a
    // profile's empty column is +∞), and the plain comparison vectorizes
    let max = |a: f64, b: f64| if a > b { a } else { b };
    let mut y = start;
    for (s, l) in sky.chunks(REST_BLOCK).zip(lo.chunks(REST_BLOCK)) {
        let mut lanes = [y; 4];
        let (s4, l4) = (s.chunks_exact(4), l.chunks_exact(4));
        let (sr, lr) = (s4.remainder(), l4.remainder());
        for (a, b) in s4.zip(l4) {
            for k in 0..4 {
                lanes[k] = max(lanes[k], a[k] - b[k]);
            }
        }
        for (a, b) in sr.iter().zip(lr) {
            lanes[0] = max(lanes[0], a - b);
        }
        y = max(max(lanes[0], lanes[1]), max(lanes[2], lanes[3]));
        if y >= limit {
            break;
        }
    }
    y
}

/// Columns of a profile compared with the skyline between two checks of the bound in
/// [`rest_height`]: 32.
const REST_BLOCK: usize = 32;

/// Packs `charts` (each given in its candidate orientations) in `order` into a square of
/// `n` texels at `scale` texels per layout unit with `margin` texels between charts (half
/// of it at the square's edges): each chart at the column and orientation where its top
/// ends lowest (ties: the first orientation, then leftmost). Columns are `cell` texels
/// wide (1: exact to a texel; coarser is conservative, every chart's extremes taken over
/// the whole column, and `cell²` times faster). `None` when a chart does not fit below the
/// square's top; else the places and the height used, in texels. With `fixed`, chart `k`
/// is tried in orientation `fixed[k]` only.
pub(crate) fn pack(
    charts: &[Vec<Turned>],
    order: &[usize],
    scale: f64,
    n: usize,
    margin: f64,
    cell: f64,
    fixed: Option<&[usize]>,
) -> Option<(Vec<Place>, f64)> {
    // in units of columns
    let half = 0.5 * margin / cell;
    let scale = scale / cell;
    let top = n as f64 / cell;
    let n = (n as f64 / cell).floor() as usize;
    let mut sky = vec![0.0f64; n];
    let mut out = vec![
        Place {
            turn: 0,
            offset: [0.0; 2]
        };
        charts.len()
    ];
    for &k in order {
        // (top, rest height of the chart's origin, column, orientation, profile)
        let mut best: Option<(f64, f64, usize, usize, Profile)> = None;
        let sky_min = sky.iter().copied().fold(f64::INFINITY, f64::min);
        for (turn, t) in charts[k].iter().enumerate() {
            if fixed.is_some_and(|f| f[k] != turn) {
                continue;
            }
            // a chart comes to rest no lower than the lowest point of the skyline: an
            // orientation whose top would end above the best so far even there is not
            // profiled (the slack keeps rounding from ever skipping one that could win)
            let height = (t.max_y * scale + half) - (t.min_y * scale - half);
            let bound = best.as_ref().map_or(top, |b| b.0);
            if sky_min + height > bound + PRUNE_SLACK * bound.abs().max(1.0) {
                continue;
            }
            let p = Profile::new(t, scale, half);
            let w = p.lo.len();
            if w > n {
                continue;
            }
            let max_hi = p.hi.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let min_lo = p.lo.iter().copied().fold(f64::INFINITY, f64::min);
            // the chart's top must end below the square's and below the best so far
            let mut bound = best.as_ref().map_or(top, |b| b.0);
            let mut found: Option<(f64, usize)> = None;
            // the column where the chart reaches lowest touches the others first: looked
            // at first, it lets the bound cut a column's scan short sooner
            let low =
                p.lo.iter()
                    .enumerate()
                    .fold(0, |b, (c, &l)| if l < p.lo[b] { c } else { b });
            for x in 0..=n - w {
                let y = (sky[x + low] - p.lo[low]).max(-min_lo);
                if y + max_hi >= bound {
                    continue;
                }
                let y = rest_height(&sky[x..x + w], &p.lo, y, bound - max_hi);
                if y + max_hi < bound {
                    bound = y + max_hi;
                    found = Some((y, x));
                }
            }
            if let Some((y, x)) = found {
                best = Some((y + max_hi, y, x, turn, p));
            }
        }
        let (_, y, x, turn, p) = best?;
        for c in 0..p.lo.len() {
            let t = y + p.hi[c];
            if t.is_finite() {
                sky[x + c] = sky[x + c].max(t);
            }
        }
        let t = &charts[k][turn];
        out[k] = Place {
            turn,
            offset: [x as f64 + p.left - t.min_x * scale, y],
        };
    }
    let height = sky.iter().copied().fold(0.0, f64::max);
    for p in &mut out {
        p.offset = [p.offset[0] * cell, p.offset[1] * cell];
    }
    Some((out, height * cell))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blocked, laned maximum is the column-by-column one below the limit, and at
    /// least the limit when the column scan reaches it.
    #[test]
    fn rest_height_is_the_columns_maximum() {
        // a deterministic jumble of skylines and profiles, lengths across the block size
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % 10_000) as f64 / 100.0
        };
        for w in [1, 3, 4, 31, 32, 33, 100, 257] {
            let sky: Vec<f64> = (0..w).map(|_| next()).collect();
            let mut lo: Vec<f64> = (0..w).map(|_| next() - 50.0).collect();
            lo[w / 2] = f64::INFINITY; // a column the chart leaves empty
            let scan = sky.iter().zip(&lo).fold(-1e9f64, |y, (s, l)| y.max(s - l));
            assert_eq!(rest_height(&sky, &lo, -1e9, f64::INFINITY), scan, "w = {w}");
            let limit = scan - 1.0;
            assert!(rest_height(&sky, &lo, -1e9, limit) >= limit, "w = {w}");
            assert_eq!(
                rest_height(&sky, &lo, scan + 5.0, f64::INFINITY),
                scan + 5.0
            );
        }
    }
}
