//! A flat unit disk with circular holes, from a Delaunay triangulation (Bowyer–Watson).

use std::f64::consts::PI;

use conformap_mesh::TriMesh;

use crate::planar::build;

/// A circle in the plane (a hole of [`disk_with_holes`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Centre `(x, y)`.
    pub center: [f64; 2],
    /// Radius, `> 0`.
    pub radius: f64,
}

impl Circle {
    /// A circle of radius `radius` centred at `(x, y)`.
    pub const fn new(x: f64, y: f64, radius: f64) -> Self {
        Self {
            center: [x, y],
            radius,
        }
    }
}

/// The flat unit disk with circular holes, edge length about `spacing`.
///
/// Points: the unit circle and every hole circle sampled evenly (spacing `≈ spacing`, at
/// least 8 points per hole, the first at angle 0), and a hexagonal lattice of spacing
/// `spacing` kept at least `spacing / 2` away from every circle. Their Delaunay triangulation
/// (with a temporary vertex at each hole centre, whose fan is then removed) is the mesh, so
/// it is Delaunay and every hole boundary is exactly the sampled polygon.
///
/// Vertex order: lattice points, then each hole's circle in the order given, then the unit
/// circle (its vertices are the last `⌈2π / spacing⌉`). Boundary loops: the outer circle
/// counter-clockwise, the holes clockwise; χ = 1 − holes.
///
/// Deterministic (no randomness). Quadratic time: meant for test meshes of a few thousand
/// vertices.
///
/// # Panics
/// If `spacing` is not in `(0, 0.5]`, a hole does not lie inside the disk with a margin of
/// `spacing` (`|c| + r + spacing ≤ 1`), or two holes are closer than `spacing`.
pub fn disk_with_holes(holes: &[Circle], spacing: f64) -> TriMesh {
    let h = spacing;
    assert!(
        h > 0.0 && h <= 0.5,
        "disk_with_holes needs 0 < spacing ≤ 0.5"
    );
    for (i, c) in holes.iter().enumerate() {
        assert!(
            c.radius > 0.0 && c.center[0].hypot(c.center[1]) + c.radius + h <= 1.0,
            "hole {i} must lie inside the unit disk with a margin of `spacing`"
        );
        for (j, d) in holes.iter().enumerate().skip(i + 1) {
            let gap = (c.center[0] - d.center[0]).hypot(c.center[1] - d.center[1]);
            assert!(
                gap >= c.radius + d.radius + h,
                "holes {i} and {j} are closer than `spacing`"
            );
        }
    }
    // lattice
    let mut points: Vec<[f64; 2]> = Vec::new();
    let dy = h * 3f64.sqrt() / 2.0;
    let rows = (1.0 / dy).ceil() as i64;
    let cols = (1.0 / h).ceil() as i64 + 1;
    for j in -rows..=rows {
        let shift = if j.rem_euclid(2) == 1 { h / 2.0 } else { 0.0 };
        for i in -cols..=cols {
            let p = [i as f64 * h + shift, j as f64 * dy];
            let clear_of_outer = p[0].hypot(p[1]) <= 1.0 - h / 2.0;
            let clear_of_holes = holes
                .iter()
                .all(|c| (p[0] - c.center[0]).hypot(p[1] - c.center[1]) >= c.radius + h / 2.0);
            if clear_of_outer && clear_of_holes {
                points.push(p);
            }
        }
    }
    let on_circle = |c: Circle, n: usize| {
        (0..n).map(move |k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            [
                c.center[0] + c.radius * t.cos(),
                c.center[1] + c.radius * t.sin(),
            ]
        })
    };
    for c in holes {
        let n = ((2.0 * PI * c.radius / h).ceil() as usize).max(8);
        points.extend(on_circle(*c, n));
    }
    let n_outer = (2.0 * PI / h).ceil() as usize;
    points.extend(on_circle(Circle::new(0.0, 0.0, 1.0), n_outer));
    let kept = points.len();
    // temporary hole centres
    points.extend(holes.iter().map(|c| c.center));

    // hole centres first, then the lattice, then the circles (keeps cocircular points from
    // meeting in one triangle while the triangulation grows)
    let mut order: Vec<usize> = (kept..points.len()).collect();
    order.extend(0..kept);
    let triangles = delaunay(&points, &order);

    let positions = points[..kept].iter().map(|p| [p[0], p[1], 0.0]).collect();
    let faces = triangles
        .into_iter()
        .filter(|t| t.iter().all(|&v| v < kept))
        .map(|t| t.map(|v| v as u32))
        .collect();
    build("disk with holes", positions, faces)
}

/// A triangle of the Bowyer–Watson triangulation with its circumcircle.
struct Tri {
    v: [usize; 3],
    center: [f64; 2],
    r2: f64,
}

