//! Packing charts into the texture square: one scale for all (one texel density), each chart
//! turned to its smallest bounding rectangle, a margin in texels around each, the largest
//! scale at which a skyline packer fits them all.

use serde::{Deserialize, Serialize};

use crate::error::AtlasError;
use crate::hull::{min_area_rect, min_square_rect, rotate, BoundingRect};
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
    check(charts, options)?;
    let too_many = AtlasError::TooManyCharts {
        charts: charts.len(),
        margin: options.margin_texels,
        resolution: options.resolution,
    };
    // three ways to turn the charts (smallest area, smallest square, mixed) and four orders
    // for the skyline: the largest common scale of the twelve is kept
    let area_rects: Vec<BoundingRect> = charts.iter().map(|c| min_area_rect(c)).collect();
    let square_rects: Vec<BoundingRect> = charts.iter().map(|c| min_square_rect(c)).collect();
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
    let mut best: Option<(Layout, Vec<usize>, &[BoundingRect])> = None;
    for rects in [&area_rects[..], &square_rects[..], &mixed[..]] {
        for key in ORDERS {
            let order = order_by(rects, key);
            let Some(layout) = largest_scale(rects, &order, options) else {
                continue;
            };
            if best.as_ref().is_none_or(|b| layout.0 > b.0 .0) {
                best = Some((layout, order, rects));
            }
        }
    }
    let ((s, spots, height), order, rects) = best.ok_or(too_many)?;
    Ok(placements(
        charts, rects, &order, &spots, s, height, options,
    ))
}

/// A packing at one scale: the scale, the spots (in packing order) and the height used.
type Layout = (f64, Vec<skyline::Spot>, f64);

/// Orders the skyline packer is tried with: tallest first, largest area first, longest
/// side first, widest first (ties by the next size, then by index: deterministic).
const ORDERS: [fn(&BoundingRect) -> [f64; 2]; 4] = [
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
