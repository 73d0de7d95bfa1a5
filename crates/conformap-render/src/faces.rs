//! Per-face quantities of a map for colouring and histograms, from `conformap-metrics`'
//! per-face distortion (planar maps as given; sphere maps through their chord triangles).

use conformap_mesh::TriMesh;
use conformap_metrics::{face_distortion, isometric_chart, FaceDistortion};
use num_complex::Complex64;
use rayon::prelude::*;

use crate::colormap::Scale;
use crate::options::ColorBy;
use crate::param::{Domain, MapCoords};
use conformap_operators::vec3::{cross, dot};

/// Quantile of the per-face values that ends a colour scale: 0.99, so a few extreme faces
/// (at boundary corners, where every conformal map concentrates its distortion) do not
/// wash out the rest; the colour bar marks a clipped end with `>`.
pub const COLOR_RANGE_QUANTILE: f64 = 0.99;

/// [`FaceDistortion`] of every face, in face order. Planar maps whose total signed area is
/// negative (mirrored, e.g. another tool's `v ↦ −v`) are measured conjugated, as
/// `conformap_metrics::planar_map_metrics` does, so only real folds count as flipped.
/// Sphere maps are measured on their chord triangles (the isometric chart of each image
/// triangle), flipped where the image triangle turns its back to the sphere's outside
/// (relative to the majority orientation).
pub(crate) fn distortions(mesh: &TriMesh, coords: &MapCoords<'_>) -> Vec<FaceDistortion> {
    let faces = 0..mesh.num_faces();
    let p = mesh.positions();
    let points = |f: usize| mesh.faces()[f].map(|v| p[v as usize]);
    match coords.domain() {
        Domain::Plane => {
            let image = |f: usize| coords.face(mesh, f).map(|q| Complex64::new(q[0], q[1]));
            let signed: f64 = faces
                .clone()
                .into_par_iter()
                .map(|f| twice_area(image(f)))
                .sum();
            let mirrored = signed < 0.0;
            faces
                .into_par_iter()
                .map(|f| {
                    let g = image(f);
                    let g = if mirrored { g.map(|z| z.conj()) } else { g };
                    face_distortion(points(f), g)
                })
                .collect()
        }
        Domain::Sphere => {
            let orient = |q: [[f64; 3]; 3]| dot(q[0], cross(q[1], q[2]));
            let signed: f64 = faces
                .clone()
                .into_par_iter()
                .map(|f| orient(coords.face(mesh, f)))
                .sum();
            faces
                .into_par_iter()
                .map(|f| {
                    let q = coords.face(mesh, f);
                    let chart = isometric_chart(q);
                    let outward = (orient(q) >= 0.0) == (signed >= 0.0);
                    let g = if outward {
                        chart
                    } else {
                        chart.map(|z| z.conj())
                    };
                    face_distortion(points(f), g)
                })
                .collect()
        }
    }
}

#[inline]
fn twice_area(g: [Complex64; 3]) -> f64 {
    let (a, b) = (g[1] - g[0], g[2] - g[0]);
    a.re * b.im - a.im * b.re
}

/// A per-face quantity ready to colour: one value per face (`NaN` for flagged faces:
/// flipped or degenerate), the colour scale, and what it is called.
pub(crate) struct FaceField {
    /// Value per face, `NaN` where flagged.
    pub values: Vec<f64>,
    /// Number of flagged (flipped or degenerate) faces.
    pub flagged: usize,
    /// The colour scale.
    pub scale: Scale,
    /// Whether the largest value exceeds the scale's top (the bar marks it with `>`).
    pub clipped_hi: bool,
    /// Whether the smallest value is below the scale's bottom.
    pub clipped_lo: bool,
    /// Colour bar title.
    pub title: &'static str,
    /// Unit appended to the bar's numbers.
    pub unit: &'static str,
}

impl FaceField {
    /// One colour per face: the scale's colour of its value, the flagging colour where the
    /// value is undefined (a folded or degenerate face).
    pub(crate) fn colors(&self) -> Vec<[f32; 3]> {
        self.values
            .par_iter()
            .map(|&v| {
                if v.is_nan() {
                    crate::colormap::FLAG_COLOR
                } else {
                    self.scale.color(v)
                }
            })
            .collect()
    }
}

