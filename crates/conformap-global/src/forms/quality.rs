//! How good a layout is: angle distortion (over all corners and away from the zeros),
//! area distortion, and the scale-free uniformity energy of Jin et al. Eq. 7.

use conformap_mesh::TriMesh;
use conformap_operators::{face_areas, triangle_angles};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::forms::zeros::signed_angle;
use conformap_metrics::{angle_stats, log_ratio_stats, AngleStats, LogRatioStats};
use conformap_operators::planar::triangle_signed_area;

/// Faces per parallel block of [`layout_metrics`]: ~1 ms of trigonometry, far more than a
/// task hand-off.
const FACE_BLOCK: usize = 1 << 13;

/// Quality of a global layout.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct LayoutMetrics {
    /// `|mesh corner angle − layout corner angle|` in degrees over all corners (signed
    /// layout angles, so a folded corner counts fully).
    pub angle_distortion_deg: AngleStats,
    /// The same over the corners of faces with no vertex in a zero cluster.
    pub angle_distortion_away_from_zeros_deg: AngleStats,
    /// `log((a_f/Σa) / (S_f/ΣS))` over unfolded faces (`a`: layout area, `S`: surface area).
    pub area_distortion_log: LogRatioStats,
    /// Jin et al. Eq. 7 made scale-free: `Σ_f (a_f/Σa − S_f/ΣS)²` with signed layout areas.
    pub uniformity_energy: f64,
    /// `Σ a_f`, the signed layout area.
    pub image_area: f64,
    /// `Σ S_f`.
    pub surface_area: f64,
}

/// Signed layout area of each face.
pub fn layout_areas(corner_uv: &[Complex64], faces: usize) -> Vec<f64> {
    (0..faces)
        .map(|f| triangle_signed_area(corner_uv[3 * f], corner_uv[3 * f + 1], corner_uv[3 * f + 2]))
        .collect()
}

/// The scale-free uniformity energy `Σ_f (a_f/Σa − S_f/ΣS)²`.
pub fn uniformity_energy(layout_area: &[f64], surface_area: &[f64]) -> f64 {
    let sa: f64 = layout_area.iter().sum();
    let ss: f64 = surface_area.iter().sum();
    layout_area
        .iter()
        .zip(surface_area)
        .map(|(a, s)| (a / sa - s / ss).powi(2))
        .sum()
}

/// Measures the layout of the first `faces` faces of `mesh`; `near_zero[v]` marks the
/// vertices of zero clusters.
pub fn layout_metrics(
    mesh: &TriMesh,
    corner_uv: &[Complex64],
    faces: usize,
    near_zero: &[bool],
) -> LayoutMetrics {
    let s_area: Vec<f64> = face_areas(mesh)[..faces].to_vec();
    let a_area = layout_areas(corner_uv, faces);
    // per-corner distortions in blocks of faces on both cores, joined in face order (the
    // same values in the same order as one sequential pass)
    let blocks: Vec<(Vec<f64>, Vec<f64>)> = (0..faces.div_ceil(FACE_BLOCK))
        .into_par_iter()
        .map(|b| {
            let range = b * FACE_BLOCK..((b + 1) * FACE_BLOCK).min(faces);
            let mut all = Vec::with_capacity(3 * range.len());
            let mut away = Vec::with_capacity(3 * range.len());
            for f in range {
                let t = mesh.faces()[f];
                let p = t.map(|v| mesh.positions()[v as usize]);
                let mesh_angles = triangle_angles(p);
                let q = [corner_uv[3 * f], corner_uv[3 * f + 1], corner_uv[3 * f + 2]];
                let clear = t.iter().all(|&v| !near_zero[v as usize]);
                for k in 0..3 {
                    let a = signed_angle(q[k], q[(k + 1) % 3], q[(k + 2) % 3]);
                    let d = (mesh_angles[k] - a).abs().to_degrees();
                    all.push(d);
                    if clear {
                        away.push(d);
                    }
                }
            }
            (all, away)
        })
        .collect();
    let mut all = Vec::with_capacity(3 * faces);
    let mut away = Vec::with_capacity(3 * faces);
    for (a, w) in &blocks {
        all.extend_from_slice(a);
        away.extend_from_slice(w);
    }
    let sa: f64 = a_area.iter().sum();
    let ss: f64 = s_area.iter().sum();
    let logs: Vec<f64> = a_area
        .iter()
        .zip(&s_area)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, s)| ((a / sa) / (s / ss)).ln())
        .collect();
    LayoutMetrics {
        angle_distortion_deg: angle_stats(&mut all),
        angle_distortion_away_from_zeros_deg: angle_stats(&mut away),
        area_distortion_log: log_ratio_stats(&logs),
        uniformity_energy: uniformity_energy(&a_area, &s_area),
        image_area: sa,
        surface_area: ss,
    }
}
