//! Packing charts into the texture square: one scale for all (one texel density), each chart
//! turned to its smallest bounding rectangle, a margin in texels around each, the largest
//! scale at which a skyline packer fits them all.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::AtlasError;
use crate::hull::{min_area_rect, min_square_rect, quarter_rect, rotate, BoundingRect};
use crate::skyline;

/// How charts are packed. `Default` is [`PackOptions::DEFAULT`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct PackOptions {
    /// Texels a side of the texture the margin is measured in. Default: 1024 (the
    /// resolution overlap is judged at).
    pub resolution: usize,
    /// Empty texels between two charts (half of it between a chart and the square's edge,
    /// so a wrapping sampler sees the full margin too). Default: 2, enough for bilinear
    /// filtering without bleeding at the default resolution.
    pub margin_texels: f64,
    /// Whether a chart may also be turned a quarter from its smallest rectangle when that
    /// packs lower. Default: true.
    pub turn: bool,
    /// Whether charts may only be turned by quarter turns of their own axes (a seamless
    /// atlas: the rotation across a seam between two charts changes by the difference of
    /// their turns). Default: false (each chart turned to its smallest rectangle).
    pub quarter_turns_only: bool,
    /// Steps of the bisection for the common scale. Default: 40 (the scale to 1e-12 of its
    /// upper bound; each step packs once, microseconds for hundreds of charts).
    pub scale_steps: usize,
}

impl PackOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        resolution: 1024,
        margin_texels: 2.0,
        turn: true,
        quarter_turns_only: false,
        scale_steps: 40,
    };

    /// With another resolution.
    pub fn with_resolution(mut self, resolution: usize) -> Self {
        self.resolution = resolution;
        self
    }

    /// With another margin.
    pub fn with_margin_texels(mut self, margin: f64) -> Self {
        self.margin_texels = margin;
        self
    }

    /// With or without quarter turns.
    pub fn with_turn(mut self, turn: bool) -> Self {
        self.turn = turn;
        self
    }

    /// With charts turned by quarter turns only ([`Self::quarter_turns_only`]).
    pub fn with_quarter_turns_only(mut self, only: bool) -> Self {
        self.quarter_turns_only = only;
        self
    }

    /// The smallest-area and smallest-square rectangles of `charts` (both the charts'
    /// own axes, turned a quarter at most, with [`Self::quarter_turns_only`]).
    fn rects(&self, charts: &[Vec<[f64; 2]>]) -> (Vec<BoundingRect>, Vec<BoundingRect>) {
        if self.quarter_turns_only {
            let r: Vec<BoundingRect> = charts.iter().map(|c| quarter_rect(c)).collect();
            return (r.clone(), r);
        }
        (
            charts.iter().map(|c| min_area_rect(c)).collect(),
            charts.iter().map(|c| min_square_rect(c)).collect(),
        )
    }
}

impl Default for PackOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Where one chart goes: texture point = `scale · rotate(p, angle) + offset`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct ChartPlacement {
    /// Rotation, radians counter-clockwise.
    pub angle: f64,
    /// Texture units per layout unit (the same for every chart, unless the atlas scales
    /// each component on its own: [`crate::ChartScale::PerChart`]).
    pub scale: f64,
    /// Translation after rotation and scaling.
    pub offset: [f64; 2],
}

impl ChartPlacement {
    /// The texture coordinates of layout point `p`.
    #[inline]
    pub fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        let q = rotate(p, self.angle);
        [
            self.scale * q[0] + self.offset[0],
            self.scale * q[1] + self.offset[1],
        ]
    }
}

/// Charts placed in `[0,1]²`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Packing {
    /// One placement per chart, in the order given.
    pub charts: Vec<ChartPlacement>,
    /// The common scale: texture units per layout unit.
    pub scale: f64,
    /// Share of the square covered by the charts' convex hulls (an upper bound of the
    /// share their triangles cover; see [`Packing::efficiency_of`]).
    pub efficiency: f64,
    /// Height of the square used, in texture units (≤ 1).
    pub used_height: f64,
}

