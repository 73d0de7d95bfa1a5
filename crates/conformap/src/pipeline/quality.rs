//! `--quality-overlay FILE.shape.gii`: the map's quality at every vertex of the input, as
//! a GIfTI data file that neuroimaging viewers (FreeView, wb_view, nilearn) load as an
//! overlay on the input surface, staged with the command's other outputs.
//!
//! Two arrays, in the input's vertex order, by the formulas of the report's metrics
//! (`conformap-metrics`' per-face distortion):
//! - `angle_distortion_deg`: the mean over the vertex's corners of |mesh corner angle −
//!   image corner angle|, in degrees (the report's `angle_distortion_deg` is the same over
//!   all corners);
//! - `area_log_ratio`: ln of the vertex's share of the image area over its share of the
//!   mesh area (each face gives a third of its area to each corner): 0 where the map keeps
//!   area up to one global scale, positive where it enlarges.
//!
//! Sphere maps are measured on their chord triangles, seamed planar maps per face corner.
//! A vertex whose faces all have degenerate images gets NaN in both arrays.

use conformap_mesh::TriMesh;
use conformap_metrics::{face_distortion, isometric_chart};
use num_complex::Complex64;

use crate::failure::Failure;
use crate::pipeline::{PictureDomain, Solved, Staged, TexCoords};
use std::path::Path;

/// The names of the overlay's arrays (GIfTI `Name` metadata), in file order.
pub const QUALITY_ARRAYS: [&str; 2] = ["angle_distortion_deg", "area_log_ratio"];

/// The map's quality at every vertex (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct VertexQuality {
    /// Mean angle distortion of the vertex's corners, in degrees.
    pub angle_distortion_deg: Vec<f64>,
    /// ln(image area share / mesh area share) of the vertex.
    pub area_log_ratio: Vec<f64>,
}

/// Per-vertex sums over the faces around each vertex.
struct Sums {
    angle: Vec<f64>,
    corners: Vec<u32>,
    mesh_area: Vec<f64>,
    image_area: Vec<f64>,
}

/// The quality of `solved`'s map at the first `vertices` vertices of the mesh it maps
/// (`mesh`, or the refined mesh of a [`TexCoords::Refined`] result, whose first vertices
/// are the input's), the map read where the pictures read it (`domain`).
pub fn vertex_quality(
    mesh: &TriMesh,
    solved: &Solved,
    domain: PictureDomain,
    vertices: usize,
) -> VertexQuality {
    let mesh = match &solved.uv {
        TexCoords::Refined { mesh, .. } => mesh,
        _ => mesh,
    };
    let z = |t: [f64; 2]| Complex64::new(t[0], t[1]);
    let image = |f: usize| -> [Complex64; 3] {
        let face = mesh.faces()[f];
        match (domain, &solved.uv) {
            (PictureDomain::Sphere, _) => {
                let points = &solved.flat.0;
                isometric_chart(face.map(|v| points.get(v as usize).copied().unwrap_or_default()))
            }
            (PictureDomain::Plane, TexCoords::PerVertex(uv)) => {
                face.map(|v| z(uv.get(v as usize).copied().unwrap_or_default()))
            }
            (PictureDomain::Plane, TexCoords::PerCorner(uv) | TexCoords::Refined { uv, .. }) => {
                std::array::from_fn(|k| z(uv.corner(f, k)))
            }
        }
    };
    from_images(mesh, image, vertices)
}

/// [`vertex_quality`] of the map giving face `f` the image `image(f)`.
fn from_images(
    mesh: &TriMesh,
    image: impl Fn(usize) -> [Complex64; 3],
    vertices: usize,
) -> VertexQuality {
    let sums = accumulate(mesh, image);
    let (mesh_total, image_total) = (
        sums.mesh_area.iter().sum::<f64>(),
        sums.image_area.iter().sum::<f64>(),
    );
    let n = vertices.min(mesh.num_vertices());
    let mut quality = VertexQuality {
        angle_distortion_deg: Vec::with_capacity(n),
        area_log_ratio: Vec::with_capacity(n),
    };
    for v in 0..n {
        let measured = sums.corners[v] > 0 && sums.image_area[v] > 0.0;
        let (angle, area) = if measured {
            (
                sums.angle[v] / f64::from(sums.corners[v]),
                (sums.image_area[v] / image_total).ln() - (sums.mesh_area[v] / mesh_total).ln(),
            )
        } else {
            (f64::NAN, f64::NAN)
        };
        quality.angle_distortion_deg.push(angle);
        quality.area_log_ratio.push(area);
    }
    quality
}

