//! Per-face distortion of a map, for pictures and custom statistics: the corner angle
//! differences, `|μ|` and the areas of one face, by the same formulas as
//! [`crate::planar_map_metrics`].

use conformap_mesh::{triangle_area, TriMesh};
use conformap_operators::{face_points, triangle_angles};
use num_complex::Complex64;

use crate::energy::{corners, twice_signed_area};
use crate::error::{check_map, MetricsError};
use crate::face::{image_angles, Chart};

/// The distortion of one face under a map: what [`crate::planar_map_metrics`] measures on
/// it before it sums over the faces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaceDistortion {
    /// `|mesh corner angle − image corner angle|` in degrees at the face's three corners
    /// (unsigned image angles, so a flipped face is measured like its mirror image).
    pub corner_angle_distortion_deg: [f64; 3],
    /// `|μ|` of the affine map from an isometric chart of the 3D face to its image: 0 for a
    /// similarity, `< 1` orientation-preserving, `> 1` flipped, at most
    /// [`crate::BELTRAMI_ABS_CAP`].
    pub beltrami_abs: f64,
    /// Area of the 3D face.
    pub mesh_area: f64,
    /// Signed area of the image face (negative when flipped).
    pub image_signed_area: f64,
}

impl FaceDistortion {
    /// Whether the image face is degenerate: signed area exactly zero or not finite (such a
    /// face has no image shape; [`crate::planar_map_metrics`] leaves it out of the angle,
    /// Beltrami and area statistics).
    #[inline]
    pub fn degenerate(&self) -> bool {
        !(self.image_signed_area.abs() > 0.0 && self.image_signed_area.is_finite())
    }

    /// Whether the image face is flipped (negative signed area).
    #[inline]
    pub fn flipped(&self) -> bool {
        self.image_signed_area < 0.0
    }

    /// Mean of the three corner angle distortions, in degrees.
    #[inline]
    pub fn mean_angle_distortion_deg(&self) -> f64 {
        self.corner_angle_distortion_deg.iter().sum::<f64>() / 3.0
    }
}

/// The distortion of the 3D triangle `p` mapped onto the planar triangle `image` (corner `k`
/// to `image[k]`). Inputs are assumed finite and `p` non-degenerate (every face of a
/// validated mesh is).
///
/// # Examples
/// ```
/// use conformap_metrics::face_distortion;
/// use num_complex::Complex64;
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
/// // a rotation and scaling by 2: conformal, four times the area
/// let s = Complex64::new(0.0, 2.0);
/// let image = p.map(|q| s * Complex64::new(q[0], q[1]));
/// let d = face_distortion(p, image);
/// assert!(d.beltrami_abs < 1e-15 && d.mean_angle_distortion_deg() < 1e-12);
/// assert!((d.image_signed_area - 4.0 * d.mesh_area).abs() < 1e-15 && !d.flipped());
/// ```
pub fn face_distortion(p: [[f64; 3]; 3], image: [Complex64; 3]) -> FaceDistortion {
    let mesh_angles = triangle_angles(p);
    let img_angles = image_angles(image);
    let mut corner = [0.0; 3];
    for k in 0..3 {
        corner[k] = (mesh_angles[k] - img_angles[k]).abs().to_degrees();
    }
    FaceDistortion {
        corner_angle_distortion_deg: corner,
        beltrami_abs: Chart::new(p).beltrami_abs(image),
        mesh_area: triangle_area(p[0], p[1], p[2]),
        image_signed_area: 0.5 * twice_signed_area(image),
    }
}

/// [`face_distortion`] of every face of `mesh` under the per-vertex planar map `map`, in
/// face order. The map is scored as given: a mirrored map has every face flipped (see
/// [`crate::planar_map_metrics`] for the orientation fix of the summary).
///
/// # Errors
/// [`MetricsError::LengthMismatch`], [`MetricsError::NonFiniteValue`],
/// [`MetricsError::ValueTooLarge`]: `map` is not one finite, moderate value per vertex.
pub fn face_distortions(
    mesh: &TriMesh,
    map: &[Complex64],
) -> Result<Vec<FaceDistortion>, MetricsError> {
    check_map(mesh.num_vertices(), map)?;
    Ok(mesh
        .faces()
        .iter()
        .enumerate()
        .map(|(f, &t)| face_distortion(face_points(mesh, f), corners(map, t)))
        .collect())
}

/// An isometric, orientation-preserving chart of the 3D triangle `p`: `p0 ↦ 0`, `p1` on
/// the positive real axis, `p2` in the upper half-plane (for a non-degenerate triangle).
/// Lets a map into 3D (e.g. the chord triangles of a sphere map) be judged by
/// [`face_distortion`].
#[inline]
pub fn isometric_chart(p: [[f64; 3]; 3]) -> [Complex64; 3] {
    let c = Chart::new(p);
    [
        Complex64::new(0.0, 0.0),
        Complex64::new(c.w1(), 0.0),
        c.w2(),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{planar_map_metrics, MetricsOptions};

    #[test]
    fn agrees_with_the_summary() {
        let mesh = TriMesh::try_new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.2],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.3],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .expect("valid square");
        let map: Vec<Complex64> = mesh
            .positions()
            .iter()
            .map(|p| Complex64::new(p[0] + 0.3 * p[1] * p[1], p[1]))
            .collect();
        let faces = face_distortions(&mesh, &map).expect("valid map");
        let m = planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT).expect("valid map");
        let max_angle = faces
            .iter()
            .flat_map(|d| d.corner_angle_distortion_deg)
            .fold(0.0, f64::max);
        let max_mu = faces.iter().map(|d| d.beltrami_abs).fold(0.0, f64::max);
        assert!((max_angle - m.angle_distortion_deg.max).abs() < 1e-12);
        assert!((max_mu - m.beltrami_abs.max).abs() < 1e-15);
        let area: f64 = faces.iter().map(|d| d.image_signed_area).sum();
        assert!((area - m.image_area).abs() < 1e-15);
    }

    #[test]
    fn chart_keeps_lengths_and_orientation() {
        let p = [[0.1, 0.2, 0.3], [1.3, 0.4, -0.2], [0.5, 1.1, 0.9]];
        let w = isometric_chart(p);
        let d = face_distortion(p, w);
        assert!(d.beltrami_abs < 1e-15);
        assert!((d.image_signed_area - d.mesh_area).abs() < 1e-15);
        assert!(w[2].im > 0.0);
    }
}
