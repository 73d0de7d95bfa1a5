//! The double covering of a disk mesh (Jin et al. 2004, §3.1): two copies glued along the
//! boundary, the second reversed, form a closed symmetric genus-0 surface; its sphere map,
//! made symmetric, sends each copy to a hemisphere, and stereographic projection of the
//! first hemisphere is a disk map — a second route to the disk, independent of CEM.

use std::time::Instant;

use conformap_mesh::{Topology, TriMesh};
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::mobius::maps::boost_sphere_point;
use crate::sphere::map::{sphere_map, SphereOptions};
use crate::sphere::source::{centre_vertex, regular_face_around};
use crate::{SphereError, SphereReport};
use conformap_operators::vec3::{cross, dot, normalize};

/// A double covering of a disk mesh.
///
/// Vertex ids: `0..split_vertices` are the (split) input mesh — the input's vertices keep
/// their ids `0..original_vertices`, followed by one midpoint per split edge — and
/// `split_vertices..` are the second copies of its interior vertices. Faces: the split
/// mesh's, then their reversed second copies.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct DoubleCover {
    /// The closed, symmetric mesh (genus 0).
    pub mesh: TriMesh,
    /// Vertices of the input mesh.
    pub original_vertices: usize,
    /// Vertices of the input after splitting the interior edges that join two boundary
    /// vertices (which would otherwise become non-manifold edges of the covering).
    pub split_vertices: usize,
    /// For each covering vertex, its mirror image in the other copy (boundary vertices are
    /// their own mirror).
    pub mirror: Vec<u32>,
    /// Number of interior edges split.
    pub split_edges: usize,
}

/// Builds the double covering of a disk mesh. Interior edges whose two ends are both on the
/// boundary are split at their midpoints first (each adds a vertex and turns its two faces
/// into four): glued, such an edge would lie on four faces.
///
/// # Errors
/// [`SphereError::WrongTopology`] unless the mesh is a disk; [`SphereError::Mesh`] if the
/// covering fails validation.
///
/// # Examples
/// ```
/// use conformap_sphere::double_cover;
/// let disk = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, -1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]],
/// )?;
/// let dc = double_cover(&disk)?;
/// assert_eq!(dc.mesh.num_vertices(), 6); // 4 boundary vertices + 2 copies of the centre
/// assert_eq!(dc.mesh.topology(), conformap_mesh::Topology::Sphere);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
pub fn double_cover(mesh: &TriMesh) -> Result<DoubleCover, SphereError> {
    let found = mesh.topology();
    if found != Topology::Disk {
        return Err(SphereError::WrongTopology {
            operation: "a double covering",
            expected: "a disk (genus 0, one boundary loop)",
            found,
        });
    }
    build_double_cover(mesh)
}

/// The double covering of any connected surface with boundary (genus `g`, `b ≥ 1` loops):
/// two copies glued along all boundary loops, the second reversed — a closed surface of
/// genus `2g + b − 1` (Jin et al. 2004, §3.1; the higher-genus route for surfaces with
/// boundary). Same vertex and face numbering as [`double_cover`].
///
/// # Errors
/// [`SphereError::WrongTopology`] unless the mesh is connected with at least one boundary
/// loop; [`SphereError::Mesh`] if the covering fails validation.
pub fn double_cover_surface(mesh: &TriMesh) -> Result<DoubleCover, SphereError> {
    if mesh.num_components() != 1 || mesh.boundary_loops().is_empty() {
        return Err(SphereError::WrongTopology {
            operation: "a double covering",
            expected: "a connected surface with at least one boundary loop",
            found: mesh.topology(),
        });
    }
    build_double_cover(mesh)
}

