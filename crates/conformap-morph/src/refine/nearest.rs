//! The triangle of a mesh nearest to a point in 3D: a uniform grid of cubes listing the
//! triangles whose bounding box meets them, searched in growing shells of cubes until no
//! cube left can hold a nearer triangle, or, from a guessed triangle, in the cubes within
//! its distance; and whether that nearest triangle's normal points against a given one,
//! most often settled by the cone of normals of each cube without a distance.

use conformap_mesh::TriMesh;
use conformap_operators::vec3::{dot, norm, sub};

use std::f64::consts::{FRAC_PI_2, PI};

use crate::quality::{face_normal, point_triangle_distance};

/// Angle (radians) by which a cube's cone of normals must clear the plane orthogonal to
/// a face's normal for the cube to be skipped without looking at its triangles: `1e-9`
/// (far above the rounding of `acos` near its middle, 1e-16; a cube that misses it is
/// only scanned triangle by triangle).
pub const CONE_MARGIN: f64 = 1e-9;

/// Side of the grid's cubes in median edge lengths of the mesh: `2` (a point near the
/// surface is answered from one cube or a few; the median keeps a few large triangles
/// from setting the scale; on the shared faces the side is 0.50–0.54, the mean edge
/// 0.29). Triangles are culled by their bounding spheres before any distance is measured.
pub const NEAREST_CELL_EDGES: f64 = 2.0;

/// Nearest triangle of a mesh to a point (3D).
pub struct NearestTriangle<'m> {
    mesh: &'m TriMesh,
    lo: [f64; 3],
    h: f64,
    dims: [usize; 3],
    /// CSR: triangles of cube `c` are `items[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    items: Vec<u32>,
    /// Every triangle's normal (twice its area vector).
    normals: Vec<[f64; 3]>,
    /// Every triangle's bounding sphere: centroid and the distance to its farthest
    /// vertex.
    spheres: Vec<([f64; 3], f64)>,
    /// Per cube, a cone holding the unit normals of its triangles: axis and half-angle
    /// (radians; π for an empty cube or a degenerate triangle, which settles nothing).
    cones: Vec<([f64; 3], f64)>,
}

