//! Quality metrics of a sphere map, with its Möbius-invariant length cross-ratio distortion
//! (the planar one is `conformap_metrics::cross_ratio_distortion`).

use conformap_mesh::TriMesh;
use conformap_operators::{face_areas, face_points, triangle_angles};
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::mobius::energy::{check_len, chord_area, surface_shares, uniformity_from_areas};
use crate::stereo::{det3, stereographic, stereographic_south};
use crate::SphereError;
use conformap_metrics::{
    abs_log_stats, angle_stats, log_ratio_stats, summary_stats as summary, AbsLogStats, AngleStats,
    LogRatioStats, SummaryStats,
};
use conformap_operators::vec3::norm;

/// `|μ|` reported for a face whose chart image has `f_z = 0` (exactly anti-conformal):
/// `1e12`, finite so the report stays valid JSON; only inverted faces can reach it.
pub const SPHERE_BELTRAMI_CAP: f64 = 1e12;

/// Quality of a sphere map. The field names shared with the planar report
/// (`angle_distortion_deg`, `beltrami_abs`, `area_distortion_log`, `flipped_faces`,
/// `degenerate_faces`) mean the same there, measured as documented here.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct SphereMetrics {
    /// `max_v ||x_v| − 1|`.
    pub radius_residual_max: f64,
    /// Faces inverted on the sphere: `det[x_i, x_j, x_k] ≤ 0` for face `(i, j, k)`, i.e. the
    /// image triangle is not counter-clockwise seen from outside (orientation relative to
    /// the outward normal). Includes the degenerate faces.
    pub flipped_faces: usize,
    /// Faces whose chord triangle has zero area or `det = 0` (coincident or collinear image
    /// points).
    pub degenerate_faces: usize,
    /// `|mesh corner angle − chord-triangle corner angle|` in degrees over all corners of the
    /// non-degenerate faces. The chord triangle is the flat triangle through the three image
    /// points; its angles differ from the spherical triangle's by `O(h²)` for edge length `h`.
    pub angle_distortion_deg: AngleStats,
    /// `|μ|` (Beltrami coefficient `f_z̄ / f_z` of the affine map from an isometric chart of
    /// the 3D face to its image) measured in a stereographic chart: `τ̄ = (x − iy)/(1 − z)`
    /// for faces whose image centroid has `z ≤ 0`, `σ̄ = (x + iy)/(1 + z)` otherwise, so every
    /// face is measured in a chart where the sphere's metric varies by at most a factor 4.
    /// (The conjugates, because `τ` and `σ` reverse the orientation seen from outside.)
    pub beltrami_abs: SummaryStats,
    /// Per non-degenerate face `log(a_f / s_f)`: image share (chord area over total chord
    /// area) over surface share.
    pub area_distortion_log: LogRatioStats,
    /// Uniformity energy `Σ_f (a_f − s_f)²` (Jin et al. 2004, Eq. 7, §3.4).
    pub uniformity_energy: f64,
    /// Möbius-invariant discrete conformality: per interior edge, `|log(c' / c)|` of the
    /// length cross-ratios of the edge's two triangles on the mesh (`c`) and on the sphere
    /// with chordal lengths (`c'`); unchanged by any Möbius map. See
    /// [`sphere_cross_ratio_distortion`].
    pub cross_ratio_log: AbsLogStats,
    /// Faces in the angle, Beltrami and area statistics (all but the degenerate ones).
    pub measured_faces: usize,
}

