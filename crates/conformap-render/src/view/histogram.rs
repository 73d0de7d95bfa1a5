//! The histogram of the corner angle distortion in degrees (the format of the CEM and
//! CCEM papers' figures: `|mesh angle − image angle|` over all corners), as PNG or SVG.

use std::fmt::Write;

use conformap_mesh::TriMesh;

use crate::error::RenderError;
use crate::faces::distortions;
use crate::font::{draw_text, format_value, text_width, GLYPH_H};
use crate::image::Image;
use crate::options::RenderOptions;
use crate::param::MapCoords;
use crate::textures::TONE_DARK;

/// Colour of axes and text.
const INK: [u8; 3] = [20, 20, 20];
/// Height of a histogram picture as a share of its width: 5/8.
const ASPECT: f64 = 0.625;

/// Counts of the corner angle distortion (degrees) in equal bins from 0 to a round upper
/// end at or above the largest value.
#[derive(Debug, Clone, PartialEq)]
pub struct AngleHistogram {
    /// Bin edges in degrees, `bins + 1` of them, from 0.
    pub edges_deg: Vec<f64>,
    /// Corners per bin (the last bin includes its upper edge).
    pub counts: Vec<u64>,
    /// Mean corner distortion, degrees.
    pub mean_deg: f64,
    /// Largest corner distortion, degrees.
    pub max_deg: f64,
    /// Corners counted (three per face whose image is not degenerate).
    pub corners: u64,
}

/// The smallest of `{1, 2, 2.5, 5} × 10^k` at or above `x` (1 for `x ≤ 0`).
fn nice_ceil(x: f64) -> f64 {
    if !(x > 0.0) || !x.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    for m in [1.0, 2.0, 2.5, 5.0, 10.0] {
        if m * p >= x * (1.0 - 1e-12) {
            return m * p;
        }
    }
    10.0 * p
}

/// The histogram of the corner angle distortion of the map `coords` of `mesh`, in
/// `bins` equal bins (faces whose image is degenerate are left out, as in
/// `conformap_metrics::planar_map_metrics`).
///
/// # Errors
/// [`RenderError`] for a map that does not fit the mesh (see [`MapCoords::check`]) or
/// `bins == 0`.
pub fn angle_histogram(
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    bins: usize,
) -> Result<AngleHistogram, RenderError> {
    coords.check(mesh)?;
    if bins == 0 {
        return Err(RenderError::InvalidOption {
            name: "histogram_bins",
            reason: "must be at least 1",
        });
    }
    let d = distortions(mesh, coords);
    let values = || {
        d.iter()
            .filter(|x| !x.degenerate())
            .flat_map(|x| x.corner_angle_distortion_deg)
    };
    let (mut sum, mut max, mut n) = (0.0, 0.0f64, 0u64);
    for v in values() {
        sum += v;
        max = max.max(v);
        n += 1;
    }
    let hi = nice_ceil(max);
    let mut counts = vec![0u64; bins];
    for v in values() {
        let b = ((v / hi * bins as f64) as usize).min(bins - 1);
        counts[b] += 1;
    }
    Ok(AngleHistogram {
        edges_deg: (0..=bins).map(|k| hi * k as f64 / bins as f64).collect(),
        counts,
        mean_deg: if n > 0 { sum / n as f64 } else { 0.0 },
        max_deg: max,
        corners: n,
    })
}

/// Plot area `[x0, y0, x1, y1]` of a histogram picture `w × h`.
fn plot_area(w: f64, h: f64) -> [f64; 4] {
    [0.12 * w, 0.12 * h, 0.96 * w, 0.84 * h]
}

