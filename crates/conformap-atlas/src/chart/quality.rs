//! How good a chart is, by the numbers of the atlas tables: area spread, angle
//! distortion, flipped faces and seam length agreement.

use conformap_mesh::{CutMesh, TriMesh};
use conformap_metrics::{corner_map_metrics, MetricsOptions};
use num_complex::Complex64;
use serde::Serialize;

/// The quality of a layout of a mesh's faces (one uv per corner through the cut mesh).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct ChartQuality {
    /// sd over faces of `log(uv area share / 3D area share)`.
    pub area_spread: f64,
    /// Mean over corners of `|uv angle − 3D angle|`, degrees.
    pub angle_mean_deg: f64,
    /// Faces turned over in the layout.
    pub flipped: usize,
    /// Mean over seam edges of `|log(uv length on one side / on the other)|`.
    pub seam_log_ratio_mean: f64,
    /// The largest such ratio.
    pub seam_log_ratio_max: f64,
}

/// Measures the layout `uv` (one point per vertex of `cut.mesh`) of `mesh`'s faces: the
/// area spread and angle distortion are `conformap-metrics`' (`area_distortion_log.sd`,
/// `angle_distortion_deg.mean` of [`corner_map_metrics`]); flips are counted as they stand
/// (no orientation fix: an atlas must be counter-clockwise).
pub fn chart_quality(mesh: &TriMesh, cut: &CutMesh, uv: &[Complex64]) -> ChartQuality {
    let corner: Vec<Complex64> = cut
        .mesh
        .faces()
        .iter()
        .flat_map(|t| t.map(|v| uv[v as usize]))
        .collect();
    let (area_spread, angle_mean_deg) = spread_and_angle(mesh, &corner);
    let flipped = flipped_corner_faces(&corner);
    // seams: an input edge whose two half-edges sit on different cut vertices
    let opp = mesh.opposite_halfedges();
    let (mut seam_sum, mut seam_max, mut seams) = (0.0f64, 0.0f64, 0usize);
    for (h, &o) in opp.iter().enumerate() {
        if o == conformap_mesh::NO_HALFEDGE || (o as usize) < h {
            continue;
        }
        let ends = |h: usize| {
            let (f, k) = (h / 3, h % 3);
            let c = cut.mesh.faces()[f];
            (c[k], c[(k + 1) % 3])
        };
        let (a, b) = ends(h);
        let (c, d) = ends(o as usize);
        if a == d && b == c {
            continue; // not a seam
        }
        let r = ((uv[a as usize] - uv[b as usize]).norm()
            / (uv[c as usize] - uv[d as usize]).norm())
        .ln()
        .abs();
        seam_sum += r;
        seam_max = seam_max.max(r);
        seams += 1;
    }
    ChartQuality {
        area_spread,
        angle_mean_deg,
        flipped,
        seam_log_ratio_mean: seam_sum / seams.max(1) as f64,
        seam_log_ratio_max: seam_max,
    }
}

/// The area spread and mean angle distortion (degrees) of a per-corner map, as
/// `conformap-metrics` measures them; NaN if the map cannot be judged (not finite).
fn spread_and_angle(mesh: &TriMesh, corner: &[Complex64]) -> (f64, f64) {
    match corner_map_metrics(mesh, corner, &MetricsOptions::DEFAULT) {
        Ok(m) => (m.area_distortion_log.sd, m.angle_distortion_deg.mean),
        Err(_) => (f64::NAN, f64::NAN),
    }
}

/// Faces of a per-corner map (`corner[3 f + k]`) whose image is not counter-clockwise.
pub(crate) fn flipped_corner_faces(corner: &[Complex64]) -> usize {
    corner
        .chunks_exact(3)
        .filter(|q| {
            let (e1, e2) = (q[1] - q[0], q[2] - q[0]);
            e1.re * e2.im - e1.im * e2.re <= 0.0
        })
        .count()
}
