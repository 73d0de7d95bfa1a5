//! Curved analytic surfaces: an open cylinder, a torus of revolution and a round sphere.
//! Faces are counter-clockwise seen from outside (outward normals).

use std::collections::HashMap;
use std::f64::consts::PI;

use conformap_mesh::TriMesh;

use crate::grid::wrapped_grid_faces;
use crate::planar::build;

/// An open cylinder of radius `radius` around the z-axis, `0 ≤ z ≤ height`: `rings + 1`
/// circles of `sectors` vertices (circle `k` at `z = height · k / rings`, vertex `(j, k)` at
/// index `k · sectors + j`), quads split along a diagonal. Two boundary loops (the bottom and
/// top circles), χ = 0. Conformally an annulus of modulus `height / radius`.
///
/// # Panics
/// If `radius` or `height` is not positive, `rings == 0` or `sectors < 3`.
pub fn cylinder(radius: f64, height: f64, rings: usize, sectors: usize) -> TriMesh {
    assert!(
        radius > 0.0 && height > 0.0,
        "cylinder needs a positive size"
    );
    assert!(
        rings >= 1 && sectors >= 3,
        "cylinder needs rings ≥ 1 and sectors ≥ 3"
    );
    let mut positions = Vec::with_capacity((rings + 1) * sectors);
    for k in 0..=rings {
        let z = height * k as f64 / rings as f64;
        positions.extend((0..sectors).map(|j| {
            let t = 2.0 * PI * j as f64 / sectors as f64;
            [radius * t.cos(), radius * t.sin(), z]
        }));
    }
    build(
        "cylinder",
        positions,
        wrapped_grid_faces(sectors, rings + 1, true, false),
    )
}

/// A torus of revolution around the z-axis with tube centre radius `major` and tube radius
/// `minor`: vertex `(i, j)` (index `j · n_major + i`) at major angle `φ = 2π i / n_major` and
/// minor angle `θ = 2π j / n_minor`,
/// `((major + minor cos θ) cos φ, (major + minor cos θ) sin φ, minor sin θ)`.
/// Closed, genus 1, χ = 0.
///
/// # Panics
/// If not `0 < minor < major`, or `n_major < 3` or `n_minor < 3`.
pub fn torus(major: f64, minor: f64, n_major: usize, n_minor: usize) -> TriMesh {
    check_torus(major, minor, n_major, n_minor);
    let mut positions = Vec::with_capacity(n_major * n_minor);
    for j in 0..n_minor {
        let theta = 2.0 * PI * j as f64 / n_minor as f64;
        let rho = major + minor * theta.cos();
        positions.extend((0..n_major).map(|i| {
            let phi = 2.0 * PI * i as f64 / n_major as f64;
            [rho * phi.cos(), rho * phi.sin(), minor * theta.sin()]
        }));
    }
    build(
        "torus",
        positions,
        wrapped_grid_faces(n_major, n_minor, true, true),
    )
}

/// The argument checks of [`torus`] and [`crate::jittered_torus`].
pub(crate) fn check_torus(major: f64, minor: f64, n_major: usize, n_minor: usize) {
    assert!(
        0.0 < minor && minor < major,
        "torus needs 0 < minor < major"
    );
    assert!(
        n_major >= 3 && n_minor >= 3,
        "torus needs at least 3 × 3 vertices"
    );
}

/// A round sphere of radius `radius` centred at the origin: the icosahedron, each face split
/// into four `subdivisions` times, every vertex pushed onto the sphere. `10 · 4^s + 2`
/// vertices, `20 · 4^s` nearly equilateral faces; the first 12 vertices are the
/// icosahedron's. Closed, genus 0, χ = 2.
///
/// # Panics
/// If `radius` is not positive or `subdivisions > 8` (over 2.6 million faces).
pub fn icosphere(radius: f64, subdivisions: u32) -> TriMesh {
    assert!(radius > 0.0, "icosphere needs a positive radius");
    assert!(subdivisions <= 8, "icosphere: at most 8 subdivisions");
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions: Vec<[f64; 3]> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .map(|p| project(p, radius))
    .to_vec();
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::with_capacity(4 * faces.len());
        for f in &faces {
            let mut mid = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                mid[k] = *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (p, q) = (positions[a as usize], positions[b as usize]);
                    positions.push(project([p[0] + q[0], p[1] + q[1], p[2] + q[2]], radius));
                    (positions.len() - 1) as u32
                });
            }
            next.push([f[0], mid[0], mid[2]]);
            next.push([f[1], mid[1], mid[0]]);
            next.push([f[2], mid[2], mid[1]]);
            next.push(mid);
        }
        faces = next;
    }
    build("icosphere", positions, faces)
}

/// `p` scaled onto the sphere of radius `radius`.
fn project(p: [f64; 3], radius: f64) -> [f64; 3] {
    let s = radius / (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    [p[0] * s, p[1] * s, p[2] * s]
}

#[cfg(test)]
mod tests {
    use super::*;
    use conformap_mesh::Topology;

    /// Every face normal (unnormalized) and its centroid.
    fn normals(mesh: &TriMesh) -> impl Iterator<Item = ([f64; 3], [f64; 3])> + '_ {
        let p = mesh.positions();
        mesh.faces().iter().map(move |f| {
            let [a, b, c] = f.map(|v| p[v as usize]);
            let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
            let n = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let m = [
                (a[0] + b[0] + c[0]) / 3.0,
                (a[1] + b[1] + c[1]) / 3.0,
                (a[2] + b[2] + c[2]) / 3.0,
            ];
            (n, m)
        })
    }

    #[test]
    fn cylinder_topology_and_outward_normals() {
        let mesh = cylinder(1.0, 2.0, 6, 20);
        assert_eq!(mesh.num_vertices(), 7 * 20);
        assert_eq!(
            mesh.topology(),
            Topology::MultiplyConnected { boundaries: 2 }
        );
        assert_eq!(mesh.euler_characteristic(), 0);
        assert!(mesh.boundary_loops().iter().all(|l| l.len() == 20));
        assert!(normals(&mesh).all(|(n, m)| n[0] * m[0] + n[1] * m[1] > 0.0));
    }

    #[test]
    fn torus_topology_and_outward_normals() {
        let (major, minor) = (2.0, 0.5);
        let mesh = torus(major, minor, 24, 12);
        assert_eq!((mesh.num_vertices(), mesh.num_faces()), (288, 576));
        assert_eq!(mesh.topology(), Topology::ClosedHigherGenus { genus: 1 });
        assert_eq!(mesh.euler_characteristic(), 0);
        assert!(mesh.boundary_loops().is_empty());
        // outward: away from the tube's centre circle
        assert!(normals(&mesh).all(|(n, m)| {
            let rho = m[0].hypot(m[1]);
            let c = [major * m[0] / rho, major * m[1] / rho, 0.0];
            n[0] * (m[0] - c[0]) + n[1] * (m[1] - c[1]) + n[2] * (m[2] - c[2]) > 0.0
        }));
    }

    #[test]
    fn icosphere_topology_and_outward_normals() {
        let mesh = icosphere(2.0, 3);
        assert_eq!((mesh.num_vertices(), mesh.num_faces()), (642, 1280));
        assert_eq!(mesh.topology(), Topology::Sphere);
        assert_eq!(mesh.euler_characteristic(), 2);
        assert!(normals(&mesh).all(|(n, m)| n[0] * m[0] + n[1] * m[1] + n[2] * m[2] > 0.0));
        for q in mesh.positions() {
            crate::assert_near!((q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt(), 2.0, 1e-14);
        }
    }
}
