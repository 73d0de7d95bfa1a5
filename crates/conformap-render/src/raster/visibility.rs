//! The visibility pass: which face is nearest at every sample of a band of sample rows, by
//! a z-buffer that stays in the cache; triangles are binned into the bands first.

use rayon::prelude::*;

use crate::textures::floor_i64;

/// Face id of a sample that no face covers.
pub(crate) const NO_FACE: u32 = u32::MAX;

/// The triangles of every band of `band_rows` sample rows (a triangle is listed in every
/// band its bounding box touches; off-screen ones in none).
pub(crate) struct Bins {
    /// Samples per row.
    pub width: usize,
    /// Sample rows.
    pub height: usize,
    /// Sample rows per band (the last band may be shorter).
    pub band_rows: usize,
    /// `lists[start[b]..start[b + 1]]` are the triangles of band `b`, ascending.
    start: Vec<usize>,
    lists: Vec<u32>,
}

impl Bins {
    /// Bins the triangles `tri(t)` (`t < n_tris`, indices into `screen`: `x`, `y` in
    /// samples, `y` down) into bands of `band_rows` rows of a `width × height` sample grid.
    pub(crate) fn new(
        width: usize,
        height: usize,
        band_rows: usize,
        screen: &[[f64; 3]],
        n_tris: usize,
        tri: impl Fn(usize) -> [u32; 3] + Sync,
    ) -> Self {
        let band_rows = band_rows.max(1);
        let bands = height.div_ceil(band_rows).max(1);
        // band range of every triangle (empty when off screen)
        let ranges: Vec<(u32, u32)> = (0..n_tris)
            .into_par_iter()
            .map(|t| {
                let [a, b, c] = tri(t).map(|i| screen[i as usize]);
                let (y0, y1) = (a[1].min(b[1]).min(c[1]), a[1].max(b[1]).max(c[1]));
                let (x0, x1) = (a[0].min(b[0]).min(c[0]), a[0].max(b[0]).max(c[0]));
                if !(y1 >= 0.0 && y0 < height as f64 && x1 >= 0.0 && x0 < width as f64) {
                    return (1, 0);
                }
                let r0 = (y0.max(0.0) as usize / band_rows) as u32;
                let r1 = ((y1.min(height as f64 - 1.0)) as usize / band_rows) as u32;
                (r0, r1.min(bands as u32 - 1))
            })
            .collect();
        let mut start = vec![0usize; bands + 1];
        for &(r0, r1) in &ranges {
            for b in r0..=r1 {
                start[b as usize + 1] += 1;
            }
        }
        for b in 0..bands {
            start[b + 1] += start[b];
        }
        let mut cursor = start.clone();
        let mut lists = vec![0u32; start[bands]];
        for (t, &(r0, r1)) in ranges.iter().enumerate() {
            for b in r0..=r1 {
                lists[cursor[b as usize]] = t as u32;
                cursor[b as usize] += 1;
            }
        }
        Self {
            width,
            height,
            band_rows,
            start,
            lists,
        }
    }

    /// Number of bands.
    pub(crate) fn bands(&self) -> usize {
        self.start.len() - 1
    }

    /// The first sample row of band `b` and its number of rows.
    pub(crate) fn rows(&self, b: usize) -> (usize, usize) {
        let y0 = b * self.band_rows;
        (y0, self.band_rows.min(self.height.saturating_sub(y0)))
    }

    /// Draws band `b` into `ids` (the nearest face per sample of the band, row-major,
    /// [`NO_FACE`] where none), with `depth` as scratch; both are resized to the band.
    /// Sample centres are at half-integers; a sample on an edge belongs to both sides (no
    /// cracks, and the z-test decides); ties in depth go to the lower face id, so the
    /// result depends neither on the thread count nor on the banding.
    pub(crate) fn draw_band(
        &self,
        b: usize,
        screen: &[[f64; 3]],
        tri: impl Fn(usize) -> [u32; 3],
        depth: &mut Vec<f64>,
        ids: &mut Vec<u32>,
    ) {
        let (y0, rows) = self.rows(b);
        let n = rows * self.width;
        depth.clear();
        depth.resize(n, f64::INFINITY);
        ids.clear();
        ids.resize(n, NO_FACE);
        for &t in &self.lists[self.start[b]..self.start[b + 1]] {
            let corners = tri(t as usize).map(|i| screen[i as usize]);
            draw_triangle(corners, t, self.width, y0, rows, depth, ids);
        }
    }
}