/// Glues two copies of `mesh` along all its boundary loops.
fn build_double_cover(mesh: &TriMesh) -> Result<DoubleCover, SphereError> {
    let (positions, faces, split_edges) = split_boundary_chords(mesh);
    let n = positions.len();
    let mut is_boundary = vec![false; n];
    for l in mesh.boundary_loops() {
        for &v in l {
            is_boundary[v as usize] = true;
        }
    }
    let mut copy = vec![0u32; n];
    let mut all_positions = positions.clone();
    let mut mirror: Vec<u32> = (0..n as u32).collect();
    for v in 0..n {
        if is_boundary[v] {
            copy[v] = v as u32;
        } else {
            copy[v] = all_positions.len() as u32;
            mirror[v] = copy[v];
            all_positions.push(positions[v]);
            mirror.push(v as u32);
        }
    }
    let mut all_faces = faces.clone();
    all_faces.extend(faces.iter().map(|f| {
        [
            copy[f[2] as usize],
            copy[f[1] as usize],
            copy[f[0] as usize],
        ]
    }));
    let dc = TriMesh::try_new(all_positions, all_faces)?;
    Ok(DoubleCover {
        mesh: dc,
        original_vertices: mesh.num_vertices(),
        split_vertices: n,
        mirror,
        split_edges,
    })
}

/// Splits every interior edge with both ends on the boundary at its midpoint.
fn split_boundary_chords(mesh: &TriMesh) -> (Vec<[f64; 3]>, Vec<[u32; 3]>, usize) {
    let mut positions = mesh.positions().to_vec();
    let mut faces = mesh.faces().to_vec();
    let opp = mesh.opposite_halfedges();
    let bnd = mesh.boundary_flags();
    // midpoint vertex of each split edge, keyed by its smaller half-edge
    let mut mid = std::collections::HashMap::new();
    for (h, &o) in opp.iter().enumerate() {
        if o == conformap_mesh::NO_HALFEDGE || (o as usize) < h {
            continue;
        }
        let (a, b) = mesh.halfedge_vertices(h);
        if bnd[a as usize] && bnd[b as usize] {
            let (pa, pb) = (positions[a as usize], positions[b as usize]);
            mid.insert(h, positions.len() as u32);
            mid.insert(o as usize, positions.len() as u32);
            positions.push([
                0.5 * (pa[0] + pb[0]),
                0.5 * (pa[1] + pb[1]),
                0.5 * (pa[2] + pb[2]),
            ]);
        }
    }
    let split = mid.len() / 2;
    if split == 0 {
        return (positions, faces, 0);
    }
    // re-triangulate each face by its split edges (a face can have up to 3)
    let mut out = Vec::with_capacity(faces.len() + 2 * split);
    for (f, t) in faces.drain(..).enumerate() {
        let m: [Option<u32>; 3] = [0, 1, 2].map(|k| mid.get(&(3 * f + k)).copied());
        fan_split(t, m, &mut out);
    }
    (positions, out, split)
}

/// Triangulates face `t` whose edge `k` (from `t[k]` to `t[k+1]`) may carry midpoint `m[k]`.
fn fan_split(t: [u32; 3], m: [Option<u32>; 3], out: &mut Vec<[u32; 3]>) {
    // the polygon t0 (m0) t1 (m1) t2 (m2), triangulated as a fan from a midpoint if any
    let mut poly = Vec::with_capacity(6);
    for k in 0..3 {
        poly.push(t[k]);
        if let Some(v) = m[k] {
            poly.push(v);
        }
    }
    let start = (0..3)
        .find_map(|k| m[k])
        .and_then(|v| poly.iter().position(|&p| p == v));
    let s = start.unwrap_or(0);
    let len = poly.len();
    for i in 1..len - 1 {
        out.push([poly[s], poly[(s + i) % len], poly[(s + i + 1) % len]]);
    }
}

/// A disk map obtained through the double covering.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct DoubleCoverDisk {
    /// One value per input vertex, in the closed unit disk; boundary vertices on the circle.
    pub map: Vec<Complex64>,
    /// What was done.
    pub report: DoubleCoverReport,
}

