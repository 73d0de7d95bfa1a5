//! Zeros of a holomorphic 1-form found by the winding of its layout, and the conformal
//! factor per vertex (Jin et al. 2004, Eq. 12).
//!
//! The signed corner angles of the layout around a vertex add up to `2π w` with an integer
//! winding `w` (the link polygon's winding around the vertex's image). A discrete zero
//! usually falls inside a face: the layout folds the one or two faces there and spreads the
//! excess angle over their vertices, so a cone-angle threshold misses it. Here the vertices
//! with `w ≠ 1` and the vertices of folded faces are grouped into edge-connected clusters;
//! a cluster carries multiplicity `Σ (w − 1) + folded faces`, and on a closed surface the
//! clusters' multiplicities add up to `2g − 2` (Σ_v w_v = F/2 − F_folded and
//! F/2 − V = 2g − 2). A cluster of positive multiplicity is a zero; a fold in a cluster of
//! multiplicity ≤ 0 is a defect.

use conformap_mesh::{EdgeIndex, TriMesh};
use conformap_operators::planar::triangle_signed_area;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// One zero of the form.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct Zero {
    /// The cluster's vertex of smallest stretch `|φ|/|dr|` (nearest the zero).
    pub vertex: usize,
    /// Its order (`Σ (w − 1) + folded faces` over the cluster).
    pub multiplicity: i64,
    /// Vertices of the cluster.
    pub cluster_vertices: Vec<usize>,
    /// Folded faces in the cluster.
    pub folded_faces: usize,
}

/// The zeros and folds of a layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct ZeroReport {
    /// Zeros (clusters of positive multiplicity), by vertex.
    pub zeros: Vec<Zero>,
    /// `Σ` multiplicity over the zeros (`2g − 2` on a closed surface when no cluster has
    /// negative multiplicity).
    pub multiplicity_sum: i64,
    /// Faces with non-positive signed layout area.
    pub folded_faces: usize,
    /// Folded faces inside zero clusters (the zeros themselves).
    pub folds_at_zeros: usize,
    /// Folded faces in clusters of multiplicity ≤ 0: defects.
    pub folds_outside_zeros: usize,
    /// Clusters of negative multiplicity (poles: a defect of the discrete form).
    pub negative_clusters: usize,
    /// Largest distance of a vertex's angle sum / 2π from its integer winding (rounding
    /// level unless the layout is broken).
    pub winding_residual: f64,
    /// Per vertex: whether it lies in a zero cluster.
    #[serde(skip)]
    pub in_zero_cluster: Vec<bool>,
}

/// Signed angle at `p0` of triangle `(p0, p1, p2)`.
pub(crate) fn signed_angle(p0: Complex64, p1: Complex64, p2: Complex64) -> f64 {
    let (u, v) = (p1 - p0, p2 - p0);
    (u.re * v.im - u.im * v.re).atan2(u.re * v.re + u.im * v.im)
}

/// Per vertex, the mean of `|φ(e)| / |e|` over its edges: the stretch of the layout,
/// `1/λ` of Eq. 12 in the mean, finite everywhere and 0 where the form vanishes.
pub fn vertex_stretch(mesh: &TriMesh, edges: &EdgeIndex, form: &[Complex64]) -> Vec<f64> {
    let n = mesh.num_vertices();
    let (mut sum, mut count) = (vec![0.0; n], vec![0usize; n]);
    for (e, &h) in edges.halfedge.iter().enumerate() {
        let (a, b) = mesh.halfedge_vertices(h as usize);
        let len = dist(mesh, a, b);
        let s = form[e].norm() / len;
        for v in [a, b] {
            sum[v as usize] += s;
            count[v as usize] += 1;
        }
    }
    sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect()
}

/// The conformal factor of Eq. 12: `λ(v) = (1/n) Σ_{edges (v, v_i)} |r(v_i) − r(v)| /
/// |φ([v_i, v])|`, `+∞` where an edge's form value is exactly 0.
pub fn conformal_factor(mesh: &TriMesh, edges: &EdgeIndex, form: &[Complex64]) -> Vec<f64> {
    let n = mesh.num_vertices();
    let (mut sum, mut count) = (vec![0.0; n], vec![0usize; n]);
    for (e, &h) in edges.halfedge.iter().enumerate() {
        let (a, b) = mesh.halfedge_vertices(h as usize);
        let len = dist(mesh, a, b);
        let w = form[e].norm();
        let s = if w > 0.0 { len / w } else { f64::INFINITY };
        for v in [a, b] {
            sum[v as usize] += s;
            count[v as usize] += 1;
        }
    }
    sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect()
}

