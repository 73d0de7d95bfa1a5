//! The options of an atlas that are not packing proper: charts kept in their own
//! coordinates (`--pack none`) and one texel density per chart (`--scale per-chart`).

use crate::chart::Piece;
use crate::component::ComponentChart;
use crate::error::AtlasError;
use crate::pack::{ChartPlacement, PackOptions, Packing};

/// Where the charts of an atlas go.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Layout {
    /// Turned and packed into `[0,1]²` with one common scale ([`crate::pack_charts`]).
    #[default]
    Pack,
    /// Kept in their own coordinates (not turned, not scaled: texture units are layout
    /// units, each component's layout at its surface's area, so 3D units on the whole),
    /// only moved apart side by side ([`keep_in_rows`]).
    Keep,
}

/// How large each chart is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ChartScale {
    /// One texel density for the whole atlas: every component's layout brought to its
    /// surface's area, all charts packed at one scale.
    #[default]
    Uniform,
    /// Every component's charts scaled together to the same texture area: a small
    /// component gets as many texels as a large one (a texel density per component; the
    /// charts a component was split into keep one density, so its seams stay even).
    PerChart,
}

/// Per piece of `charts` (in packing order), the factor that brings its component's
/// charts together to the mean layout area of the components: every component gets the
/// same texture area, the pieces of one component keep one density between them.
pub(crate) fn per_chart_factors(charts: &[ComponentChart]) -> Vec<f64> {
    let areas: Vec<f64> = charts
        .iter()
        .map(|c| c.pieces.iter().map(piece_area).sum())
        .collect();
    let mean = areas.iter().sum::<f64>() / areas.len().max(1) as f64;
    charts
        .iter()
        .zip(&areas)
        .flat_map(|(c, &a)| {
            let f = if a > 0.0 { (mean / a).sqrt() } else { 1.0 };
            std::iter::repeat_n(f, c.pieces.len())
        })
        .collect()
}

/// The layout area of a piece.
fn piece_area(p: &Piece) -> f64 {
    p.mesh
        .faces()
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| p.uv[v as usize]);
            0.5 * ((b - a).conj() * (c - a)).im.abs()
        })
        .sum()
}

/// `charts` (layout points) moved apart, neither turned nor scaled: left to right in rows
/// about `L = √(Σ bounding box areas)` wide (a roughly square block), each row above the
/// last, a gap of `L · margin / resolution` between charts (the margin the packer would
/// leave if the block filled the texture square).
///
/// # Errors
/// [`AtlasError::NonFinite`] for a NaN or infinite point.
pub fn keep_in_rows(
    charts: &[Vec<[f64; 2]>],
    options: &PackOptions,
) -> Result<Packing, AtlasError> {
    let mut boxes = Vec::with_capacity(charts.len());
    for (chart, points) in charts.iter().enumerate() {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (index, p) in points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(AtlasError::NonFinite { chart, index });
            }
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if points.is_empty() {
            (lo, hi) = ([0.0; 2], [0.0; 2]);
        }
        boxes.push((lo, hi));
    }
    let area: f64 = boxes
        .iter()
        .map(|(lo, hi)| (hi[0] - lo[0]) * (hi[1] - lo[1]))
        .sum();
    let width = area.sqrt();
    let gap = width * options.margin_texels / options.resolution.max(1) as f64;
    let (mut x, mut y, mut row_height) = (0.0f64, 0.0f64, 0.0f64);
    let mut placements = Vec::with_capacity(charts.len());
    for (lo, hi) in &boxes {
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        if x > 0.0 && x + w > width {
            (x, y, row_height) = (0.0, y + row_height + gap, 0.0);
        }
        placements.push(ChartPlacement {
            angle: 0.0,
            scale: 1.0,
            offset: [x - lo[0], y - lo[1]],
        });
        x += w + gap;
        row_height = row_height.max(h);
    }
    Ok(Packing {
        charts: placements,
        scale: 1.0,
        efficiency: f64::NAN,
        used_height: y + row_height,
    })
}