impl Packing {
    /// The share of the square covered by charts of layout areas `areas` (one per chart):
    /// `Σ area · scale²`, the packing efficiency of an atlas.
    pub fn efficiency_of(&self, areas: &[f64]) -> f64 {
        areas.iter().sum::<f64>() * self.scale * self.scale
    }
}

/// Packs `charts` (each the layout points of one chart: its vertices, or just its outline)
/// into the unit square with one common scale, the largest the packer reaches.
///
/// # Errors
/// [`AtlasError::NonFinite`] for a NaN or infinite point, [`AtlasError::InvalidOption`] for
/// a resolution of 0 or a negative margin, [`AtlasError::TooManyCharts`] when the margins
/// alone overflow the square.
pub fn pack_charts(charts: &[Vec<[f64; 2]>], options: &PackOptions) -> Result<Packing, AtlasError> {
    let hulls: Vec<Vec<Vec<[f64; 2]>>> = charts
        .iter()
        .map(|c| vec![crate::hull::convex_hull(c)])
        .collect();
    pack_outlined(charts, &hulls, options)
}

/// [`pack_charts`] with each chart's outline: its boundary loops (closed polylines of
/// layout points; every point of the chart lies inside its outer loop). The charts are
/// packed both as rectangles and by their outlines (a profile packer: each chart dropped
/// onto the others at the column where it rests lowest, its bays taking the spikes of
/// the charts below), and the larger common scale is kept.
///
/// # Errors
/// As [`pack_charts`]; [`AtlasError::InvalidOption`] when `outlines` does not hold one
/// entry per chart.
pub fn pack_outlined(
    charts: &[Vec<[f64; 2]>],
    outlines: &[Vec<Vec<[f64; 2]>>],
    options: &PackOptions,
) -> Result<Packing, AtlasError> {
    check(charts, options)?;
    if outlines.len() != charts.len() {
        return Err(AtlasError::InvalidOption {
            name: "outlines",
            value: outlines.len().to_string(),
            why: "one outline per chart",
        });
    }
    let too_many = AtlasError::TooManyCharts {
        charts: charts.len(),
        margin: options.margin_texels,
        resolution: options.resolution,
    };
    // three ways to turn the charts (smallest area, smallest square, mixed) and four orders
    // for the skyline: the largest common scale of the twelve is kept
    let (area_rects, square_rects) = options.rects(charts);
    // mixed: the charts that could fill a quarter of the square alone turned to their
    // smallest square, the others to their smallest area
    let total: f64 = area_rects.iter().map(|r| r.size[0] * r.size[1]).sum();
    let mixed: Vec<BoundingRect> = area_rects
        .iter()
        .zip(&square_rects)
        .map(|(a, q)| {
            if a.size[0] * a.size[1] > 0.25 * total {
                *q
            } else {
                *a
            }
        })
        .collect();
    // the twelve searches on all cores, the best taken in their order (the first of equals)
    let combos: Vec<(&[BoundingRect], SortKey)> = [&area_rects[..], &square_rects[..], &mixed[..]]
        .into_iter()
        .flat_map(|rects| ORDERS.map(|key| (rects, key)))
        .collect();
    let searched: Vec<Option<RectLayout>> = combos
        .par_iter()
        .map(|&(rects, key)| {
            let order = order_by(rects, key);
            largest_scale(rects, &order, options).map(|layout| (layout, order, rects))
        })
        .collect();
    let mut best: Option<RectLayout> = None;
    for found in searched.into_iter().flatten() {
        if best.as_ref().is_none_or(|b| found.0 .0 > b.0 .0) {
            best = Some(found);
        }
    }
    let ((s, spots, height), order, rects) = best.ok_or(too_many)?;
    let by_rects = placements(charts, rects, &order, &spots, s, height, options);
    Ok(
        match by_outlines(
            outlines,
            &area_rects,
            &square_rects,
            s,
            options,
            true,
            PROFILE_STEPS,
        ) {
            Some(p) if p.scale > by_rects.scale => Packing {
                efficiency: by_rects.efficiency * (p.scale / by_rects.scale).powi(2),
                ..p
            },
            _ => by_rects,
        },
    )
}