/// The field of `color` (one of the per-face quantities) from the face distortions.
pub(crate) fn face_field(d: &[FaceDistortion], color: ColorBy) -> FaceField {
    let bad = |x: &FaceDistortion| x.flipped() || x.degenerate();
    let (values, title, unit, diverging): (Vec<f64>, _, _, _) = match color {
        ColorBy::Beltrami => (
            d.iter()
                .map(|x| if bad(x) { f64::NAN } else { x.beltrami_abs })
                .collect(),
            "|μ|",
            "",
            false,
        ),
        ColorBy::Area => {
            let (mut img, mut mesh) = (0.0, 0.0);
            for x in d.iter().filter(|x| !x.degenerate()) {
                img += x.image_signed_area.abs();
                mesh += x.mesh_area;
            }
            let log_totals = mesh.ln() - img.ln();
            (
                d.iter()
                    .map(|x| {
                        if bad(x) {
                            f64::NAN
                        } else {
                            x.image_signed_area.abs().ln() - x.mesh_area.ln() + log_totals
                        }
                    })
                    .collect(),
                "log area",
                "",
                true,
            )
        }
        _ => (
            d.iter()
                .map(|x| {
                    if bad(x) {
                        f64::NAN
                    } else {
                        x.mean_angle_distortion_deg()
                    }
                })
                .collect(),
            "angle",
            "°",
            false,
        ),
    };
    let flagged = values.iter().filter(|v| v.is_nan()).count();
    let mut finite: Vec<f64> = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .map(|v| if diverging { v.abs() } else { v })
        .collect();
    let max = finite.iter().copied().fold(0.0, f64::max);
    let top = quantile(&mut finite, COLOR_RANGE_QUANTILE);
    // a perfect map: give the scale some room so its one colour is the low end
    let top = if top > 0.0 { top } else { max.max(1e-12) };
    let (lo, hi) = if diverging { (-top, top) } else { (0.0, top) };
    let min_value = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let max_value = values
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(f64::NEG_INFINITY, f64::max);
    FaceField {
        values,
        flagged,
        scale: Scale { lo, hi, diverging },
        clipped_hi: max_value > hi,
        clipped_lo: diverging && min_value < lo,
        title,
        unit,
    }
}

/// The `q`-quantile (nearest rank) of `values` (reordered); 0 for none.
fn quantile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let k = ((q * values.len() as f64).ceil() as usize).clamp(1, values.len()) - 1;
    let (_, v, _) = values.select_nth_unstable_by(k, f64::total_cmp);
    *v
}

/// The charts of the map `coords` of `mesh`: a label per face (0 for the chart of face 0,
/// then in order of first face) and their number. Two faces sharing an edge are in one
/// chart when each end of the edge has the same image in both (exactly: a seamed map
/// written with one texture coordinate per chart vertex reads back equal); a per-vertex
/// map is one chart per connected component.
pub fn chart_labels(mesh: &TriMesh, coords: &MapCoords<'_>) -> (Vec<u32>, usize) {
    let n = mesh.num_faces();
    let faces = mesh.faces();
    let opposite = mesh.opposite_halfedges();
    let mut label = vec![u32::MAX; n];
    let mut count = 0usize;
    let mut stack = Vec::new();
    for seed in 0..n {
        if label[seed] != u32::MAX {
            continue;
        }
        label[seed] = count as u32;
        stack.push(seed);
        while let Some(f) = stack.pop() {
            let here = coords.face(mesh, f);
            for k in 0..3 {
                let o = opposite[3 * f + k];
                if o == conformap_mesh::NO_HALFEDGE {
                    continue;
                }
                let g = o as usize / 3;
                if label[g] != u32::MAX {
                    continue;
                }
                // the edge's two ends, each with its image in f and in g
                let (a, b) = mesh.halfedge_vertices(3 * f + k);
                let there = coords.face(mesh, g);
                let at = |t: usize, v: u32| faces[t].iter().position(|&w| w == v);
                let same = |v: u32| match (at(f, v), at(g, v)) {
                    (Some(x), Some(y)) => here[x] == there[y],
                    _ => false,
                };
                if same(a) && same(b) {
                    label[g] = count as u32;
                    stack.push(g);
                }
            }
        }
        count += 1;
    }
    (label, count)
}