/// How a double-cover disk map was made.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct DoubleCoverReport {
    /// Vertices of the covering.
    pub cover_vertices: usize,
    /// Interior edges split before gluing.
    pub split_edges: usize,
    /// The sphere map of the covering.
    pub sphere: SphereReport,
    /// Largest distance of a boundary point from the fitted plane of the boundary's image
    /// (before it is moved to the equator): how far the boundary is from a circle.
    pub boundary_plane_residual: f64,
    /// Largest `|z₁ − z₂|` between a vertex's disk value from the first copy and the
    /// reflected value from its mirror in the second copy: how symmetric the covering's
    /// sphere map is.
    pub symmetry_defect_max: f64,
    /// Largest `||z| − 1|` of the boundary before it was projected onto the circle.
    pub circle_residual_max: f64,
    /// Signed turns of the projected boundary around the circle: 1 when its order is kept
    /// (every step between consecutive boundary vertices turns counter-clockwise by less
    /// than π); anything else means crossing boundary vertices.
    pub boundary_winding: f64,
    /// Largest `|z_harmonic − z_cover|` over interior vertices: how far the harmonic
    /// extension moved the covering's own interior values.
    pub interior_change_max: f64,
    /// Wall-clock milliseconds, all stages.
    pub time_ms: f64,
}