/// Bisection steps of the profile packer's common scale on its coarse grid, between the
/// rectangle packer's scale and the area bound, in its first order: 10 (the scale to 2⁻¹⁰
/// of that interval, a tenth of a percent or so); the second order gets half as many,
/// above the first's scale.
pub const PROFILE_STEPS: usize = 10;

/// Texels per column of the profile packer's coarse grid: 4 (at 1024 texels, 256 columns:
/// each step of the bisection 16 times faster than at one texel, a chart's outline
/// rounded out by at most 4 texels).
pub const PROFILE_CELL: f64 = 4.0;

/// Steps of the bisection at one texel per column above the coarse grid's scale, up to
/// [`PROFILE_REFINE`] higher: 4 (an eighth of a percent).
pub const PROFILE_REFINE_STEPS: usize = 4;

/// How far above the coarse grid's scale the one-texel grid is searched: 2 % (the
/// coarse grid's rounding, 4 texels on charts of a few hundred).
pub const PROFILE_REFINE: f64 = 0.02;

/// Each chart's outline in the orientations the profile packer tries: four quarter turns
/// of its smallest-area rectangle (one when `turn` is off), and as many of its smallest
/// square for a chart that could fill a quarter of the square alone (the rule of the
/// rectangle packer's mixed turns: a small chart's square turn seldom packs better, and
/// every orientation costs a profile per packing).
fn turned_charts(
    outlines: &[Vec<Vec<[f64; 2]>>],
    area_rects: &[BoundingRect],
    square_rects: &[BoundingRect],
    options: &PackOptions,
) -> Vec<Vec<crate::profile::Turned>> {
    let quarter = std::f64::consts::FRAC_PI_2;
    let turns: &[f64] = if options.turn {
        &[0.0, quarter, 2.0 * quarter, 3.0 * quarter]
    } else {
        &[0.0]
    };
    let total: f64 = area_rects.iter().map(|r| r.size[0] * r.size[1]).sum();
    outlines
        .iter()
        .zip(area_rects.iter().zip(square_rects))
        .map(|(o, (a, q))| {
            let mut angles: Vec<f64> = turns.iter().map(|t| a.angle + t).collect();
            let large = a.size[0] * a.size[1] > 0.25 * total;
            if large && (q.angle - a.angle).abs() > 1e-9 {
                angles.extend(turns.iter().map(|t| q.angle + t));
            }
            angles
                .into_iter()
                .map(|angle| crate::profile::Turned::new(o, angle))
                .collect()
        })
        .collect()
}

/// The profile packer's two orders: largest rectangle area first, widest first.
fn orders(area_rects: &[BoundingRect]) -> [Vec<usize>; 2] {
    let area = |k: usize| area_rects[k].size[0] * area_rects[k].size[1];
    let mut by_area: Vec<usize> = (0..area_rects.len()).collect();
    by_area.sort_by(|&a, &b| area(b).total_cmp(&area(a)).then(a.cmp(&b)));
    let mut by_width: Vec<usize> = (0..area_rects.len()).collect();
    by_width.sort_by(|&a, &b| {
        area_rects[b].size[0]
            .total_cmp(&area_rects[a].size[0])
            .then(a.cmp(&b))
    });
    [by_area, by_width]
}

/// Charts as a neck trial packs them: each chart's outline loops (closed polylines of
/// layout points; every point of the chart inside them) with its smallest-area and
/// smallest-square rectangles. A trial replaces one chart by its two parts: only theirs
/// are measured, the others' rectangles carried over (measuring every chart's again was
/// a third of a trial's work on eight).
pub(crate) struct Outlined {
    loops: Vec<Vec<Vec<[f64; 2]>>>,
    area: Vec<BoundingRect>,
    square: Vec<BoundingRect>,
}

impl Outlined {
    /// The charts of `loops`, their rectangles measured.
    pub(crate) fn new(loops: Vec<Vec<Vec<[f64; 2]>>>, options: &PackOptions) -> Self {
        let points: Vec<Vec<[f64; 2]>> = loops.iter().map(|o| o.concat()).collect();
        let (area, square) = options.rects(&points);
        Self {
            loops,
            area,
            square,
        }
    }

