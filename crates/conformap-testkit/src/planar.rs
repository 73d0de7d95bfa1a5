//! Flat analytic meshes in the plane `z = 0`, counter-clockwise faces (normal `+z`): the unit
//! disk, a square grid and an annulus. The disk with holes is in [`crate::holes`].

use std::f64::consts::PI;

use conformap_mesh::TriMesh;

use crate::grid::grid_faces;

/// Validates a mesh built by this crate. The builders construct valid meshes by design, so a
/// failure is a bug in the builder (or arguments outside its documented range).
pub(crate) fn build(what: &str, positions: Vec<[f64; 3]>, faces: Vec<[u32; 3]>) -> TriMesh {
    match TriMesh::try_new(positions, faces) {
        Ok(mesh) => mesh,
        Err(e) => panic!("conformap-testkit built an invalid {what}: {e}"),
    }
}

/// Squared distance of two points.
fn dist2(p: [f64; 3], q: [f64; 3]) -> f64 {
    (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)
}

/// Triangulates the band between two closed rings of vertex indices that run the same way
/// around (counter-clockwise seen from the front), `inner` on the right of the direction of
/// travel and `outer` on the left. Starts with the edge `inner[0]–outer[0]` and at each step
/// adds the triangle whose new diagonal is shorter, so rings of different sizes are merged
/// evenly. Adds `inner.len() + outer.len()` front-facing triangles.
pub(crate) fn stitch_rings(
    inner: &[u32],
    outer: &[u32],
    positions: &[[f64; 3]],
    faces: &mut Vec<[u32; 3]>,
) {
    let (ni, no) = (inner.len(), outer.len());
    let p = |v: u32| positions[v as usize];
    let (mut i, mut o) = (0, 0);
    while i < ni || o < no {
        let (a, a1) = (inner[i % ni], inner[(i + 1) % ni]);
        let (b, b1) = (outer[o % no], outer[(o + 1) % no]);
        let advance_inner = if i == ni {
            false
        } else if o == no {
            true
        } else {
            dist2(p(a1), p(b)) <= dist2(p(a), p(b1))
        };
        if advance_inner {
            faces.push([a, b, a1]);
            i += 1;
        } else {
            faces.push([b, b1, a]);
            o += 1;
        }
    }
}

/// The flat unit disk, triangulated in concentric rings: a centre vertex and `rings` circles
/// of radius `k / rings` (`k = 1..=rings`), circle `k` carrying `k · sectors` evenly spaced
/// vertices starting at angle 0. With `sectors = 6` the triangles are close to equilateral
/// (a hexagonal pattern); the mesh is Delaunay for `4 ≤ sectors ≤ 8` (tested up to 25
/// rings; `sectors = 3` is not). The boundary vertices lie on the unit circle to rounding
/// (`||p| − 1| ≤ 2⁻⁵²`).
///
/// Vertex 0 is the centre; `1 + sectors · rings (rings + 1) / 2` vertices and
/// `sectors · rings²` faces in all. One boundary loop (counter-clockwise), χ = 1.
///
/// # Panics
/// If `rings == 0` or `sectors < 3`.
pub fn flat_disk(rings: usize, sectors: usize) -> TriMesh {
    assert!(
        rings >= 1 && sectors >= 3,
        "flat_disk needs rings ≥ 1 and sectors ≥ 3"
    );
    let mut positions = vec![[0.0, 0.0, 0.0]];
    let mut circles: Vec<Vec<u32>> = Vec::with_capacity(rings);
    for k in 1..=rings {
        let n = k * sectors;
        let r = k as f64 / rings as f64;
        let start = positions.len() as u32;
        positions.extend((0..n).map(|j| {
            let t = 2.0 * PI * j as f64 / n as f64;
            [r * t.cos(), r * t.sin(), 0.0]
        }));
        circles.push((start..start + n as u32).collect());
    }
    let mut faces = Vec::with_capacity(sectors * rings * rings);
    let first = &circles[0];
    for j in 0..first.len() {
        faces.push([0, first[j], first[(j + 1) % first.len()]]);
    }
    for w in circles.windows(2) {
        stitch_rings(&w[0], &w[1], &positions, &mut faces);
    }
    build("flat disk", positions, faces)
}

