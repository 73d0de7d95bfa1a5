//! The area energies of Jin et al. 2004 (Eq. 1–4, 7, 8, 10) for a sphere or disk map:
//! uniformity and the image-area share of an emphasized region.
//!
//! Both compare normalized areas: a face's *image share* `a_f = A_f / Σ A` (its image area
//! over the whole image area) and its *surface share* `s_f = S_f / Σ S` (its 3D area over
//! the surface area). Normalizing both sides is the constraint of Eq. 2/6 (parameter area =
//! surface area) written scale-free, so energies are comparable across meshes and units.
//! Image areas are those of the straight triangles through the image points: chord
//! triangles on the sphere, planar triangles in the disk.

use conformap_mesh::TriMesh;
use conformap_operators::face_areas;
use num_complex::Complex64;

use crate::SphereError;
use conformap_operators::planar::triangle_signed_area;
use conformap_operators::vec3::{cross, norm, sub};

/// Area of the chord triangle `(p0, p1, p2)`.
#[inline]
pub(crate) fn chord_area(p: [[f64; 3]; 3]) -> f64 {
    0.5 * norm(cross(sub(p[1], p[0]), sub(p[2], p[0])))
}

/// Signed area of the planar triangle `(z0, z1, z2)` (positive counter-clockwise).
#[inline]
pub(crate) fn planar_signed_area(z: [Complex64; 3]) -> f64 {
    triangle_signed_area(z[0], z[1], z[2])
}

/// The surface shares `s_f = S_f / Σ S` of the faces of `mesh`.
pub fn surface_shares(mesh: &TriMesh) -> Vec<f64> {
    let areas = face_areas(mesh);
    let total: f64 = areas.iter().sum();
    areas.iter().map(|a| a / total).collect()
}

/// The uniformity energy `E = Σ_f (a_f − s_f)²` (Jin et al. 2004, Eq. 7 with the normalization
/// of Eq. 2; §3.4 for the sphere): 0 when every face keeps its share of the area, and
/// unchanged by rotations. `image`: the image area of each face ([`sphere_face_areas`],
/// [`planar_face_areas`]); `shares`: its surface share ([`surface_shares`]).
pub fn uniformity_from_areas(image: &[f64], shares: &[f64]) -> f64 {
    let total: f64 = image.iter().sum();
    image
        .iter()
        .zip(shares)
        .map(|(a, s)| {
            let d = a / total - s;
            d * d
        })
        .sum()
}

/// The uniformity energy `Σ_f (a_f − s_f)²` of a sphere map (`points[v]` = image of vertex
/// `v`; Jin et al. 2004, Eq. 7 with Eq. 2, §3.4): `a_f` is face `f`'s chord-triangle area over
/// the total, `s_f` its 3D area over the surface area (see [`surface_shares`]).
///
/// # Errors
/// [`SphereError::MapLength`] if `points` does not have one entry per vertex.
pub fn sphere_uniformity_energy(mesh: &TriMesh, points: &[[f64; 3]]) -> Result<f64, SphereError> {
    check_len(mesh, points.len())?;
    let image = chord_areas(mesh, points);
    Ok(uniformity_from_areas(&image, &surface_shares(mesh)))
}

/// The uniformity energy `Σ_f (a_f − s_f)²` of a planar (disk) map, with `a_f` the unsigned
/// image triangle area over the total (Jin et al. 2004, Eq. 7 with Eq. 2).
///
/// # Errors
/// [`SphereError::MapLength`] if `map` does not have one entry per vertex.
pub fn disk_uniformity_energy(mesh: &TriMesh, map: &[Complex64]) -> Result<f64, SphereError> {
    check_len(mesh, map.len())?;
    let image = planar_areas(mesh, map);
    Ok(uniformity_from_areas(&image, &surface_shares(mesh)))
}

