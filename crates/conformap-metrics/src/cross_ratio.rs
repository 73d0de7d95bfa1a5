//! The Möbius-invariant length cross-ratio distortion of a map: per interior edge, how much
//! the cross-ratio of the four edge lengths around it changes. A Möbius map scales distances
//! by `|μ(z) − μ(w)| = |z − w| / (|cz + d| |cw + d|)` in the plane (and chordal distances by
//! `√(λ(x) λ(y))` on the sphere), which cancels in every cross-ratio: the metric is exactly
//! unchanged by Möbius transformations, unlike corner angles.

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use crate::error::{check_map, MetricsError};
use crate::summary::{abs_log_stats, AbsLogStats};

/// `log c' − log c` per interior edge, where for the edge `(i, j)` with opposite vertices `k`
/// (left face) and `l` (right face) `c = (ℓ_il ℓ_jk)/(ℓ_lj ℓ_ki)` from the 3D edge lengths
/// and `c'` the same with `image_len(a, b)`, the image distance of vertices `a` and `b`.
/// Edges with a zero or non-finite image ratio are skipped.
pub fn cross_ratio_logs(mesh: &TriMesh, image_len: impl Fn(usize, usize) -> f64) -> Vec<f64> {
    let pos = mesh.positions();
    let len3 = |a: usize, b: usize| {
        let (p, q) = (pos[a], pos[b]);
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    let faces = mesh.faces();
    let opp = mesh.opposite_halfedges();
    let mut out = Vec::with_capacity(opp.len() / 2);
    for (h, &o) in opp.iter().enumerate() {
        if o == conformap_mesh::NO_HALFEDGE || (o as usize) < h {
            continue;
        }
        let (f, k) = (h / 3, h % 3);
        let (g, m) = (o as usize / 3, o as usize % 3);
        let i = faces[f][k] as usize;
        let j = faces[f][(k + 1) % 3] as usize;
        let kk = faces[f][(k + 2) % 3] as usize;
        let l = faces[g][(m + 2) % 3] as usize;
        let c = (len3(i, l) * len3(j, kk)) / (len3(l, j) * len3(kk, i));
        let ci = (image_len(i, l) * image_len(j, kk)) / (image_len(l, j) * image_len(kk, i));
        if ci > 0.0 && ci.is_finite() {
            out.push(ci.ln() - c.ln());
        }
    }
    out
}

/// The length cross-ratio distortion of a planar map (one value per vertex): mean and max
/// of `|log c' − log c|` over the interior edges (see [`cross_ratio_logs`]).
///
/// # Errors
/// [`MetricsError::LengthMismatch`], [`MetricsError::NonFiniteValue`],
/// [`MetricsError::ValueTooLarge`] for a map that is not one finite value per vertex.
///
/// # Examples
/// ```
/// use conformap_metrics::cross_ratio_distortion;
/// use num_complex::Complex64;
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// // a Möbius map of the plane leaves every cross-ratio as it was
/// let m = |z: Complex64| (2.0 * z + 1.0) / (0.3 * z + 2.0);
/// let map: Vec<Complex64> =
///     mesh.positions().iter().map(|p| m(Complex64::new(p[0], p[1]))).collect();
/// assert!(cross_ratio_distortion(&mesh, &map)?.max_abs < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn cross_ratio_distortion(
    mesh: &TriMesh,
    map: &[Complex64],
) -> Result<AbsLogStats, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    Ok(abs_log_stats(&cross_ratio_logs(mesh, |a, b| {
        (map[a] - map[b]).norm()
    })))
}