impl<'m> NearestTriangle<'m> {
    /// The grid over `mesh`'s triangles.
    pub fn new(mesh: &'m TriMesh) -> Self {
        let p = mesh.positions();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for q in p {
            for i in 0..3 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        let mut edges: Vec<f64> = mesh
            .faces()
            .iter()
            .flat_map(|f| (0..3).map(move |e| (f[e], f[(e + 1) % 3])))
            .map(|(a, b)| norm(sub(p[a as usize], p[b as usize])))
            .collect();
        edges.sort_unstable_by(f64::total_cmp);
        let median = edges.get(edges.len() / 2).copied().unwrap_or(1.0);
        let span = (0..3).map(|i| hi[i] - lo[i]).fold(0.0, f64::max);
        // at most 128 cubes along the longest side, and never a zero side
        let h = (NEAREST_CELL_EDGES * median).max(span / 128.0).max(1e-300);
        let dims = [0, 1, 2].map(|i| (((hi[i] - lo[i]) / h).floor() as usize) + 1);
        let mut grid = Self {
            mesh,
            lo,
            h,
            dims,
            start: vec![0; dims[0] * dims[1] * dims[2] + 1],
            items: Vec::new(),
            normals: mesh.faces().iter().map(|f| face_normal(p, f)).collect(),
            cones: Vec::new(),
            spheres: mesh
                .faces()
                .iter()
                .map(|f| {
                    let t = f.map(|v| p[v as usize]);
                    let c = [0, 1, 2].map(|i| (t[0][i] + t[1][i] + t[2][i]) / 3.0);
                    let r = t.iter().map(|&v| norm(sub(v, c))).fold(0.0, f64::max);
                    (c, r)
                })
                .collect(),
        };
        let boxes: Vec<([usize; 3], [usize; 3])> = mesh
            .faces()
            .iter()
            .map(|f| {
                let mut a = [usize::MAX; 3];
                let mut b = [0usize; 3];
                for &v in f {
                    let c = grid.cell(p[v as usize]);
                    for i in 0..3 {
                        a[i] = a[i].min(c[i]);
                        b[i] = b[i].max(c[i]);
                    }
                }
                (a, b)
            })
            .collect();
        let index = |x: usize, y: usize, z: usize| (x * dims[1] + y) * dims[2] + z;
        for (a, b) in &boxes {
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        grid.start[index(x, y, z) + 1] += 1;
                    }
                }
            }
        }
        for c in 0..grid.start.len() - 1 {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; grid.start[grid.start.len() - 1]];
        for (t, (a, b)) in boxes.iter().enumerate() {
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        let c = index(x, y, z);
                        grid.items[fill[c]] = t as u32;
                        fill[c] += 1;
                    }
                }
            }
        }
        let unit: Vec<[f64; 3]> = grid
            .normals
            .iter()
            .map(|&m| {
                let l = norm(m);
                [m[0] / l, m[1] / l, m[2] / l]
            })
            .collect();
        grid.cones = (0..grid.start.len() - 1)
            .map(|c| normal_cone(&unit, &grid.items[grid.start[c]..grid.start[c + 1]]))
            .collect();
        grid
    }

    /// Whether triangle `t` may lie within `d` of `q` (its bounding sphere does).
    fn within(&self, q: [f64; 3], t: usize, d: f64) -> bool {
        let (c, r) = self.spheres[t];
        !(norm(sub(q, c)) - r > d)
    }

    /// The mesh searched.
    pub fn mesh(&self) -> &'m TriMesh {
        self.mesh
    }

    fn cell(&self, q: [f64; 3]) -> [usize; 3] {
        [0, 1, 2].map(|i| (((q[i] - self.lo[i]) / self.h).max(0.0) as usize).min(self.dims[i] - 1))
    }

    /// Whether the triangle nearest to `q` (searched from triangle `start`, as
    /// [`Self::nearest_from`]) has a normal `m` with `m · n ≤ 0` (or not a number): the
    /// triangles within reach are first only checked for such a normal, the distances
    /// are measured only when one has it.
    pub fn nearest_points_against(&self, q: [f64; 3], start: usize, n: [f64; 3]) -> bool {
        let (p, f) = (self.mesh.positions(), self.mesh.faces());
        let against = |t: usize| !(dot(self.normals[t], n) > 0.0);
        let d0 = point_triangle_distance(q, f[start].map(|v| p[v as usize]));
        if !d0.is_finite() {
            return against(self.nearest(q));
        }
        let a = self.cell([q[0] - d0, q[1] - d0, q[2] - d0]);
        let b = self.cell([q[0] + d0, q[1] + d0, q[2] + d0]);
        let mut any = against(start);
        let n_len = norm(n);
        'cubes: for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    let k = (x * self.dims[1] + y) * self.dims[2] + z;
                    // the whole cone on n's side: no triangle of the cube is against n
                    let (axis, half) = self.cones[k];
                    let off = (dot(axis, n) / n_len).clamp(-1.0, 1.0).acos();
                    if off + half < FRAC_PI_2 - CONE_MARGIN {
                        continue;
                    }
                    if self.items[self.start[k]..self.start[k + 1]]
                        .iter()
                        .any(|&t| self.within(q, t as usize, d0) && against(t as usize))
                    {
                        any = true;
                        break 'cubes;
                    }
                }
            }
        }
        any && against(self.nearest_from(q, start))
    }

    /// The triangle nearest to `q`, starting from a guess: triangle `start`, whose
    /// distance bounds the search to the cubes within it (one or a few where the guess
    /// is near). Equally near triangles: `start` first, then the first found.
    pub fn nearest_from(&self, q: [f64; 3], start: usize) -> usize {
        let (p, f) = (self.mesh.positions(), self.mesh.faces());
        let tri = |t: usize| f[t].map(|v| p[v as usize]);
        let mut best = (point_triangle_distance(q, tri(start)), start);
        if !best.0.is_finite() {
            return self.nearest(q);
        }
        let a = self.cell([q[0] - best.0, q[1] - best.0, q[2] - best.0]);
        let b = self.cell([q[0] + best.0, q[1] + best.0, q[2] + best.0]);
        for x in a[0]..=b[0] {
            for y in a[1]..=b[1] {
                for z in a[2]..=b[2] {
                    let k = (x * self.dims[1] + y) * self.dims[2] + z;
                    for &t in &self.items[self.start[k]..self.start[k + 1]] {
                        if !self.within(q, t as usize, best.0) {
                            continue;
                        }
                        let d = point_triangle_distance(q, tri(t as usize));
                        if d < best.0 {
                            best = (d, t as usize);
                        }
                    }
                }
            }
        }
        best.1
    }

    /// The triangle nearest to `q` (the first found of equally near ones).
    pub fn nearest(&self, q: [f64; 3]) -> usize {
        let c = self.cell(q);
        let (p, f) = (self.mesh.positions(), self.mesh.faces());
        let mut best = (f64::INFINITY, 0usize);
        let reach = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=reach {
            let range = |i: usize| c[i].saturating_sub(r)..=(c[i] + r).min(self.dims[i] - 1);
            for x in range(0) {
                for y in range(1) {
                    for z in range(2) {
                        let shell = [x, y, z].iter().zip(&c).any(|(&a, &b)| a.abs_diff(b) == r);
                        if !shell {
                            continue;
                        }
                        let k = (x * self.dims[1] + y) * self.dims[2] + z;
                        for &t in &self.items[self.start[k]..self.start[k + 1]] {
                            let tri = f[t as usize].map(|v| p[v as usize]);
                            let d = point_triangle_distance(q, tri);
                            if d < best.0 {
                                best = (d, t as usize);
                            }
                        }
                    }
                }
            }
            // every cube outside the searched block is at least this far from q (a side
            // of the block on the grid's edge has no cube beyond it)
            let mut reach_out = f64::INFINITY;
            for i in 0..3 {
                if c[i] > r {
                    let wall = self.lo[i] + (c[i] - r) as f64 * self.h;
                    reach_out = reach_out.min(q[i] - wall);
                }
                if c[i] + r + 1 < self.dims[i] {
                    let wall = self.lo[i] + (c[i] + r + 1) as f64 * self.h;
                    reach_out = reach_out.min(wall - q[i]);
                }
            }
            if best.0 <= reach_out {
                break;
            }
        }
        best.1
    }
}