/// Draws one triangle into the band of `rows` sample rows starting at row `y0`: the samples
/// of its bounding box (clipped to the band) whose three edge functions are ≥ 0, stepped
/// incrementally along each row.
#[inline]
fn draw_triangle(
    mut p: [[f64; 3]; 3],
    t: u32,
    width: usize,
    y0: usize,
    rows: usize,
    depth: &mut [f64],
    ids: &mut [u32],
) {
    let mut area2 =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if !(area2.abs() > 0.0) {
        return;
    }
    if area2 < 0.0 {
        p.swap(1, 2);
        area2 = -area2;
    }
    let min_x = p[0][0].min(p[1][0]).min(p[2][0]);
    let max_x = p[0][0].max(p[1][0]).max(p[2][0]);
    let min_y = p[0][1].min(p[1][1]).min(p[2][1]);
    let max_y = p[0][1].max(p[1][1]).max(p[2][1]);
    // samples i with centre i + ½ in [min, max] (floor_i64: no libm call; the bounds are
    // clamped to the band, so a far-off corner only saturates)
    let i0 = (-floor_i64(0.5 - min_x)).max(0);
    let i1 = floor_i64(max_x - 0.5).min(width as i64 - 1);
    let j0 = (-floor_i64(0.5 - min_y)).max(y0 as i64);
    let j1 = floor_i64(max_y - 0.5).min((y0 + rows) as i64 - 1);
    if i0 > i1 || j0 > j1 {
        return;
    }
    let (i0, i1, j0, j1) = (i0 as usize, i1 as usize, j0 as usize, j1 as usize);
    // edge functions w_k(x, y) = A_k x + B_k y + C_k, positive inside (area2 > 0)
    let edge = |a: [f64; 3], b: [f64; 3]| {
        let ea = a[1] - b[1];
        let eb = b[0] - a[0];
        let ec = a[0] * b[1] - a[1] * b[0];
        (ea, eb, ec)
    };
    let e0 = edge(p[1], p[2]);
    let e1 = edge(p[2], p[0]);
    let e2 = edge(p[0], p[1]);
    let inv = 1.0 / area2;
    let (z0, z1, z2) = (p[0][2], p[1][2], p[2][2]);
    let x_start = i0 as f64 + 0.5;
    for j in j0..=j1 {
        let y = j as f64 + 0.5;
        let mut w0 = e0.0 * x_start + e0.1 * y + e0.2;
        let mut w1 = e1.0 * x_start + e1.1 * y + e1.2;
        let mut w2 = e2.0 * x_start + e2.1 * y + e2.2;
        let row = (j - y0) * width;
        let (d, f) = (
            &mut depth[row + i0..=row + i1],
            &mut ids[row + i0..=row + i1],
        );
        for (d, f) in d.iter_mut().zip(f.iter_mut()) {
            if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                let z = (w0 * z0 + w1 * z1 + w2 * z2) * inv;
                if z < *d || (z == *d && t < *f) {
                    *d = z;
                    *f = t;
                }
            }
            w0 += e0.0;
            w1 += e1.0;
            w2 += e2.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The face ids of the whole `width × height` grid, drawn band by band.
    fn rasterize(
        width: usize,
        height: usize,
        band_rows: usize,
        screen: &[[f64; 3]],
        tris: &[[u32; 3]],
    ) -> Vec<u32> {
        let bins = Bins::new(width, height, band_rows, screen, tris.len(), |t| tris[t]);
        let (mut depth, mut ids, mut all) = (Vec::new(), Vec::new(), Vec::new());
        for b in 0..bins.bands() {
            bins.draw_band(b, screen, |t| tris[t], &mut depth, &mut ids);
            all.extend_from_slice(&ids);
        }
        assert_eq!(all.len(), width * height);
        all
    }

    #[test]
    fn two_triangles_cover_a_square_without_cracks() {
        // the square [2, 14]² split along its diagonal
        let screen = [
            [2.0, 2.0, 0.0],
            [14.0, 2.0, 0.0],
            [14.0, 14.0, 0.0],
            [2.0, 14.0, 0.0],
        ];
        let tris = [[0u32, 1, 2], [0, 2, 3]];
        for band_rows in [1, 5, 16, 40] {
            let face = rasterize(16, 16, band_rows, &screen, &tris);
            let covered = face.iter().filter(|&&f| f != NO_FACE).count();
            assert_eq!(covered, 12 * 12, "bands of {band_rows} rows");
            assert!(face.contains(&0) && face.contains(&1));
        }
    }

    #[test]
    fn the_nearer_face_wins() {
        let screen = [
            [0.0, 0.0, 1.0],
            [40.0, 0.0, 1.0],
            [0.0, 40.0, 1.0],
            [0.0, 0.0, 0.5],
            [40.0, 0.0, 0.5],
            [0.0, 40.0, 0.5],
        ];
        let face = rasterize(40, 40, 16, &screen, &[[0, 1, 2], [3, 4, 5]]);
        assert_eq!(face[5 * 40 + 5], 1);
        // and clockwise triangles are drawn too (no culling)
        let face = rasterize(40, 40, 16, &screen, &[[0, 2, 1]]);
        assert_eq!(face[5 * 40 + 5], 0);
    }

    #[test]
    fn banding_does_not_change_the_result() {
        // a fan of thin overlapping triangles at several depths
        let mut screen = Vec::new();
        let mut tris = Vec::new();
        for k in 0..30u32 {
            let a = k as f64 * 0.21;
            screen.push([20.0, 20.0, 0.1 * (k % 7) as f64]);
            screen.push([20.0 + 19.0 * a.cos(), 20.0 + 19.0 * a.sin(), 0.3]);
            screen.push([
                20.0 + 19.0 * (a + 0.5).cos(),
                20.0 + 19.0 * (a + 0.5).sin(),
                0.2,
            ]);
            tris.push([3 * k, 3 * k + 1, 3 * k + 2]);
        }
        let one = rasterize(40, 40, 40, &screen, &tris);
        for band_rows in [1, 3, 7, 16] {
            assert_eq!(rasterize(40, 40, band_rows, &screen, &tris), one);
        }
    }
}