/// Every metric of [`SphereMetrics`] for a sphere map (`points[v]` = image of vertex `v`).
///
/// # Errors
/// [`SphereError::MapLength`] or [`SphereError::NonFiniteMap`].
///
/// # Examples
/// ```
/// use conformap_sphere::sphere_metrics;
/// // the octahedron on the unit sphere, mapped by the identity
/// let p = vec![[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
///              [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
/// let faces = vec![[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
///                  [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]];
/// let mesh = conformap_mesh::TriMesh::try_new(p.clone(), faces)?;
/// let m = sphere_metrics(&mesh, &p)?;
/// assert_eq!(m.flipped_faces, 0);
/// assert!(m.angle_distortion_deg.max < 1e-12 && m.uniformity_energy < 1e-30);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn sphere_metrics(mesh: &TriMesh, points: &[[f64; 3]]) -> Result<SphereMetrics, SphereError> {
    check_len(mesh, points.len())?;
    if let Some(v) = points.iter().position(|p| !p.iter().all(|x| x.is_finite())) {
        return Err(SphereError::NonFiniteMap { vertex: v });
    }
    let radius_residual_max = points
        .iter()
        .map(|p| (norm(*p) - 1.0).abs())
        .fold(0.0, f64::max);
    let shares = surface_shares(mesh);
    let mesh_areas = face_areas(mesh);
    let nf = mesh.num_faces();
    let mut image_areas = Vec::with_capacity(nf);
    let mut angles = Vec::with_capacity(3 * nf);
    let mut mus = Vec::with_capacity(nf);
    let (mut flipped, mut degenerate) = (0usize, 0usize);
    let mut measured = Vec::with_capacity(nf);
    for (f, t) in mesh.faces().iter().enumerate() {
        let q = t.map(|v| points[v as usize]);
        let area = chord_area(q);
        image_areas.push(area);
        let det = det3(q[0], q[1], q[2]);
        if !(det > 0.0) {
            flipped += 1;
        }
        if !(area > 0.0) || det == 0.0 {
            degenerate += 1;
            continue;
        }
        measured.push(f);
        let p = face_points(mesh, f);
        let (am, ai) = (triangle_angles(p), triangle_angles(q));
        for k in 0..3 {
            angles.push((am[k] - ai[k]).abs().to_degrees());
        }
        mus.push(chart_beltrami(p, q));
    }
    let total_image: f64 = measured.iter().map(|&f| image_areas[f]).sum();
    let total_mesh: f64 = measured.iter().map(|&f| mesh_areas[f]).sum();
    let log_ratios: Vec<f64> = measured
        .iter()
        .map(|&f| ((image_areas[f] / total_image) / (mesh_areas[f] / total_mesh)).ln())
        .collect();
    let cross = conformap_metrics::cross_ratio_logs(mesh, |a, b| {
        norm(conformap_operators::vec3::sub(points[a], points[b]))
    });
    Ok(SphereMetrics {
        radius_residual_max,
        flipped_faces: flipped,
        degenerate_faces: degenerate,
        angle_distortion_deg: angle_stats(&mut angles),
        beltrami_abs: summary(&mus),
        area_distortion_log: log_ratio_stats(&log_ratios),
        uniformity_energy: uniformity_from_areas(&image_areas, &shares),
        cross_ratio_log: abs_log_stats(&cross),
        measured_faces: measured.len(),
    })
}

/// `|μ|` of face `p` (3D) mapped to the sphere triangle `q`, in the stereographic chart of
/// the hemisphere holding the image centroid (see [`SphereMetrics::beltrami_abs`]).
fn chart_beltrami(p: [[f64; 3]; 3], q: [[f64; 3]; 3]) -> f64 {
    let cz = q[0][2] + q[1][2] + q[2][2];
    // τ and σ reverse the orientation of the outward normal; their conjugates keep it
    let f = if cz <= 0.0 {
        q.map(|x| stereographic(x).conj())
    } else {
        q.map(|x| stereographic_south(x).conj())
    };
    beltrami_abs(p, f)
}

/// `|μ|` of the affine map from an isometric, orientation-preserving chart of the 3D triangle
/// `p` (`p0 ↦ 0`, `p1 ↦ w1 > 0`, `p2 ↦ w2` in the upper half-plane) to the planar triangle
/// `f`: `μ = (w1 d2 − w2 d1)/(w̄2 d1 − w1 d2)` with `d_k = f_k − f_0` (the formula of
/// conformap-metrics; 0 for a similarity, > 1 for an inverted image), capped at
/// [`SPHERE_BELTRAMI_CAP`].
pub(crate) fn beltrami_abs(p: [[f64; 3]; 3], f: [Complex64; 3]) -> f64 {
    let e1 = conformap_operators::vec3::sub(p[1], p[0]);
    let e2 = conformap_operators::vec3::sub(p[2], p[0]);
    let w1 = norm(e1);
    let w2 = Complex64::new(
        conformap_operators::vec3::dot(e1, e2) / w1,
        norm(conformap_operators::vec3::cross(e1, e2)) / w1,
    );
    let (d1, d2) = (f[1] - f[0], f[2] - f[0]);
    let num = d2 * w1 - d1 * w2;
    let den = d1 * w2.conj() - d2 * w1;
    let mu = num.norm() / den.norm();
    if mu <= SPHERE_BELTRAMI_CAP {
        mu
    } else {
        SPHERE_BELTRAMI_CAP
    }
}

/// Möbius-invariant conformality of a sphere map: per interior edge `|log(c'/c)|` of the
/// length cross-ratios (chordal lengths on the sphere). A Möbius map scales chordal distances
/// by `|φ(x) − φ(y)| = |x − y| √(λ(x) λ(y))`, which cancels in every cross-ratio, so this
/// metric is exactly unchanged by Möbius transformations — unlike corner angles of the chord
/// triangles, which change by `O(h |∇ log λ|)`. The planar counterpart is
/// [`conformap_metrics::cross_ratio_distortion`].
///
/// # Errors
/// [`SphereError::MapLength`].
pub fn sphere_cross_ratio_distortion(
    mesh: &TriMesh,
    points: &[[f64; 3]],
) -> Result<AbsLogStats, SphereError> {
    check_len(mesh, points.len())?;
    Ok(abs_log_stats(&conformap_metrics::cross_ratio_logs(
        mesh,
        |a, b| norm(conformap_operators::vec3::sub(points[a], points[b])),
    )))
}