impl Tri {
    fn new(v: [usize; 3], p: &[[f64; 2]]) -> Self {
        let [a, b, c] = v.map(|i| p[i]);
        // circumcentre relative to `a`
        let (bx, by) = (b[0] - a[0], b[1] - a[1]);
        let (cx, cy) = (c[0] - a[0], c[1] - a[1]);
        let d = 2.0 * (bx * cy - by * cx);
        let (b2, c2) = (bx * bx + by * by, cx * cx + cy * cy);
        let ux = (cy * b2 - by * c2) / d;
        let uy = (bx * c2 - cx * b2) / d;
        Self {
            v,
            center: [a[0] + ux, a[1] + uy],
            r2: ux * ux + uy * uy,
        }
    }

    fn circle_contains(&self, p: [f64; 2]) -> bool {
        (p[0] - self.center[0]).powi(2) + (p[1] - self.center[1]).powi(2) < self.r2
    }
}

/// Counter-clockwise Delaunay triangles of `points` (inserted in `order`, all inside the
/// square `[-1, 1]²`), without the super-triangle.
fn delaunay(points: &[[f64; 2]], order: &[usize]) -> Vec<[usize; 3]> {
    let n = points.len();
    let mut p = points.to_vec();
    p.extend([[-40.0, -30.0], [40.0, -30.0], [0.0, 40.0]]);
    let mut tris = vec![Tri::new([n, n + 1, n + 2], &p)];
    let mut cavity: Vec<(usize, usize)> = Vec::new();
    for &i in order {
        let q = p[i];
        cavity.clear();
        tris.retain(|t| {
            if t.circle_contains(q) {
                cavity.extend([(t.v[0], t.v[1]), (t.v[1], t.v[2]), (t.v[2], t.v[0])]);
                false
            } else {
                true
            }
        });
        // the cavity's boundary: directed edges whose reverse is not in the cavity
        cavity.sort_unstable();
        for &(a, b) in &cavity {
            if cavity.binary_search(&(b, a)).is_err() {
                tris.push(Tri::new([a, b, i], &p));
            }
        }
    }
    tris.into_iter()
        .map(|t| t.v)
        .filter(|v| v.iter().all(|&k| k < n))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planar::tests::{signed_areas, worst_delaunay_violation};
    use conformap_mesh::Topology;

    #[test]
    fn three_holes_topology() {
        let holes = [
            Circle::new(0.2, 0.1, 0.3),
            Circle::new(-0.5, -0.3, 0.15),
            Circle::new(-0.35, 0.55, 0.1),
        ];
        let mesh = disk_with_holes(&holes, 0.08);
        assert_eq!(
            mesh.topology(),
            Topology::MultiplyConnected { boundaries: 4 }
        );
        assert_eq!(mesh.euler_characteristic(), -2);
        assert!(signed_areas(&mesh).iter().all(|&a| a > 0.0));
        assert!(worst_delaunay_violation(&mesh) <= 1e-9);
        // every loop lies on its circle; the outer one is the longest
        let p = mesh.positions();
        let outer = mesh.longest_boundary_loop().unwrap_or(usize::MAX);
        assert_eq!(mesh.boundary_loops()[outer].len(), 79);
        for (k, lp) in mesh.boundary_loops().iter().enumerate() {
            let q = p[lp[0] as usize];
            let c = if k == outer {
                Circle::new(0.0, 0.0, 1.0)
            } else {
                *holes
                    .iter()
                    .find(|c| {
                        ((q[0] - c.center[0]).hypot(q[1] - c.center[1]) - c.radius).abs() < 1e-12
                    })
                    .unwrap_or(&Circle::new(f64::NAN, 0.0, 0.0))
            };
            for &v in lp {
                let q = p[v as usize];
                let d = (q[0] - c.center[0]).hypot(q[1] - c.center[1]) - c.radius;
                assert!(
                    d.abs() < 1e-12,
                    "loop {k}, vertex {v}: off its circle by {d}"
                );
            }
        }
        // area = π (1 − Σ r²) up to the polygonal approximation
        let area: f64 = signed_areas(&mesh).iter().sum();
        let exact = PI * (1.0 - 0.09 - 0.0225 - 0.01);
        crate::assert_rel_near!(area, exact, 1e-2);
    }

    #[test]
    fn no_holes_is_a_delaunay_disk() {
        let mesh = disk_with_holes(&[], 0.2);
        assert_eq!(mesh.topology(), Topology::Disk);
        assert_eq!(mesh.boundary_loops()[0].len(), 32);
        assert!(worst_delaunay_violation(&mesh) <= 1e-9);
    }
}