/// The histogram as a PNG picture, `size` wide.
pub(crate) fn histogram_image(hist: &AngleHistogram, options: &RenderOptions) -> Image {
    let w = options.size;
    let h = ((w as f64 * ASPECT) as u32).max(16);
    let mut img = Image::filled(w, h, options.background);
    let [x0, y0, x1, y1] = plot_area(w as f64, h as f64);
    let top = hist.counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    let bins = hist.counts.len();
    let bar = [TONE_DARK[0], TONE_DARK[1], TONE_DARK[2]].map(|c| (c * 255.0) as u8);
    for (b, &c) in hist.counts.iter().enumerate() {
        let bx0 = x0 + (x1 - x0) * b as f64 / bins as f64;
        let bx1 = x0 + (x1 - x0) * (b + 1) as f64 / bins as f64;
        let by = y1 - (y1 - y0) * c as f64 / top;
        img.fill_rect(
            bx0.round() as i64 + 1,
            by.round() as i64,
            bx1.round() as i64,
            y1.round() as i64,
            bar,
        );
    }
    let k = ((w as i64) / 400).max(1);
    let (ix0, iy0, ix1, iy1) = (x0 as i64, y0 as i64, x1 as i64, y1 as i64);
    img.fill_rect(ix0 - k, iy1, ix1, iy1 + k, INK);
    img.fill_rect(ix0 - k, iy0, ix0, iy1 + k, INK);
    let hi = hist.edges_deg.last().copied().unwrap_or(1.0);
    for q in 0..=4 {
        let x = ix0 + ((x1 - x0) * q as f64 / 4.0) as i64;
        img.fill_rect(x - k / 2, iy1, x - k / 2 + k, iy1 + 3 * k, INK);
        let label = format!("{}°", format_value(hi * q as f64 / 4.0));
        let tw = text_width(&label, k);
        draw_text(&mut img, x - tw / 2, iy1 + 5 * k, &label, k, INK);
    }
    for (count, y) in [(0u64, iy1), (top as u64, iy0)] {
        let label = count.to_string();
        let tw = text_width(&label, k);
        img.fill_rect(ix0 - 3 * k, y, ix0, y + k, INK);
        draw_text(
            &mut img,
            ix0 - 5 * k - tw,
            y - GLYPH_H * k / 2,
            &label,
            k,
            INK,
        );
    }
    let title = "angle distortion";
    draw_text(&mut img, ix0, iy0 - 3 * GLYPH_H * k / 2, title, k, INK);
    let stats = format!(
        "mean {}°  max {}°",
        format_value(hist.mean_deg),
        format_value(hist.max_deg)
    );
    let tw = text_width(&stats, k);
    draw_text(
        &mut img,
        ix1 - tw,
        iy0 - 3 * GLYPH_H * k / 2,
        &stats,
        k,
        INK,
    );
    draw_text(
        &mut img,
        ix0,
        h as i64 - 2 * GLYPH_H * k + k,
        "corners",
        k,
        INK,
    );
    img
}

/// The histogram as an SVG document, `size` pixels wide (text in the viewer's sans-serif
/// font).
pub fn histogram_svg(hist: &AngleHistogram, size: u32) -> String {
    let w = size as f64;
    let h = (w * ASPECT).round();
    let [x0, y0, x1, y1] = plot_area(w, h);
    let top = hist.counts.iter().copied().max().unwrap_or(0).max(1) as f64;
    let bins = hist.counts.len().max(1);
    let font = (w / 50.0).round().max(8.0);
    let fill = TONE_DARK.map(|c| (c * 255.0) as u8);
    let mut s = String::new();
    // writing into a String cannot fail
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="{font}">"#
    );
    let _ = writeln!(s, r#"<rect width="{w}" height="{h}" fill="white"/>"#);
    let _ = writeln!(s, r#"<g fill="rgb({},{},{})">"#, fill[0], fill[1], fill[2]);
    for (b, &c) in hist.counts.iter().enumerate() {
        if c == 0 {
            continue;
        }
        let bx = x0 + (x1 - x0) * b as f64 / bins as f64;
        let bw = (x1 - x0) / bins as f64;
        let bh = (y1 - y0) * c as f64 / top;
        let _ = writeln!(
            s,
            r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}"><title>{}–{}°: {}</title></rect>"#,
            bx + 0.5,
            y1 - bh,
            (bw - 1.0).max(0.5),
            bh,
            format_value(hist.edges_deg[b]),
            format_value(hist.edges_deg[b + 1]),
            c
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<path d="M{x0:.1},{y0:.1} V{y1:.1} H{x1:.1}" fill="none" stroke="black"/>"#
    );
    let hi = hist.edges_deg.last().copied().unwrap_or(1.0);
    for q in 0..=4 {
        let x = x0 + (x1 - x0) * q as f64 / 4.0;
        let _ = writeln!(
            s,
            r#"<line x1="{x:.1}" y1="{y1:.1}" x2="{x:.1}" y2="{:.1}" stroke="black"/><text x="{x:.1}" y="{:.1}" text-anchor="middle">{}°</text>"#,
            y1 + 5.0,
            y1 + 5.0 + 1.2 * font,
            format_value(hi * q as f64 / 4.0)
        );
    }
    for (count, y) in [(0u64, y1), (top as u64, y0)] {
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{count}</text>"#,
            x0 - 6.0,
            y + 0.35 * font
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{x0:.1}" y="{:.1}">angle distortion (degrees)</text><text x="{x1:.1}" y="{:.1}" text-anchor="end">mean {}°, max {}°, {} corners</text>"#,
        y0 - 0.8 * font,
        y0 - 0.8 * font,
        format_value(hist.mean_deg),
        format_value(hist.max_deg),
        hist.corners
    );
    let _ = writeln!(s, "</svg>");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_upper_ends() {
        assert_eq!(nice_ceil(0.0), 1.0);
        assert_eq!(nice_ceil(3.2), 5.0);
        assert_eq!(nice_ceil(2.0), 2.0);
        assert_eq!(nice_ceil(0.21), 0.25);
        assert_eq!(nice_ceil(57.0), 100.0);
    }
}