/// Sums the corner angle distortions (faces with a non-degenerate image) and a third of
/// every face's mesh and image area at each of its vertices.
fn accumulate(mesh: &TriMesh, image: impl Fn(usize) -> [Complex64; 3]) -> Sums {
    let n = mesh.num_vertices();
    let mut sums = Sums {
        angle: vec![0.0; n],
        corners: vec![0; n],
        mesh_area: vec![0.0; n],
        image_area: vec![0.0; n],
    };
    let p = mesh.positions();
    for (f, face) in mesh.faces().iter().enumerate() {
        let d = face_distortion(face.map(|v| p[v as usize]), image(f));
        let measured = !d.degenerate();
        for (k, &v) in face.iter().enumerate() {
            let v = v as usize;
            sums.mesh_area[v] += d.mesh_area / 3.0;
            if measured {
                sums.image_area[v] += d.image_signed_area.abs() / 3.0;
                sums.angle[v] += d.corner_angle_distortion_deg[k];
                sums.corners[v] += 1;
            }
        }
    }
    sums
}

/// Computes the overlay of `solved` and stages it as `target` (GIfTI data arrays named
/// [`QUALITY_ARRAYS`], in the input's vertex order).
pub fn stage_quality(
    staged: &mut Staged,
    target: &Path,
    mesh: &TriMesh,
    solved: &Solved,
    domain: PictureDomain,
) -> Result<(), Failure> {
    let q = vertex_quality(mesh, solved, domain, mesh.num_vertices());
    staged.vertex_data(
        target,
        &[
            (QUALITY_ARRAYS[0], &q.angle_distortion_deg),
            (QUALITY_ARRAYS[1], &q.area_log_ratio),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square split into two triangles (z = 0), and a fifth vertex off to the side
    /// in a third triangle.
    fn mesh() -> TriMesh {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
        ];
        TriMesh::try_new(p, vec![[0, 1, 2], [0, 2, 3], [1, 4, 2]]).unwrap_or_else(|_| {
            unreachable!("a valid mesh");
        })
    }

    fn planar(mesh: &TriMesh, f: impl Fn([f64; 3]) -> Complex64) -> Vec<Complex64> {
        mesh.positions().iter().map(|&p| f(p)).collect()
    }

    fn quality(mesh: &TriMesh, map: &[Complex64]) -> VertexQuality {
        from_images(mesh, |f| mesh.faces()[f].map(|v| map[v as usize]), 4)
    }

    #[test]
    fn a_similarity_has_no_distortion_at_any_vertex() {
        let m = mesh();
        let s = Complex64::new(0.6, 0.8) * 3.0;
        let q = quality(&m, &planar(&m, |p| s * Complex64::new(p[0], p[1]) + 5.0));
        assert_eq!(q.angle_distortion_deg.len(), 4); // only the first `vertices`
        assert!(q.angle_distortion_deg.iter().all(|a| a.abs() < 1e-12));
        assert!(q.area_log_ratio.iter().all(|a| a.abs() < 1e-12));
    }

    #[test]
    fn a_stretch_distorts_angles_and_a_local_growth_shows_in_the_area_ratio() {
        let m = mesh();
        // x ↦ 2x: vertex 3's one corner, a right angle, stays 90°; vertex 0's two 45°
        // corners become atan(1/2) and atan(2): both off by atan(2) − 45°
        let q = quality(&m, &planar(&m, |p| Complex64::new(2.0 * p[0], p[1])));
        let d = (2.0f64.atan() - std::f64::consts::FRAC_PI_4).to_degrees();
        assert!(q.angle_distortion_deg[3].abs() < 1e-12);
        assert!((q.angle_distortion_deg[0] - d).abs() < 1e-12);
        // a uniform stretch keeps every area share
        assert!(q.area_log_ratio.iter().all(|a| a.abs() < 1e-12));
        // moving vertex 4 out doubles face [1, 4, 2]'s area: vertex 4 alone is in it
        let mut map = planar(&m, |p| Complex64::new(p[0], p[1]));
        map[4] = Complex64::new(3.0, 0.0);
        let all = from_images(&m, |f| m.faces()[f].map(|v| map[v as usize]), 5);
        let (mesh_share, image_share): (f64, f64) = ((0.5 / 3.0) / 1.5, (1.0 / 3.0) / 2.0);
        assert!((all.area_log_ratio[4] - (image_share / mesh_share).ln()).abs() < 1e-12);
        assert!(all.angle_distortion_deg[0].abs() < 1e-12 && all.angle_distortion_deg[4] > 1.0);
    }

    #[test]
    fn a_vertex_with_only_degenerate_images_is_nan() {
        let m = mesh();
        let mut map = planar(&m, |p| Complex64::new(p[0], p[1]));
        map[4] = map[1]; // face [1, 4, 2] collapses to a segment
        let q = from_images(&m, |f| m.faces()[f].map(|v| map[v as usize]), 5);
        assert!(q.angle_distortion_deg[4].is_nan() && q.area_log_ratio[4].is_nan());
        assert!(q.angle_distortion_deg[1].is_finite());
    }
}
