//! The visibility pass: which face is nearest at every sample, by a z-buffer, in parallel
//! over horizontal bands of samples.

use rayon::prelude::*;

/// Face id of a sample that no face covers.
pub(crate) const NO_FACE: u32 = u32::MAX;

/// Sample rows per band: the unit of parallel work. 16 rows keep a band's depth and id
/// rows (16 × width × 8 bytes, 390 KiB at 3072 samples) in the L2 cache while giving
/// hundreds of bands to balance.
const BAND_ROWS: usize = 16;

/// The nearest face and its depth at every sample (row-major, `width × height`).
pub(crate) struct VisBuffer {
    /// Samples per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The nearest face per sample, [`NO_FACE`] where none.
    pub face: Vec<u32>,
}

/// Rasterizes the triangles `tri(t)` (indices into `screen`, `t < n_tris`) with the screen
/// positions `screen` (`x`, `y` in samples, `y` down; depth, smaller nearer). Sample
/// centres are at half-integers; a sample on an edge belongs to both sides (no cracks, and
/// the z-test decides); ties in depth go to the lower face id, so the result does not
/// depend on the thread count.
pub(crate) fn rasterize(
    width: usize,
    height: usize,
    screen: &[[f64; 3]],
    n_tris: usize,
    tri: impl Fn(usize) -> [u32; 3] + Sync,
) -> VisBuffer {
    let bands = height.div_ceil(BAND_ROWS).max(1);
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
            let r0 = (y0.max(0.0) as usize / BAND_ROWS) as u32;
            let r1 = ((y1.min(height as f64 - 1.0)) as usize / BAND_ROWS) as u32;
            (r0, r1)
        })
        .collect();
    let mut start = vec![0usize; bands + 1];
    for &(r0, r1) in &ranges {
        for b in r0..=r1.min(bands as u32 - 1) {
            start[b as usize + 1] += 1;
        }
    }
    for b in 0..bands {
        start[b + 1] += start[b];
    }
    let mut cursor = start.clone();
    let mut lists = vec![0u32; start[bands]];
    for (t, &(r0, r1)) in ranges.iter().enumerate() {
        for b in r0..=r1.min(bands as u32 - 1) {
            lists[cursor[b as usize]] = t as u32;
            cursor[b as usize] += 1;
        }
    }
    drop(ranges);

    let mut face = vec![NO_FACE; width * height];
    face.par_chunks_mut(BAND_ROWS * width)
        .enumerate()
        .for_each(|(b, ids)| {
            let y0 = b * BAND_ROWS;
            let rows = ids.len() / width;
            let mut depth = vec![f64::INFINITY; ids.len()];
            for &t in &lists[start[b]..start[b + 1]] {
                let corners = tri(t as usize).map(|i| screen[i as usize]);
                draw_triangle(corners, t, width, y0, rows, &mut depth, ids);
            }
        });
    VisBuffer {
        width,
        height,
        face,
    }
}

/// Draws one triangle into the band of `rows` sample rows starting at row `y0`.
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
    // samples i with centre i + ½ in [min, max]
    let i0 = (min_x - 0.5).ceil().max(0.0);
    let i1 = (max_x - 0.5).floor().min(width as f64 - 1.0);
    let j0 = (min_y - 0.5).ceil().max(y0 as f64);
    let j1 = (max_y - 0.5).floor().min((y0 + rows) as f64 - 1.0);
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
        for i in i0..=i1 {
            if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                let z = (w0 * z0 + w1 * z1 + w2 * z2) * inv;
                let s = row + i;
                if z < depth[s] || (z == depth[s] && t < ids[s]) {
                    depth[s] = z;
                    ids[s] = t;
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
        let vis = rasterize(16, 16, &screen, 2, |t| tris[t]);
        let covered = vis.face.iter().filter(|&&f| f != NO_FACE).count();
        assert_eq!(covered, 12 * 12);
        assert!(vis.face.contains(&0) && vis.face.contains(&1));
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
        let tris = [[0u32, 1, 2], [3, 4, 5]];
        let vis = rasterize(40, 40, &screen, 2, |t| tris[t]);
        assert_eq!(vis.face[5 * 40 + 5], 1);
        // and clockwise triangles are drawn too (no culling)
        let vis = rasterize(40, 40, &screen, 1, |_| [0, 2, 1]);
        assert_eq!(vis.face[5 * 40 + 5], 0);
    }
}