/// One colour per face from its chart ([`chart_labels`]): the charts taken largest first,
/// the `i`-th given colour `i` of [`crate::colormap::CHART_COLORS`] (cycling), or the next
/// one that none of its neighbours across a seam has.
pub(crate) fn chart_colors(mesh: &TriMesh, coords: &MapCoords<'_>) -> Vec<[f32; 3]> {
    use crate::colormap::CHART_COLORS;
    let (label, count) = chart_labels(mesh, coords);
    let opposite = mesh.opposite_halfedges();
    let mut size = vec![0usize; count];
    let mut next: Vec<Vec<u32>> = vec![Vec::new(); count];
    for (h, &o) in opposite.iter().enumerate() {
        size[label[h / 3] as usize] += usize::from(h % 3 == 0);
        if o == conformap_mesh::NO_HALFEDGE {
            continue;
        }
        let (a, b) = (label[h / 3], label[o as usize / 3]);
        if a != b {
            next[a as usize].push(b);
        }
    }
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by_key(|&c| (std::cmp::Reverse(size[c]), c));
    let mut color = vec![usize::MAX; count];
    for (rank, &c) in order.iter().enumerate() {
        let taken: Vec<usize> = next[c].iter().map(|&d| color[d as usize]).collect();
        // the next colour in turn (charts apart in the map still differ), passed over
        // while a neighbour across a seam has it
        let m = CHART_COLORS.len();
        color[c] = (0..m)
            .map(|k| (rank + k) % m)
            .find(|k| !taken.contains(k))
            .unwrap_or(rank % m);
    }
    label
        .iter()
        .map(|&l| CHART_COLORS[color[l as usize]])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::param::UvValues;

    #[test]
    fn quantile_nearest_rank() {
        let mut v: Vec<f64> = (1..=100).map(f64::from).collect();
        assert_eq!(quantile(&mut v, 0.99), 99.0);
        assert_eq!(quantile(&mut v, 1.0), 100.0);
        assert_eq!(quantile(&mut [], 0.5), 0.0);
    }
    /// Two triangles on the unit square, as a per-corner map: `apart` moves the second's
    /// images off the first's along their shared edge.
    fn square(apart: f64) -> (TriMesh, Vec<[Complex64; 3]>) {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let f = vec![[0, 1, 2], [0, 2, 3]];
        let mesh = TriMesh::try_new(p.clone(), f.clone()).expect("mesh");
        let z = |v: u32, d: f64| Complex64::new(p[v as usize][0] + d, p[v as usize][1]);
        let uv = vec![f[0].map(|v| z(v, 0.0)), f[1].map(|v| z(v, apart))];
        (mesh, uv)
    }

    #[test]
    fn charts_join_across_edges_whose_ends_agree_only() {
        let (mesh, joined) = square(0.0);
        let map = MapCoords::Planar(UvValues::PerCorner(&joined));
        assert_eq!(chart_labels(&mesh, &map), (vec![0, 0], 1));
        let (mesh, seam) = square(2.0);
        let map = MapCoords::Planar(UvValues::PerCorner(&seam));
        assert_eq!(chart_labels(&mesh, &map), (vec![0, 1], 2));
        // two charts across a seam get different colours
        let colors = chart_colors(&mesh, &map);
        assert_ne!(colors[0], colors[1]);
        // a per-vertex map is one chart
        let z: Vec<Complex64> = mesh
            .positions()
            .iter()
            .map(|q| Complex64::new(q[0], q[1]))
            .collect();
        let map = MapCoords::Planar(UvValues::PerVertex(&z));
        assert_eq!(chart_labels(&mesh, &map).1, 1);
    }
}