/// The share of the image area that the faces flagged in `region` get:
/// `Σ_{f ∈ D} A_f / Σ_f A_f` (Jin et al. 2004, Eq. 8/10 divided by the fixed total).
pub(crate) fn region_share_from_areas(image: &[f64], region: &[bool]) -> f64 {
    let total: f64 = image.iter().sum();
    let inside: f64 = image
        .iter()
        .zip(region)
        .filter(|(_, &r)| r)
        .map(|(a, _)| a)
        .sum();
    inside / total
}

/// Chord triangle areas of a sphere map (`points[v]` = image of vertex `v`), per face.
///
/// # Errors
/// [`SphereError::MapLength`] if `points` does not have one entry per vertex.
pub fn sphere_face_areas(mesh: &TriMesh, points: &[[f64; 3]]) -> Result<Vec<f64>, SphereError> {
    check_len(mesh, points.len())?;
    Ok(chord_areas(mesh, points))
}

/// Unsigned planar triangle areas of a planar map (`map[v]` = image of vertex `v`), per
/// face.
///
/// # Errors
/// [`SphereError::MapLength`] if `map` does not have one entry per vertex.
pub fn planar_face_areas(mesh: &TriMesh, map: &[Complex64]) -> Result<Vec<f64>, SphereError> {
    check_len(mesh, map.len())?;
    Ok(planar_areas(mesh, map))
}

/// [`sphere_face_areas`] of a map of the right length.
pub(crate) fn chord_areas(mesh: &TriMesh, points: &[[f64; 3]]) -> Vec<f64> {
    mesh.faces()
        .iter()
        .map(|t| chord_area(t.map(|v| points[v as usize])))
        .collect()
}

/// [`planar_face_areas`] of a map of the right length.
pub(crate) fn planar_areas(mesh: &TriMesh, map: &[Complex64]) -> Vec<f64> {
    mesh.faces()
        .iter()
        .map(|t| planar_signed_area(t.map(|v| map[v as usize])).abs())
        .collect()
}

/// The share of the image area taken by the faces of `region` under a sphere map.
///
/// # Errors
/// [`SphereError::MapLength`] for a map of the wrong length; the region errors of
/// [`region_mask`].
pub fn sphere_region_share(
    mesh: &TriMesh,
    points: &[[f64; 3]],
    region: &[usize],
) -> Result<f64, SphereError> {
    check_len(mesh, points.len())?;
    let mask = region_mask(mesh.num_faces(), region)?;
    Ok(region_share_from_areas(&chord_areas(mesh, points), &mask))
}

/// The share of the image area taken by the faces of `region` under a planar map.
///
/// # Errors
/// As [`sphere_region_share`].
pub fn disk_region_share(
    mesh: &TriMesh,
    map: &[Complex64],
    region: &[usize],
) -> Result<f64, SphereError> {
    check_len(mesh, map.len())?;
    let mask = region_mask(mesh.num_faces(), region)?;
    Ok(region_share_from_areas(&planar_areas(mesh, map), &mask))
}

/// A per-face flag of the faces listed in `region` (repeats allowed).
///
/// # Errors
/// [`SphereError::RegionFaceOutOfRange`] for an index `≥ faces`;
/// [`SphereError::DegenerateRegion`] if the region is empty or has every face.
pub fn region_mask(faces: usize, region: &[usize]) -> Result<Vec<bool>, SphereError> {
    let mut mask = vec![false; faces];
    for &f in region {
        if f >= faces {
            return Err(SphereError::RegionFaceOutOfRange { face: f, faces });
        }
        mask[f] = true;
    }
    let count = mask.iter().filter(|&&m| m).count();
    if count == 0 || count == faces {
        return Err(SphereError::DegenerateRegion {
            region: count,
            faces,
        });
    }
    Ok(mask)
}

pub(crate) fn check_len(mesh: &TriMesh, len: usize) -> Result<(), SphereError> {
    if len != mesh.num_vertices() {
        return Err(SphereError::MapLength {
            expected: mesh.num_vertices(),
            found: len,
        });
    }
    Ok(())
}