/// The disk map of a disk mesh through its double covering (Jin et al. 2004, §3.1):
/// 1. [`double_cover`], then [`sphere_map`] of the covering, with the dipole at the centre
///    of the first copy (see [`crate::sphere_source_face`]);
/// 2. the boundary's image (a circle on the sphere, up to discretization) is fitted by the
///    plane `n·x = d` of least squares, and the boost along `n` that moves that plane to
///    `n·x = 0` is applied (a Möbius map, so still conformal); a rotation then takes `n` to
///    the pole on the second copy's side, so the first copy fills the southern hemisphere;
/// 3. `z = conj τ(x) = (x − iy)/(1 − z)` maps the southern hemisphere onto the unit disk
///    with the orientation of the mesh. The boundary values are divided by their modulus
///    (the circle residual is reported), and the interior is their harmonic extension
///    (CEM Eq. 10) — a conformal map is the harmonic extension of its boundary values, and
///    this keeps the covering's small asymmetries (reported) from folding the tiny
///    triangles of crowded limbs. CEM's boundary iteration is not used: the boundary comes
///    from the covering alone.
///
/// # Errors
/// As [`double_cover`] and [`sphere_map`]; [`SphereError::Operator`] if the disk's
/// interior Laplacian cannot be factored.
///
/// # Examples
/// ```
/// use conformap_sphere::{double_cover_disk_map, SphereOptions};
/// # let mesh = conformap_testkit::flat_disk(6, 12);
/// // a flat disk mesh: its conformal map is a disk automorphism, which keeps every angle
/// let out = double_cover_disk_map(&mesh, &SphereOptions::DEFAULT)?;
/// for &v in &mesh.boundary_loops()[0] {
///     assert!((out.map[v as usize].norm() - 1.0).abs() < 1e-12);
/// }
/// assert!(out.report.symmetry_defect_max < 1e-2);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
pub fn double_cover_disk_map(
    mesh: &TriMesh,
    options: &SphereOptions,
) -> Result<DoubleCoverDisk, SphereError> {
    let t0 = Instant::now();
    let dc = double_cover(mesh)?;
    // the dipole goes at the centre of the first copy, away from the fold
    let mut options = *options;
    if options.source_face.is_none() {
        let first_copy_faces = dc.mesh.num_faces() / 2;
        let centre = centre_vertex(mesh);
        options.source_face = Some(regular_face_around(&dc.mesh, centre, first_copy_faces));
    }
    let sm = sphere_map(&dc.mesh, &options)?;
    let boundary = &mesh.boundary_loops()[0];
    let bpts: Vec<[f64; 3]> = boundary.iter().map(|&v| sm.points[v as usize]).collect();
    let (mut n, mut d, residual) = fit_plane(&bpts);
    // orient n towards the second copy
    let second_mean: f64 = (dc.split_vertices..dc.mesh.num_vertices())
        .map(|v| dot(n, sm.points[v]) - d)
        .sum();
    if second_mean < 0.0 {
        n = [-n[0], -n[1], -n[2]];
        d = -d;
    }
    // boost along n moving the plane n·x = d to n·x = 0: α = s n with d s² − 2 s + d = 0
    let s = if d.abs() < 1e-300 {
        0.0
    } else {
        (1.0 - (1.0 - d * d).max(0.0).sqrt()) / d
    };
    let t = 2.0 * s.clamp(-1.0 + 1e-16, 1.0 - 1e-16).atanh();
    let u = [t * n[0], t * n[1], t * n[2]];
    // frame (e1, e2, n), right-handed: coordinates in it are a rotation taking n to +z
    let e1 = normalize(if n[0].abs() < 0.9 {
        cross(n, [1.0, 0.0, 0.0])
    } else {
        cross(n, [0.0, 1.0, 0.0])
    });
    let e2 = cross(n, e1);
    let moved: Vec<[f64; 3]> = sm
        .points
        .iter()
        .map(|&x| {
            let y = normalize(boost_sphere_point(u, x));
            [dot(e1, y), dot(e2, y), dot(n, y)]
        })
        .collect();
    let chart = |p: [f64; 3]| Complex64::new(p[0], -p[1]) / (1.0 - p[2]);
    let mut map: Vec<Complex64> = (0..mesh.num_vertices()).map(|v| chart(moved[v])).collect();
    // orientation: the boundary loop must run counter-clockwise
    let conj = conformap_disk::polygon_area_of(boundary, &map) < 0.0;
    let chart2 = |p: [f64; 3]| {
        let z = chart([p[0], p[1], -p[2]]);
        if conj {
            z.conj()
        } else {
            z
        }
    };
    if conj {
        for z in &mut map {
            *z = z.conj();
        }
    }
    let mut defect = 0.0f64;
    let mut circle = 0.0f64;
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) {
            circle = circle.max((map[v].norm() - 1.0).abs());
        } else {
            let z2 = chart2(moved[dc.mirror[v] as usize]);
            defect = defect.max((map[v] - z2).norm());
        }
    }
    if let Some(v) = map
        .iter()
        .position(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        return Err(SphereError::NonFinite {
            vertex: v,
            stage: "double-cover projection",
        });
    }
    // boundary: the angles of the covering's map; interior: their harmonic extension
    let problem = conformap_disk::DiskProblem::new(mesh).map_err(disk_error)?;
    let fb: Vec<Complex64> = boundary
        .iter()
        .map(|&v| map[v as usize] / map[v as usize].norm())
        .collect();
    let turns = winding(&fb);
    let extended = problem.harmonic_extension(&fb);
    let interior_change = (0..mesh.num_vertices())
        .filter(|&v| !mesh.is_boundary_vertex(v))
        .map(|v| (extended[v] - map[v]).norm())
        .fold(0.0, f64::max);
    Ok(DoubleCoverDisk {
        map: extended,
        report: DoubleCoverReport {
            cover_vertices: dc.mesh.num_vertices(),
            split_edges: dc.split_edges,
            sphere: sm.report,
            boundary_plane_residual: residual,
            symmetry_defect_max: defect,
            circle_residual_max: circle,
            boundary_winding: turns,
            interior_change_max: interior_change,
            time_ms: t0.elapsed().as_secs_f64() * 1e3,
        },
    })
}

/// Least-squares plane `n·x = d` through points (`|n| = 1`): `n` is the eigenvector of the
/// smallest eigenvalue of the covariance (found by inverse power iteration on the 3 × 3
/// matrix), `d = n·centroid`. Returns `(n, d, max |n·x − d|)`.
fn fit_plane(pts: &[[f64; 3]]) -> ([f64; 3], f64, f64) {
    let m = pts.len().max(1) as f64;
    let mut c = [0.0; 3];
    for p in pts {
        for k in 0..3 {
            c[k] += p[k] / m;
        }
    }
    let mut cov = [[0.0; 3]; 3];
    for p in pts {
        let q = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
        for i in 0..3 {
            for j in 0..3 {
                cov[i][j] += q[i] * q[j];
            }
        }
    }
    let n = smallest_eigenvector(cov);
    let d = dot(n, c);
    let res = pts
        .iter()
        .map(|p| (dot(n, *p) - d).abs())
        .fold(0.0, f64::max);
    (n, d, res)
}