    /// These charts with chart `slot` replaced by `parts` (each given by its loops).
    pub(crate) fn split(
        &self,
        slot: usize,
        parts: Vec<Vec<Vec<[f64; 2]>>>,
        options: &PackOptions,
    ) -> Self {
        let new = Self::new(parts, options);
        let mut out = Self {
            loops: self.loops.clone(),
            area: self.area.clone(),
            square: self.square.clone(),
        };
        out.loops.splice(slot..=slot, new.loops);
        out.area.splice(slot..=slot, new.area);
        out.square.splice(slot..=slot, new.square);
        out
    }

    /// The charts in the orientations the profile packer tries (for [`fits_at`] and
    /// [`trial_pack`] of the same charts: turned once).
    pub(crate) fn turned(&self, options: &PackOptions) -> Vec<Vec<crate::profile::Turned>> {
        turned_charts(&self.loops, &self.area, &self.square, options)
    }
}

/// Whether the profile packer fits the `charts` (`turned` as [`Outlined::turned`] gives
/// them) into the square at common scale `scale` (texture units per layout unit, as
/// [`Packing::scale`]) on its coarse grid, in either of its orders: one packing each, a
/// quick test of whether a change to the charts can beat a scale reached before.
pub(crate) fn fits_at(
    charts: &Outlined,
    turned: &[Vec<crate::profile::Turned>],
    scale: f64,
    options: &PackOptions,
) -> bool {
    let n = options.resolution;
    let cell = if n >= 64 { PROFILE_CELL } else { 1.0 };
    orders(&charts.area).iter().any(|order| {
        crate::profile::pack(
            turned,
            order,
            scale * n as f64,
            n,
            options.margin_texels,
            cell,
            None,
        )
        .is_some()
    })
}

/// Bisection steps of a neck trial's packing ([`trial_pack`]): 7, over the interval from a
/// scale the charts are known to reach to the area bound (usually under half the
/// rectangle packer's interval): the scale to a few tenths of a percent, well under the
/// gain a neck cut must bring ([`crate::neck::NECK_GAIN`], 3 %).
pub const TRIAL_STEPS: usize = 7;

/// A neck trial's packing of `charts` (`turned` as [`Outlined::turned`] gives them): the
/// profile packer alone on its coarse grid,
/// searched above `floor` (texture units per layout unit, a scale [`fits_at`] found the
/// charts reach) in [`TRIAL_STEPS`] steps; `None` when it finds no higher scale. Its
/// efficiency is not measured (0): a trial is compared by its scale, and the atlas packed
/// again once its cuts are chosen.
pub(crate) fn trial_pack(
    charts: &Outlined,
    turned: &[Vec<crate::profile::Turned>],
    floor: f64,
    options: &PackOptions,
) -> Option<Packing> {
    let n = options.resolution as f64;
    by_turned(
        turned,
        &charts.loops,
        &charts.area,
        floor * n,
        options,
        false,
        TRIAL_STEPS,
    )
}

/// The outlines packed by the profile packer at the largest scale it reaches above
/// `floor` (the rectangle packer's), `steps` bisection steps in its first order, each chart tried in four quarter turns of its
/// smallest-area rectangle and of its smallest square (one of each when `turn` is off),
/// two orders (largest area first, widest first), first on the coarse grid, then, when
/// `refine`, at one texel per column; `None` when it does not beat `floor`.
pub(crate) fn by_outlines(
    outlines: &[Vec<Vec<[f64; 2]>>],
    area_rects: &[BoundingRect],
    square_rects: &[BoundingRect],
    floor: f64,
    options: &PackOptions,
    refine: bool,
    steps: usize,
) -> Option<Packing> {
    let turned = turned_charts(outlines, area_rects, square_rects, options);
    by_turned(&turned, outlines, area_rects, floor, options, refine, steps)
}

