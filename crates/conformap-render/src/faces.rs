//! Per-face quantities of a map for colouring and histograms, from `conformap-metrics`'
//! per-face distortion (planar maps as given; sphere maps through their chord triangles).

use conformap_mesh::TriMesh;
use conformap_metrics::{face_distortion, isometric_chart, FaceDistortion};
use num_complex::Complex64;
use rayon::prelude::*;

use crate::colormap::Scale;
use crate::options::ColorBy;
use crate::param::{Domain, MapCoords};
use conformap_operators::vec3::{cross, dot};

/// Quantile of the per-face values that ends a colour scale: 0.99, so a few extreme faces
/// (at boundary corners, where every conformal map concentrates its distortion) do not
/// wash out the rest; the colour bar marks a clipped end with `>`.
pub const COLOR_RANGE_QUANTILE: f64 = 0.99;

/// [`FaceDistortion`] of every face, in face order. Planar maps whose total signed area is
/// negative (mirrored, e.g. another tool's `v ↦ −v`) are measured conjugated, as
/// `conformap_metrics::planar_map_metrics` does, so only real folds count as flipped.
/// Sphere maps are measured on their chord triangles (the isometric chart of each image
/// triangle), flipped where the image triangle turns its back to the sphere's outside
/// (relative to the majority orientation).
pub(crate) fn distortions(mesh: &TriMesh, coords: &MapCoords<'_>) -> Vec<FaceDistortion> {
    let faces = 0..mesh.num_faces();
    let p = mesh.positions();
    let points = |f: usize| mesh.faces()[f].map(|v| p[v as usize]);
    match coords.domain() {
        Domain::Plane => {
            let image = |f: usize| coords.face(mesh, f).map(|q| Complex64::new(q[0], q[1]));
            let signed: f64 = faces
                .clone()
                .into_par_iter()
                .map(|f| twice_area(image(f)))
                .sum();
            let mirrored = signed < 0.0;
            faces
                .into_par_iter()
                .map(|f| {
                    let g = image(f);
                    let g = if mirrored { g.map(|z| z.conj()) } else { g };
                    face_distortion(points(f), g)
                })
                .collect()
        }
        Domain::Sphere => {
            let orient = |q: [[f64; 3]; 3]| dot(q[0], cross(q[1], q[2]));
            let signed: f64 = faces
                .clone()
                .into_par_iter()
                .map(|f| orient(coords.face(mesh, f)))
                .sum();
            faces
                .into_par_iter()
                .map(|f| {
                    let q = coords.face(mesh, f);
                    let chart = isometric_chart(q);
                    let outward = (orient(q) >= 0.0) == (signed >= 0.0);
                    let g = if outward {
                        chart
                    } else {
                        chart.map(|z| z.conj())
                    };
                    face_distortion(points(f), g)
                })
                .collect()
        }
    }
}

#[inline]
fn twice_area(g: [Complex64; 3]) -> f64 {
    let (a, b) = (g[1] - g[0], g[2] - g[0]);
    a.re * b.im - a.im * b.re
}

/// A per-face quantity ready to colour: one value per face (`NaN` for flagged faces:
/// flipped or degenerate), the colour scale, and what it is called.
pub(crate) struct FaceField {
    /// Value per face, `NaN` where flagged.
    pub values: Vec<f64>,
    /// Number of flagged (flipped or degenerate) faces.
    pub flagged: usize,
    /// The colour scale.
    pub scale: Scale,
    /// Whether the largest value exceeds the scale's top (the bar marks it with `>`).
    pub clipped_hi: bool,
    /// Whether the smallest value is below the scale's bottom.
    pub clipped_lo: bool,
    /// Colour bar title.
    pub title: &'static str,
    /// Unit appended to the bar's numbers.
    pub unit: &'static str,
}

impl FaceField {
    /// One colour per face: the scale's colour of its value, the flagging colour where the
    /// value is undefined (a folded or degenerate face).
    pub(crate) fn colors(&self) -> Vec<[f32; 3]> {
        self.values
            .par_iter()
            .map(|&v| {
                if v.is_nan() {
                    crate::colormap::FLAG_COLOR
                } else {
                    self.scale.color(v)
                }
            })
            .collect()
    }
}

/// The field of `color` (one of the per-face quantities) from the face distortions.
pub(crate) fn face_field(d: &[FaceDistortion], color: ColorBy) -> FaceField {
    let bad = |x: &FaceDistortion| x.flipped() || x.degenerate();
    let (values, title, unit, diverging): (Vec<f64>, _, _, _) = match color {
        ColorBy::Beltrami => (
            d.iter()
                .map(|x| if bad(x) { f64::NAN } else { x.beltrami_abs })
                .collect(),
            "|μ|",
            "",
            false,
        ),
        ColorBy::Area => {
            let (mut img, mut mesh) = (0.0, 0.0);
            for x in d.iter().filter(|x| !x.degenerate()) {
                img += x.image_signed_area.abs();
                mesh += x.mesh_area;
            }
            let log_totals = mesh.ln() - img.ln();
            (
                d.iter()
                    .map(|x| {
                        if bad(x) {
                            f64::NAN
                        } else {
                            x.image_signed_area.abs().ln() - x.mesh_area.ln() + log_totals
                        }
                    })
                    .collect(),
                "log area",
                "",
                true,
            )
        }
        _ => (
            d.iter()
                .map(|x| {
                    if bad(x) {
                        f64::NAN
                    } else {
                        x.mean_angle_distortion_deg()
                    }
                })
                .collect(),
            "angle",
            "°",
            false,
        ),
    };
    let flagged = values.iter().filter(|v| v.is_nan()).count();
    let mut finite: Vec<f64> = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .map(|v| if diverging { v.abs() } else { v })
        .collect();
    let max = finite.iter().copied().fold(0.0, f64::max);
    let top = quantile(&mut finite, COLOR_RANGE_QUANTILE);
    // a perfect map: give the scale some room so its one colour is the low end
    let top = if top > 0.0 { top } else { max.max(1e-12) };
    let (lo, hi) = if diverging { (-top, top) } else { (0.0, top) };
    let min_value = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let max_value = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    FaceField {
        values,
        flagged,
        scale: Scale { lo, hi, diverging },
        clipped_hi: max_value > hi,
        clipped_lo: diverging && min_value < lo,
        title,
        unit,
    }
}

/// The `q`-quantile (nearest rank) of `values` (reordered); 0 for none.
fn quantile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let k = ((q * values.len() as f64).ceil() as usize).clamp(1, values.len()) - 1;
    let (_, v, _) = values.select_nth_unstable_by(k, f64::total_cmp);
    *v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantile_nearest_rank() {
        let mut v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(quantile(&mut v, 0.99), 99.0);
        assert_eq!(quantile(&mut v, 1.0), 100.0);
        assert_eq!(quantile(&mut [], 0.5), 0.0);
    }
}
