//! The cheap building blocks: Dirichlet energy, image area and conformal energy
//! (CEM Eq. 5–8). Solvers may call them on every iterate.

use conformap_mesh::TriMesh;
use conformap_operators::{face_points, triangle_cotangents};
use num_complex::Complex64;

use crate::error::{check_map, MetricsError};

/// `Σ_k (cot θ_k / 4) |f_i − f_j|²` over the three edges of one face, edge `(i, j)` opposite
/// corner `k`: this face's share of `½ fᴴ L f`.
#[inline]
pub(crate) fn face_dirichlet(cot: [f64; 3], f: [Complex64; 3]) -> f64 {
    let mut e = 0.0;
    for k in 0..3 {
        e += cot[k] * (f[(k + 1) % 3] - f[(k + 2) % 3]).norm_sqr();
    }
    0.25 * e
}

/// Twice the signed area of the image triangle `(f0, f1, f2)` (positive if counter-clockwise).
#[inline]
pub(crate) fn twice_signed_area(f: [Complex64; 3]) -> f64 {
    let (d1, d2) = (f[1] - f[0], f[2] - f[0]);
    d1.re * d2.im - d1.im * d2.re
}

/// The map values at the corners of face `t`.
#[inline]
pub(crate) fn corners(map: &[Complex64], t: [u32; 3]) -> [Complex64; 3] {
    [map[t[0] as usize], map[t[1] as usize], map[t[2] as usize]]
}

/// Dirichlet energy `E_D(f) = ½ fᴴ L f` of the piecewise-linear map `f` (CEM Eq. 5), with the
/// mesh's cotangent weights and the boundary convention of
/// [`conformap_operators::cotan_laplacian`] (CEM Eq. 6: a boundary edge gets half its single
/// cotangent). Computed face by face as `Σ_faces Σ_k (cot θ_k / 4) |f_i − f_j|²` (edge `(i, j)`
/// opposite corner `k`), which equals `½ fᴴ L f` without assembling `L`.
///
/// # Errors
/// [`MetricsError`] if `map` does not have one finite value per vertex.
///
/// # Examples
/// ```
/// // the identity map of a planar mesh has E_D = its area
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// let f: Vec<_> = mesh.positions().iter().map(|p| num_complex::Complex64::new(p[0], p[1])).collect();
/// let e = conformap_metrics::dirichlet_energy(&mesh, &f)?;
/// assert!((e - 2.0).abs() < 1e-14);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn dirichlet_energy(mesh: &TriMesh, map: &[Complex64]) -> Result<f64, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    Ok(dirichlet_unchecked(mesh, map))
}

pub(crate) fn dirichlet_unchecked(mesh: &TriMesh, map: &[Complex64]) -> f64 {
    mesh.faces()
        .iter()
        .enumerate()
        .map(|(f, &t)| face_dirichlet(triangle_cotangents(face_points(mesh, f)), corners(map, t)))
        .sum()
}

/// Signed image area `A(f)` (CEM Eq. 8): `Σ ½ (u_i v_j − u_j v_i)` over every boundary
/// half-edge `(i, j)`, each loop followed in the mesh's orientation (surface on the left).
/// The outer loop then counts positively and holes negatively, so `A` is the area enclosed by
/// the image of the outer loop minus the areas of the holes. For a closed mesh (no boundary)
/// it is the sum of the signed image face areas.
///
/// Positive for an orientation-preserving map, negative for a mirrored one; no orientation
/// fix is applied here (contrast [`crate::planar_map_metrics`]). Each loop is summed relative
/// to its first vertex, which leaves the value unchanged but keeps round-off small for maps
/// far from the origin.
///
/// # Errors
/// [`MetricsError`] if `map` does not have one finite value per vertex.
pub fn image_area(mesh: &TriMesh, map: &[Complex64]) -> Result<f64, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    Ok(image_area_unchecked(mesh, map))
}

pub(crate) fn image_area_unchecked(mesh: &TriMesh, map: &[Complex64]) -> f64 {
    let loops = mesh.boundary_loops();
    if loops.is_empty() {
        let twice: f64 = mesh
            .faces()
            .iter()
            .map(|&t| twice_signed_area(corners(map, t)))
            .sum();
        return 0.5 * twice;
    }
    let mut twice = 0.0;
    for lp in loops {
        let origin = map[lp[0] as usize];
        let n = lp.len();
        for k in 1..n - 1 {
            let a = map[lp[k] as usize] - origin;
            let b = map[lp[k + 1] as usize] - origin;
            twice += a.re * b.im - b.re * a.im;
        }
    }
    0.5 * twice
}

/// Conformal energy `E_C(f) = E_D(f) − A(f)` (CEM Eq. 7), from [`dirichlet_energy`] and
/// [`image_area`]. Zero exactly for a conformal (orientation-preserving) map and positive
/// otherwise; a mirrored map scores `E_D + |A|`, which is what a solver minimizing it wants.
/// [`crate::planar_map_metrics`] instead conjugates a mirrored map first.
///
/// # Errors
/// [`MetricsError`] if `map` does not have one finite value per vertex.
///
/// # Examples
/// ```
/// use conformap_metrics::conformal_energy;
/// use num_complex::Complex64;
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// // a similarity z ↦ (1 + 2i) z + 3 is conformal
/// let a = Complex64::new(1.0, 2.0);
/// let f: Vec<_> = mesh.positions().iter().map(|p| a * Complex64::new(p[0], p[1]) + 3.0).collect();
/// assert!(conformal_energy(&mesh, &f)?.abs() < 1e-13);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn conformal_energy(mesh: &TriMesh, map: &[Complex64]) -> Result<f64, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    Ok(dirichlet_unchecked(mesh, map) - image_area_unchecked(mesh, map))
}
