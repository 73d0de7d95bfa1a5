//! How good a chart is, by the numbers of the atlas tables: area spread, angle
//! distortion, flipped faces and seam length agreement.

use conformap_mesh::{CutMesh, TriMesh};
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

fn angles3(p: [[f64; 3]; 3]) -> [f64; 3] {
    let d = |a: [f64; 3], b: [f64; 3]| [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ang = |u: [f64; 3], v: [f64; 3]| {
        let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
        let c = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt().atan2(dot)
    };
    [
        ang(d(p[0], p[1]), d(p[0], p[2])),
        ang(d(p[1], p[2]), d(p[1], p[0])),
        ang(d(p[2], p[0]), d(p[2], p[1])),
    ]
}

/// Measures the layout `uv` (one point per vertex of `cut.mesh`) of `mesh`'s faces.
pub fn chart_quality(mesh: &TriMesh, cut: &CutMesh, uv: &[Complex64]) -> ChartQuality {
    let lift = |z: Complex64| [z.re, z.im, 0.0];
    let (mut a3, mut a2) = (Vec::new(), Vec::new());
    let (mut angle_sum, mut flipped) = (0.0, 0usize);
    for (f, t) in mesh.faces().iter().enumerate() {
        let c = cut.mesh.faces()[f];
        let p = t.map(|v| mesh.positions()[v as usize]);
        let q = c.map(|v| uv[v as usize]);
        let area3 = 0.5 * {
            let (u, v) = (
                [p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]],
                [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]],
            );
            ((u[1] * v[2] - u[2] * v[1]).powi(2)
                + (u[2] * v[0] - u[0] * v[2]).powi(2)
                + (u[0] * v[1] - u[1] * v[0]).powi(2))
            .sqrt()
        };
        let (e1, e2) = (q[1] - q[0], q[2] - q[0]);
        let area2 = 0.5 * (e1.re * e2.im - e1.im * e2.re);
        if area2 <= 0.0 {
            flipped += 1;
        }
        a3.push(area3);
        a2.push(area2.abs());
        let (x, y) = (angles3(p), angles3(q.map(lift)));
        angle_sum += (0..3).map(|k| (x[k] - y[k]).abs()).sum::<f64>();
    }
    let (s3, s2) = (a3.iter().sum::<f64>(), a2.iter().sum::<f64>());
    let logs: Vec<f64> = a3
        .iter()
        .zip(&a2)
        .map(|(&x, &y)| ((y / s2).max(f64::MIN_POSITIVE) / (x / s3)).ln())
        .collect();
    let mean = logs.iter().sum::<f64>() / logs.len().max(1) as f64;
    let sd =
        (logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / logs.len().max(1) as f64).sqrt();
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
        area_spread: sd,
        angle_mean_deg: (angle_sum / (3 * mesh.num_faces()).max(1) as f64).to_degrees(),
        flipped,
        seam_log_ratio_mean: seam_sum / seams.max(1) as f64,
        seam_log_ratio_max: seam_max,
    }
}