/// The cone of the unit normals `unit` of `items`: axis (the normalized sum) and
/// half-angle; π when the cube is empty or a normal is not a number (a zero triangle).
fn normal_cone(unit: &[[f64; 3]], items: &[u32]) -> ([f64; 3], f64) {
    let mut sum = [0.0; 3];
    for &t in items {
        let u = unit[t as usize];
        sum = [sum[0] + u[0], sum[1] + u[1], sum[2] + u[2]];
    }
    let l = norm(sum);
    if items.is_empty() || !(l > 0.0) {
        return ([0.0, 0.0, 1.0], PI);
    }
    let axis = [sum[0] / l, sum[1] / l, sum[2] / l];
    let mut lowest = 1.0f64;
    for &t in items {
        let c = dot(unit[t as usize], axis);
        if !c.is_finite() {
            return (axis, PI);
        }
        lowest = lowest.min(c);
    }
    (axis, lowest.clamp(-1.0, 1.0).acos())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A strip of 2 × 40 × 4 triangles bent into a hairpin (a lip's curl): two sheets
    /// 0.05 apart joined by a half-cylinder, the inner sides facing each other.
    fn hairpin() -> TriMesh {
        let (nu, nv) = (40usize, 4usize);
        let r = 0.025;
        let turn = std::f64::consts::PI * r;
        let mut p = Vec::new();
        for i in 0..=nu {
            // arc length along the strip: the lower sheet (0..1), the turn, the upper sheet
            let s = i as f64 / nu as f64 * 3.0;
            let (x, z) = if s < 1.0 {
                (s, -r)
            } else if s < 1.0 + turn {
                let a = (s - 1.0) / r - std::f64::consts::FRAC_PI_2;
                (1.0 + r * a.cos(), r * a.sin())
            } else {
                (1.0 - (s - 1.0 - turn), r)
            };
            for j in 0..=nv {
                p.push([x, j as f64 * 0.25, z]);
            }
        }
        let mut f = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                let a = (i * (nv + 1) + j) as u32;
                let b = a + (nv + 1) as u32;
                f.push([a, b, a + 1]);
                f.push([a + 1, b, b + 1]);
            }
        }
        TriMesh::try_new(p, f).unwrap()
    }

    fn brute(mesh: &TriMesh, q: [f64; 3]) -> f64 {
        mesh.faces()
            .iter()
            .map(|f| point_triangle_distance(q, f.map(|v| mesh.positions()[v as usize])))
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn the_searches_find_the_nearest_triangle_across_a_fold() {
        let mesh = hairpin();
        let near = NearestTriangle::new(&mesh);
        let tri = |t: usize| mesh.faces()[t].map(|v| mesh.positions()[v as usize]);
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut against_seen = 0;
        for _ in 0..2000 {
            let q = [1.2 * next() - 0.1, next(), 0.12 * next() - 0.06];
            let d = brute(&mesh, q);
            assert_eq!(point_triangle_distance(q, tri(near.nearest(q))), d, "{q:?}");
            let start = (next() * mesh.num_faces() as f64) as usize % mesh.num_faces();
            let found = near.nearest_from(q, start);
            assert_eq!(
                point_triangle_distance(q, tri(found)),
                d,
                "{q:?} from {start}"
            );
            // the two sheets face opposite ways: the answer is the nearest triangle's
            let n = [0.0, 0.0, 1.0];
            let expect = !(dot(near.normals[found], n) > 0.0);
            assert_eq!(near.nearest_points_against(q, start, n), expect, "{q:?}");
            against_seen += usize::from(expect);
        }
        // both sheets are met
        assert!(against_seen > 100 && against_seen < 1900, "{against_seen}");
    }
}
