//! Point location in a planar triangulation (a registered disk): a uniform grid over the
//! triangles' bounding boxes, barycentric coordinates, and the nearest triangle for
//! points just outside (the boundary of one inscribed polygon bulges past another's
//! chords by up to `O(h²)`).

use num_complex::Complex64;

/// Barycentric coordinates at least `-LOCATE_INSIDE_TOL` count as inside: `1e-12`
/// (rounding of the coordinates of a point on a shared edge, relative to a triangle of
/// unit size; keeps points on edges and vertices from falling between triangles).
pub const LOCATE_INSIDE_TOL: f64 = 1e-12;

/// Average number of triangles per grid cell the grid is sized for: `2` (measured on the
/// shared faces: 1–4 gives the same location time within 10 %).
pub const LOCATE_TRIANGLES_PER_CELL: f64 = 2.0;

/// Where a point lies: a triangle and its barycentric coordinates (summing to 1, all
/// ≥ 0 after clamping).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Location {
    /// 0-based triangle.
    pub face: u32,
    /// Barycentric coordinates of the point (or of the nearest point of the triangle).
    pub bary: [f64; 3],
    /// Distance from the point to the triangle (0 inside).
    pub outside: f64,
}

/// A uniform grid over a planar triangulation for point location.
#[derive(Debug, Clone)]
pub struct TriangleGrid<'a> {
    points: &'a [Complex64],
    faces: &'a [[u32; 3]],
    lo: Complex64,
    cell: f64,
    nx: usize,
    ny: usize,
    /// CSR: triangles of cell `c` are `items[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    items: Vec<u32>,
}

impl<'a> TriangleGrid<'a> {
    /// Bins every triangle of `faces` (vertices `points`) by its bounding box.
    ///
    /// # Examples
    /// ```
    /// use conformap_morph::TriangleGrid;
    /// use num_complex::Complex64 as C;
    /// let pts = [C::new(0.0, 0.0), C::new(1.0, 0.0), C::new(0.0, 1.0), C::new(1.0, 1.0)];
    /// let faces = [[0, 1, 2], [1, 3, 2]];
    /// let grid = TriangleGrid::new(&pts, &faces);
    /// let at = grid.locate(C::new(0.75, 0.5));
    /// assert_eq!(at.face, 1);
    /// assert!(at.outside == 0.0 && (at.bary.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    /// ```
    pub fn new(points: &'a [Complex64], faces: &'a [[u32; 3]]) -> Self {
        let (mut lo, mut hi) = (
            Complex64::new(f64::INFINITY, f64::INFINITY),
            Complex64::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in points {
            lo = Complex64::new(lo.re.min(p.re), lo.im.min(p.im));
            hi = Complex64::new(hi.re.max(p.re), hi.im.max(p.im));
        }
        let span = hi - lo;
        let cells = (faces.len() as f64 / LOCATE_TRIANGLES_PER_CELL).max(1.0);
        let cell = ((span.re * span.im) / cells).sqrt().max(1e-300);
        let nx = ((span.re / cell).ceil() as usize).clamp(1, 1 << 12);
        let ny = ((span.im / cell).ceil() as usize).clamp(1, 1 << 12);
        let cell = (span.re / nx as f64).max(span.im / ny as f64).max(1e-300);
        let mut grid = Self {
            points,
            faces,
            lo,
            cell,
            nx,
            ny,
            start: vec![0; nx * ny + 1],
            items: Vec::new(),
        };
        let ranges: Vec<_> = faces.iter().map(|f| grid.cell_range(f)).collect();
        for &(x0, x1, y0, y1) in &ranges {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    grid.start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; grid.start[nx * ny]];
        for (t, &(x0, x1, y0, y1)) in ranges.iter().enumerate() {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let c = y * nx + x;
                    grid.items[fill[c]] = t as u32;
                    fill[c] += 1;
                }
            }
        }
        grid
    }

    fn cell_of(&self, z: Complex64) -> (usize, usize) {
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        let d = (z - self.lo) / self.cell;
        (clamp(d.re, self.nx), clamp(d.im, self.ny))
    }

    fn cell_range(&self, f: &[u32; 3]) -> (usize, usize, usize, usize) {
        let p = f.map(|v| self.points[v as usize]);
        let (x0, y0) = self.cell_of(Complex64::new(
            p[0].re.min(p[1].re).min(p[2].re),
            p[0].im.min(p[1].im).min(p[2].im),
        ));
        let (x1, y1) = self.cell_of(Complex64::new(
            p[0].re.max(p[1].re).max(p[2].re),
            p[0].im.max(p[1].im).max(p[2].im),
        ));
        (x0, x1, y0, y1)
    }

    /// The triangle containing `z` (largest smallest barycentric coordinate among those
    /// containing it), or, if none does, the nearest triangle with the barycentric
    /// coordinates of the nearest point of it.
    pub fn locate(&self, z: Complex64) -> Location {
        let (cx, cy) = self.cell_of(z);
        let mut best: Option<Location> = None;
        let mut best_key = f64::NEG_INFINITY;
        for &t in self.cell_items(cx, cy) {
            let bary = barycentric(self.tri(t), z);
            let key = bary[0].min(bary[1]).min(bary[2]);
            if key > best_key {
                best_key = key;
                best = Some(Location {
                    face: t,
                    bary,
                    outside: 0.0,
                });
            }
        }
        if let Some(loc) = best.filter(|_| best_key >= -LOCATE_INSIDE_TOL) {
            return clamped(loc);
        }
        self.nearest(z, cx, cy)
    }

    fn cell_items(&self, x: usize, y: usize) -> &[u32] {
        let c = y * self.nx + x;
        &self.items[self.start[c]..self.start[c + 1]]
    }

    fn tri(&self, t: u32) -> [Complex64; 3] {
        self.faces[t as usize].map(|v| self.points[v as usize])
    }

    /// Rings of cells around `(cx, cy)` until no unvisited cell can hold a nearer triangle.
    fn nearest(&self, z: Complex64, cx: usize, cy: usize) -> Location {
        let mut best = Location {
            face: 0,
            bary: [1.0, 0.0, 0.0],
            outside: f64::INFINITY,
        };
        let max_ring = self.nx.max(self.ny);
        for ring in 0..=max_ring {
            // every cell of this ring is at least (ring − 1) cells away from z
            if ring >= 1 && (ring as f64 - 1.0) * self.cell > best.outside {
                break;
            }
            let (x0, x1) = (cx.saturating_sub(ring), (cx + ring).min(self.nx - 1));
            let (y0, y1) = (cy.saturating_sub(ring), (cy + ring).min(self.ny - 1));
            for y in y0..=y1 {
                for x in x0..=x1 {
                    let on_ring = x.abs_diff(cx) == ring || y.abs_diff(cy) == ring;
                    if !on_ring {
                        continue;
                    }
                    for &t in self.cell_items(x, y) {
                        let (d, bary) = nearest_point(self.tri(t), z);
                        if d < best.outside {
                            best = Location {
                                face: t,
                                bary,
                                outside: d,
                            };
                        }
                    }
                }
            }
        }
        best
    }
}