/// A planar grid on the unit square `[0, 1]²` with `nx × ny` square cells, each split into two
/// right triangles along its `(i, j)–(i+1, j+1)` diagonal. Vertex `(i, j)` (column `i`, row
/// `j`) has index `j · (nx + 1) + i`. One boundary loop (counter-clockwise), χ = 1.
///
/// # Panics
/// If `nx == 0` or `ny == 0`.
pub fn square_grid(nx: usize, ny: usize) -> TriMesh {
    assert!(nx >= 1 && ny >= 1, "square_grid needs nx, ny ≥ 1");
    let mut positions = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            positions.push([i as f64 / nx as f64, j as f64 / ny as f64, 0.0]);
        }
    }
    build("square grid", positions, grid_faces(nx, ny))
}

/// A planar annulus `r0 ≤ |z| ≤ r1` centred at the origin: `rings + 1` circles of `sectors`
/// vertices each, at geometrically spaced radii `r0 (r1/r0)^(k/rings)` (uniform in `log r`,
/// so cells keep their shape from the inner to the outer circle), every other circle turned
/// by half a sector. For near-equilateral triangles choose
/// `rings ≈ sectors · ln(r1/r0) / (2π) · 2/√3`.
///
/// Vertices `0..sectors` lie on the inner circle (radius exactly `r0` up to rounding), the last
/// `sectors` on the outer one. Two boundary loops of `sectors` vertices: the outer one
/// counter-clockwise, the inner one clockwise; χ = 0.
///
/// # Panics
/// If not `0 < r0 < r1`, or `rings == 0`, or `sectors < 3`.
pub fn annulus(r0: f64, r1: f64, rings: usize, sectors: usize) -> TriMesh {
    assert!(
        0.0 < r0 && r0 < r1 && r1.is_finite(),
        "annulus needs 0 < r0 < r1"
    );
    assert!(
        rings >= 1 && sectors >= 3,
        "annulus needs rings ≥ 1 and sectors ≥ 3"
    );
    let mut positions = Vec::with_capacity((rings + 1) * sectors);
    let mut circles: Vec<Vec<u32>> = Vec::with_capacity(rings + 1);
    for k in 0..=rings {
        let r = if k == rings {
            r1
        } else {
            r0 * (r1 / r0).powf(k as f64 / rings as f64)
        };
        let offset = if k % 2 == 1 { PI / sectors as f64 } else { 0.0 };
        let start = positions.len() as u32;
        positions.extend((0..sectors).map(|j| {
            let t = 2.0 * PI * j as f64 / sectors as f64 + offset;
            [r * t.cos(), r * t.sin(), 0.0]
        }));
        circles.push((start..start + sectors as u32).collect());
    }
    let mut faces = Vec::with_capacity(2 * rings * sectors);
    for w in circles.windows(2) {
        stitch_rings(&w[0], &w[1], &positions, &mut faces);
    }
    build("annulus", positions, faces)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use conformap_mesh::Topology;

    /// Signed area of every face projected to the xy-plane.
    pub(crate) fn signed_areas(mesh: &TriMesh) -> Vec<f64> {
        let p = mesh.positions();
        mesh.faces()
            .iter()
            .map(|f| {
                let [a, b, c] = f.map(|v| p[v as usize]);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
            })
            .collect()
    }

    /// Largest `−(cot α + cot β)` over the interior edges: ≤ 0 for a Delaunay mesh.
    pub(crate) fn worst_delaunay_violation(mesh: &TriMesh) -> f64 {
        let p = mesh.positions();
        let cot = |f: usize, k: usize| {
            let t = mesh.faces()[f];
            let o = p[t[k] as usize];
            let (a, b) = (p[t[(k + 1) % 3] as usize], p[t[(k + 2) % 3] as usize]);
            let u = [a[0] - o[0], a[1] - o[1], a[2] - o[2]];
            let v = [b[0] - o[0], b[1] - o[1], b[2] - o[2]];
            let dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            let c = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            dot / (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
        };
        let mut worst = f64::NEG_INFINITY;
        for (h, &o) in mesh.opposite_halfedges().iter().enumerate() {
            if o == conformap_mesh::NO_HALFEDGE || (h as u32) > o {
                continue;
            }
            let o = o as usize;
            // half-edge h = 3f + k is opposite corner (k + 2) % 3
            let s = cot(h / 3, (h % 3 + 2) % 3) + cot(o / 3, (o % 3 + 2) % 3);
            worst = worst.max(-s);
        }
        worst
    }

    #[test]
    fn flat_disk_topology_and_shape() {
        let mesh = flat_disk(8, 6);
        assert_eq!(mesh.num_vertices(), 1 + 6 * 8 * 9 / 2);
        assert_eq!(mesh.num_faces(), 6 * 64);
        assert_eq!(mesh.topology(), Topology::Disk);
        assert_eq!(mesh.euler_characteristic(), 1);
        let lp = &mesh.boundary_loops()[0];
        assert_eq!(lp.len(), 48);
        for &v in lp {
            let q = mesh.positions()[v as usize];
            assert!(((q[0] * q[0] + q[1] * q[1]).sqrt() - 1.0).abs() <= f64::EPSILON);
        }
        assert!(signed_areas(&mesh).iter().all(|&a| a > 0.0));
        let total: f64 = signed_areas(&mesh).iter().sum();
        // inscribed 48-gon
        crate::assert_rel_near!(total, 24.0 * (2.0 * PI / 48.0).sin(), 1e-13);
        assert!(worst_delaunay_violation(&mesh) <= 1e-12);
    }

    #[test]
    fn flat_disk_is_delaunay_for_four_to_eight_sectors() {
        for rings in 1..=25 {
            for sectors in 4..=8 {
                let mesh = flat_disk(rings, sectors);
                let worst = worst_delaunay_violation(&mesh);
                assert!(worst <= 1e-12, "rings {rings}, sectors {sectors}: {worst}");
            }
        }
    }

    #[test]
    fn square_grid_topology() {
        let mesh = square_grid(4, 3);
        assert_eq!((mesh.num_vertices(), mesh.num_faces()), (20, 24));
        assert_eq!(mesh.topology(), Topology::Disk);
        assert_eq!(mesh.boundary_loops()[0].len(), 14);
        crate::assert_rel_near!(signed_areas(&mesh).iter().sum::<f64>(), 1.0, 1e-14);
    }

    #[test]
    fn annulus_topology_and_orientation() {
        let mesh = annulus(0.5, 1.0, 4, 24);
        assert_eq!(mesh.num_vertices(), 5 * 24);
        assert_eq!(
            mesh.topology(),
            Topology::MultiplyConnected { boundaries: 2 }
        );
        assert_eq!(mesh.euler_characteristic(), 0);
        assert!(signed_areas(&mesh).iter().all(|&a| a > 0.0));
        assert!(worst_delaunay_violation(&mesh) <= 1e-12);
        // loop orientation: the outer loop turns counter-clockwise, the inner one clockwise
        for lp in mesh.boundary_loops() {
            let p = mesh.positions();
            let area: f64 = (0..lp.len())
                .map(|k| {
                    let (a, b) = (p[lp[k] as usize], p[lp[(k + 1) % lp.len()] as usize]);
                    0.5 * (a[0] * b[1] - b[0] * a[1])
                })
                .sum();
            let r = p[lp[0] as usize][0].hypot(p[lp[0] as usize][1]);
            assert_eq!(area > 0.0, r > 0.75, "loop at radius {r}");
        }
    }
}