/// [`by_outlines`] with the charts already turned (`turned`, as [`turned_charts`] gives
/// them for `outlines` and `area_rects`).
fn by_turned(
    turned: &[Vec<crate::profile::Turned>],
    outlines: &[Vec<Vec<[f64; 2]>>],
    area_rects: &[BoundingRect],
    floor: f64,
    options: &PackOptions,
    refine: bool,
    steps: usize,
) -> Option<Packing> {
    use crate::profile::pack;
    let n = options.resolution;
    let m = options.margin_texels;
    let [by_area, by_width] = orders(area_rects);
    let hull_area: f64 = outlines
        .iter()
        .map(|o| {
            o.first()
                .map_or(0.0, |l| polygon_area(&crate::hull::convex_hull(l)))
        })
        .sum();
    if !(hull_area > 0.0) {
        return None;
    }
    let ceiling = n as f64 / hull_area.sqrt();
    let cell = if n >= 64 { PROFILE_CELL } else { 1.0 };
    // (scale, order, places, height)
    let mut best: Option<(f64, &[usize], Vec<crate::profile::Place>, f64)> = None;
    // the second order searched above the first's scale, in half the steps
    for (order, steps) in [(&by_area[..], steps), (&by_width[..], steps / 2)] {
        let (mut lo, mut hi) = (best.as_ref().map_or(floor, |b| b.0), ceiling.max(floor));
        for _ in 0..steps {
            let mid = 0.5 * (lo + hi);
            match pack(turned, order, mid, n, m, cell, None) {
                Some((places, height)) => {
                    lo = mid;
                    if best.as_ref().is_none_or(|b| mid > b.0) {
                        best = Some((mid, order, places, height));
                    }
                }
                None => hi = mid,
            }
        }
    }
    let (mut s, order, mut places, mut height) = best?;
    if refine && cell > 1.0 {
        // each chart in the orientation the coarse grid chose
        let fixed: Vec<usize> = places.iter().map(|p| p.turn).collect();
        let (mut lo, mut hi) = (s, s * (1.0 + PROFILE_REFINE));
        for _ in 0..PROFILE_REFINE_STEPS {
            let mid = 0.5 * (lo + hi);
            match pack(turned, order, mid, n, m, 1.0, Some(&fixed)) {
                Some(found) => {
                    lo = mid;
                    (s, places, height) = (mid, found.0, found.1);
                }
                None => hi = mid,
            }
        }
    }
    let nf = n as f64;
    let charts = places
        .iter()
        .zip(turned)
        .map(|(p, t)| ChartPlacement {
            angle: t[p.turn].angle,
            scale: s / nf,
            offset: [p.offset[0] / nf, p.offset[1] / nf],
        })
        .collect();
    Some(Packing {
        charts,
        scale: s / nf,
        efficiency: 0.0,
        used_height: height / nf,
    })
}

/// A packing at one scale: the scale, the spots (in packing order) and the height used.
type Layout = (f64, Vec<skyline::Spot>, f64);

/// A rectangle packer's sort key (an entry of [`ORDERS`]).
type SortKey = fn(&BoundingRect) -> [f64; 2];

/// A rectangle packing: its layout, the order packed and the rectangles turned as packed.
type RectLayout<'a> = (Layout, Vec<usize>, &'a [BoundingRect]);

/// Orders the skyline packer is tried with: tallest first, largest area first, longest
/// side first, widest first (ties by the next size, then by index: deterministic).
const ORDERS: [SortKey; 4] = [
    |r| [r.size[1], r.size[0]],
    |r| [r.size[0] * r.size[1], r.size[1]],
    |r| [r.size[0].max(r.size[1]), r.size[0].min(r.size[1])],
    |r| [r.size[0], r.size[1]],
];

fn order_by(rects: &[BoundingRect], key: fn(&BoundingRect) -> [f64; 2]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..rects.len()).collect();
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(&rects[a]), key(&rects[b]));
        kb[0]
            .total_cmp(&ka[0])
            .then(kb[1].total_cmp(&ka[1]))
            .then(a.cmp(&b))
    });
    order
}