/// Barycentric coordinates of `z` in triangle `p` (unclamped).
fn barycentric(p: [Complex64; 3], z: Complex64) -> [f64; 3] {
    let cross = |a: Complex64, b: Complex64| (a.conj() * b).im;
    let area = cross(p[1] - p[0], p[2] - p[0]);
    if area == 0.0 {
        return [f64::NEG_INFINITY; 3];
    }
    let b1 = cross(z - p[0], p[2] - p[0]) / area;
    let b2 = cross(p[1] - p[0], z - p[0]) / area;
    [1.0 - b1 - b2, b1, b2]
}

/// The location with its coordinates clamped to ≥ 0 and renormalized.
fn clamped(mut loc: Location) -> Location {
    let b = loc.bary.map(|x| x.max(0.0));
    let s: f64 = b.iter().sum();
    loc.bary = b.map(|x| x / s);
    loc
}

/// Distance from `z` to triangle `p` and the barycentric coordinates of the nearest point.
fn nearest_point(p: [Complex64; 3], z: Complex64) -> (f64, [f64; 3]) {
    let bary = barycentric(p, z);
    if bary.iter().all(|&b| b >= 0.0) {
        return (0.0, bary);
    }
    let mut best = (f64::INFINITY, [1.0, 0.0, 0.0]);
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        let e = p[j] - p[i];
        let len2 = e.norm_sqr();
        let s = if len2 > 0.0 {
            (((z - p[i]).conj() * e).re / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = (p[i] + e * s - z).norm();
        if d < best.0 {
            let mut b = [0.0; 3];
            b[i] = 1.0 - s;
            b[j] = s;
            best = (d, b);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_point_of_a_fan_is_found_and_outside_points_snap() {
        // a regular 12-gon fan around the origin, inscribed in the unit circle
        let n = 12;
        let mut pts = vec![Complex64::new(0.0, 0.0)];
        pts.extend(
            (0..n).map(|k| Complex64::from_polar(1.0, k as f64 * std::f64::consts::TAU / n as f64)),
        );
        let faces: Vec<[u32; 3]> = (0..n as u32)
            .map(|k| [0, 1 + k, 1 + (k + 1) % n as u32])
            .collect();
        let grid = TriangleGrid::new(&pts, &faces);
        for k in 0..500 {
            let z = Complex64::from_polar(0.95 * (k as f64 / 500.0).sqrt(), 0.37 * k as f64);
            let at = grid.locate(z);
            assert_eq!(at.outside, 0.0);
            let back: Complex64 = (0..3)
                .map(|i| pts[faces[at.face as usize][i] as usize] * at.bary[i])
                .sum();
            assert!((back - z).norm() < 1e-14, "{z} -> {back}");
        }
        // on the circle between two polygon vertices: outside by 1 − cos(π/12)
        let z = Complex64::from_polar(1.0, std::f64::consts::PI / n as f64);
        let at = grid.locate(z);
        let expect = 1.0 - (std::f64::consts::PI / n as f64).cos();
        assert!((at.outside - expect).abs() < 1e-14, "{}", at.outside);
        assert_eq!(at.face, 0);
        assert!((at.bary[1] - 0.5).abs() < 1e-12 && (at.bary[2] - 0.5).abs() < 1e-12);
    }
}