/// Unit eigenvector of the smallest eigenvalue of a symmetric positive semidefinite 3 × 3
/// matrix, by Jacobi rotations (exact to rounding; 3 × 3 converges in a few sweeps).
fn smallest_eigenvector(mut a: [[f64; 3]; 3]) -> [f64; 3] {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    // Jacobi sweeps: each rotation zeroes one off-diagonal entry; 50 sweeps is far more
    // than a 3 × 3 matrix needs (quadratic convergence after the first sweep)
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let diag = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-300 || off <= 1e-18 * diag {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q].abs() <= 1e-300 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let cs = 1.0 / (t * t + 1.0).sqrt();
            let sn = t * cs;
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = cs * akp - sn * akq;
                a[k][q] = sn * akp + cs * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = cs * apk - sn * aqk;
                a[q][k] = sn * apk + cs * aqk;
            }
            for k in 0..3 {
                let (vkp, vkq) = (v[k][p], v[k][q]);
                v[k][p] = cs * vkp - sn * vkq;
                v[k][q] = sn * vkp + cs * vkq;
            }
        }
    }
    let k = (0..3)
        .min_by(|&i, &j| a[i][i].total_cmp(&a[j][j]))
        .unwrap_or(0);
    normalize([v[0][k], v[1][k], v[2][k]])
}

/// The disk crate's errors that [`conformap_disk::DiskProblem::new`] can raise on a disk.
fn disk_error(e: conformap_disk::DiskError) -> SphereError {
    match e {
        conformap_disk::DiskError::Operator(o) => SphereError::Operator(o),
        _ => SphereError::NonFinite {
            vertex: 0,
            stage: "disk problem of the double covering",
        },
    }
}

/// Total signed turning of the closed polygon `z` around the origin, in turns.
fn winding(z: &[Complex64]) -> f64 {
    let m = z.len();
    let mut total = 0.0;
    for k in 0..m {
        total += (z[(k + 1) % m] / z[k]).arg();
    }
    total / std::f64::consts::TAU
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_finds_the_normal() {
        let pts: Vec<[f64; 3]> = (0..20)
            .map(|k| {
                let t = k as f64 * 0.31;
                // the circle at height 0.3 around the axis (1, 1, 1)/√3, tilted
                let n = normalize([1.0, 1.0, 1.0]);
                let e1 = normalize(cross(n, [1.0, 0.0, 0.0]));
                let e2 = cross(n, e1);
                let r = (1.0 - 0.09f64).sqrt();
                [0, 1, 2].map(|i| 0.3 * n[i] + r * (t.cos() * e1[i] + t.sin() * e2[i]))
            })
            .collect();
        let (n, d, res) = fit_plane(&pts);
        let expect = normalize([1.0, 1.0, 1.0]);
        assert!((dot(n, expect).abs() - 1.0).abs() < 1e-12);
        assert!((d.abs() - 0.3).abs() < 1e-12 && res < 1e-12);
    }

    #[test]
    fn chords_are_split_before_gluing() {
        // a fan of 4 triangles around vertex 0 plus an ear (1, 2, 5) whose edge 1–2 becomes
        // interior with both ends on the boundary
        let mesh = TriMesh::try_new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, 0.0],
                [-1.0, 0.0, 0.0],
                [0.0, -1.0, 0.0],
                [1.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1], [1, 5, 2]],
        )
        .unwrap();
        let dc = double_cover(&mesh).unwrap();
        assert_eq!(dc.split_edges, 1);
        assert_eq!(dc.mesh.topology(), Topology::Sphere);
        // 6 vertices + 1 midpoint; interior: 0 and the midpoint, each copied once
        assert_eq!(dc.mesh.num_vertices(), 9);
        for (v, &m) in dc.mirror.iter().enumerate() {
            assert_eq!(dc.mirror[m as usize] as usize, v);
        }
    }
}