/// The largest scale (bisection) at which the skyline packer fits `rects` in `order` with
/// their margins in the square, its spots and the height used; `None` when the margins
/// alone overflow it.
fn largest_scale(rects: &[BoundingRect], order: &[usize], options: &PackOptions) -> Option<Layout> {
    let n = options.resolution as f64;
    let m = options.margin_texels;
    let try_scale = |s: f64| {
        let sizes: Vec<[f64; 2]> = order
            .iter()
            .map(|&k| [rects[k].size[0] * s + m, rects[k].size[1] * s + m])
            .collect();
        skyline::pack(&sizes, n, options.turn).filter(|(_, h)| *h <= n * (1.0 + 1e-12))
    };
    try_scale(0.0)?;
    // the rectangles' total area bounds the scale from above
    let area: f64 = rects.iter().map(|r| r.size[0] * r.size[1]).sum();
    let widest = rects.iter().map(|r| r.size[0]).fold(0.0, f64::max);
    let mut hi = if area > 0.0 { n / area.sqrt() } else { 1.0 };
    if widest > 0.0 {
        hi = hi.min((n - m).max(0.0) / widest * 2.0);
    }
    let mut lo = 0.0;
    while try_scale(hi).is_some() && hi < 1e300 {
        (lo, hi) = (hi, hi * 2.0);
    }
    for _ in 0..options.scale_steps {
        let mid = 0.5 * (lo + hi);
        if try_scale(mid).is_some() {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let (spots, height) = try_scale(lo)?;
    Some((lo, spots, height))
}

/// Turns the packer's spots into chart placements in texture units.
fn placements(
    charts: &[Vec<[f64; 2]>],
    rects: &[BoundingRect],
    order: &[usize],
    spots: &[skyline::Spot],
    s: f64,
    height: f64,
    options: &PackOptions,
) -> Packing {
    let n = options.resolution as f64;
    let half = 0.5 * options.margin_texels;
    let mut out = vec![
        ChartPlacement {
            angle: 0.0,
            scale: 0.0,
            offset: [0.0; 2]
        };
        charts.len()
    ];
    for (spot, &k) in spots.iter().zip(order) {
        let r = rects[k];
        // a quarter turn maps [x0, x0 + w] × [y0, y0 + h] to [−y0 − h, −y0] × [x0, x0 + w]
        let (angle, min) = if spot.turned {
            (
                r.angle + std::f64::consts::FRAC_PI_2,
                [-(r.min[1] + r.size[1]), r.min[0]],
            )
        } else {
            (r.angle, r.min)
        };
        out[k] = ChartPlacement {
            angle,
            scale: s / n,
            offset: [
                (spot.x + half - s * min[0]) / n,
                (spot.y + half - s * min[1]) / n,
            ],
        };
    }
    let hull_area: f64 = charts
        .iter()
        .map(|c| polygon_area(&crate::hull::convex_hull(c)))
        .sum();
    Packing {
        charts: out,
        scale: s / n,
        efficiency: hull_area * (s / n) * (s / n),
        used_height: height / n,
    }
}

/// Area of a counter-clockwise polygon.
fn polygon_area(p: &[[f64; 2]]) -> f64 {
    let k = p.len();
    0.5 * (0..k)
        .map(|i| p[i][0] * p[(i + 1) % k][1] - p[(i + 1) % k][0] * p[i][1])
        .sum::<f64>()
}

/// Options in range and every point finite.
fn check(charts: &[Vec<[f64; 2]>], options: &PackOptions) -> Result<(), AtlasError> {
    if options.resolution == 0 {
        return Err(AtlasError::InvalidOption {
            name: "resolution",
            value: "0".into(),
            why: "at least 1 texel",
        });
    }
    if !(options.margin_texels >= 0.0 && options.margin_texels.is_finite()) {
        return Err(AtlasError::InvalidOption {
            name: "margin",
            value: options.margin_texels.to_string(),
            why: "a finite number of texels, 0 or more",
        });
    }
    for (chart, points) in charts.iter().enumerate() {
        if let Some(index) = points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
            return Err(AtlasError::NonFinite { chart, index });
        }
    }
    Ok(())
}