fn dist(mesh: &TriMesh, a: u32, b: u32) -> f64 {
    let (p, q) = (mesh.positions()[a as usize], mesh.positions()[b as usize]);
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The windings, folds and zero clusters of the layout `corner_uv` (per corner) of `mesh`;
/// `stretch` (per vertex, [`vertex_stretch`]) picks each zero's vertex.
pub fn find_zeros(mesh: &TriMesh, corner_uv: &[Complex64], stretch: &[f64]) -> ZeroReport {
    let n = mesh.num_vertices();
    // the corner angles (three `atan2` per face, most of the search's time) in parallel,
    // then summed per vertex in face order as before (the same sums, bit for bit)
    let corners: Vec<([f64; 3], bool)> = (0..mesh.num_faces())
        .into_par_iter()
        .with_min_len(4096)
        .map(|f| {
            let p = [corner_uv[3 * f], corner_uv[3 * f + 1], corner_uv[3 * f + 2]];
            let a = [0, 1, 2].map(|k| signed_angle(p[k], p[(k + 1) % 3], p[(k + 2) % 3]));
            (a, !(triangle_signed_area(p[0], p[1], p[2]) > 0.0))
        })
        .collect();
    let mut angle = vec![0.0; n];
    for (t, (a, _)) in mesh.faces().iter().zip(&corners) {
        for k in 0..3 {
            angle[t[k] as usize] += a[k];
        }
    }
    let folded: Vec<bool> = corners.iter().map(|c| c.1).collect();
    let tau = std::f64::consts::TAU;
    let winding: Vec<i64> = angle.iter().map(|a| (a / tau).round() as i64).collect();
    let winding_residual = angle
        .iter()
        .zip(&winding)
        .map(|(a, &w)| (a / tau - w as f64).abs())
        .fold(0.0, f64::max);
    let mut special: Vec<bool> = winding.iter().map(|&w| w != 1).collect();
    for (f, t) in mesh.faces().iter().enumerate() {
        if folded[f] {
            for &v in t {
                special[v as usize] = true;
            }
        }
    }
    // clusters: components of the special vertices along edges
    let mut label = vec![usize::MAX; n];
    // the adjacency only when there is a cluster to grow (a genus-1 form has none)
    let adj = special.contains(&true).then(|| mesh.vertex_adjacency());
    let mut clusters: Vec<Vec<usize>> = Vec::new();
    for s in 0..n {
        if !special[s] || label[s] != usize::MAX {
            continue;
        }
        let id = clusters.len();
        let mut members = vec![s];
        label[s] = id;
        let mut i = 0;
        while i < members.len() {
            let v = members[i];
            i += 1;
            for &w in adj.as_ref().map_or(&[][..], |a| a.neighbors_of(v)) {
                let w = w as usize;
                if special[w] && label[w] == usize::MAX {
                    label[w] = id;
                    members.push(w);
                }
            }
        }
        members.sort_unstable();
        clusters.push(members);
    }
    let mut folds_in = vec![0usize; clusters.len()];
    for (f, t) in mesh.faces().iter().enumerate() {
        if folded[f] {
            folds_in[label[t[0] as usize]] += 1;
        }
    }
    let mut report = ZeroReport {
        zeros: Vec::new(),
        multiplicity_sum: 0,
        folded_faces: folded.iter().filter(|&&x| x).count(),
        folds_at_zeros: 0,
        folds_outside_zeros: 0,
        negative_clusters: 0,
        winding_residual,
        in_zero_cluster: vec![false; n],
    };
    for (c, members) in clusters.into_iter().enumerate() {
        let m: i64 = members.iter().map(|&v| winding[v] - 1).sum::<i64>() + folds_in[c] as i64;
        if m > 0 {
            let vertex = members
                .iter()
                .copied()
                .min_by(|&a, &b| stretch[a].total_cmp(&stretch[b]))
                .unwrap_or(members[0]);
            for &v in &members {
                report.in_zero_cluster[v] = true;
            }
            report.multiplicity_sum += m;
            report.folds_at_zeros += folds_in[c];
            report.zeros.push(Zero {
                vertex,
                multiplicity: m,
                cluster_vertices: members,
                folded_faces: folds_in[c],
            });
        } else {
            report.folds_outside_zeros += folds_in[c];
            if m < 0 {
                report.negative_clusters += 1;
            }
        }
    }
    report.zeros.sort_by_key(|z| z.vertex);
    report
}
