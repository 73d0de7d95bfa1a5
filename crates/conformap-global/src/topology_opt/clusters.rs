//! The extreme points of a map (Jin et al. 2004, §3.5, "Locating the extreme points"):
//! clusters of vertices of most shrunken area, each cluster's area-weighted centre, the
//! cluster vertex nearest to it.
//!
//! The conformal factor is measured by areas: a vertex's *area ratio* is the image share
//! of its star over its surface share, `(Σ_{f∋v} a_f / Σa) / (Σ_{f∋v} S_f / ΣS)` — the
//! discrete `λ⁻²` of Eq. 12 (`λ` the 3D-over-image length ratio), computed the same way on
//! sphere maps (chord triangles) and on layouts (planar triangles, folded ones counted as
//! 0), so one threshold serves both.

use conformap_mesh::{Adjacency, TriMesh};
use conformap_operators::face_areas;

/// One cluster of extreme vertices.
#[derive(Debug, Clone, PartialEq)]
pub struct Cluster {
    /// The cluster's vertices, nearest to its area-weighted centre first (the first is the
    /// extreme point of the paper; the others are fall-backs for a slit).
    pub by_distance: Vec<u32>,
    /// Share of the surface area the cluster holds.
    pub area_fraction: f64,
    /// The smallest log area ratio in the cluster.
    pub min_log_ratio: f64,
}

/// `ln` of the area ratio of each vertex of `mesh` under the image face areas `image`
/// (one per face of `mesh`; negative areas count as 0). `−∞` for a vertex whose faces all
/// collapsed.
pub fn vertex_log_area_ratio(mesh: &TriMesh, image: &[f64]) -> Vec<f64> {
    let surface = face_areas(mesh);
    let (ta, ts): (f64, f64) = (image.iter().map(|a| a.max(0.0)).sum(), surface.iter().sum());
    let n = mesh.num_vertices();
    let (mut a, mut s) = (vec![0.0; n], vec![0.0; n]);
    for (f, t) in mesh.faces().iter().enumerate() {
        for &v in t {
            a[v as usize] += image[f].max(0.0) / ta;
            s[v as usize] += surface[f] / ts;
        }
    }
    a.iter().zip(&s).map(|(a, s)| (a / s).ln()).collect()
}

/// The 3D vertex areas (a third of the incident faces'), as shares of the surface area.
fn vertex_area_shares(mesh: &TriMesh) -> Vec<f64> {
    let surface = face_areas(mesh);
    let total: f64 = surface.iter().sum();
    let mut out = vec![0.0; mesh.num_vertices()];
    for (f, t) in mesh.faces().iter().enumerate() {
        for &v in t {
            out[v as usize] += surface[f] / (3.0 * total);
        }
    }
    out
}

/// The log-ratio threshold below which vertices are extreme: the largest value such that
/// the vertices at or below it hold at most `fraction` of the surface area, capped at
/// `ln(max_ratio)`. Vertices flagged in `excluded` neither count nor qualify.
pub fn extreme_threshold(
    mesh: &TriMesh,
    log_ratio: &[f64],
    excluded: &[bool],
    fraction: f64,
    max_ratio: f64,
) -> f64 {
    let share = vertex_area_shares(mesh);
    let mut order: Vec<usize> = (0..log_ratio.len()).filter(|&v| !excluded[v]).collect();
    order.sort_by(|&a, &b| log_ratio[a].total_cmp(&log_ratio[b]).then(a.cmp(&b)));
    let mut held = 0.0;
    let mut threshold = f64::NEG_INFINITY;
    for v in order {
        held += share[v];
        if held > fraction {
            break;
        }
        threshold = log_ratio[v];
    }
    threshold.min(max_ratio.ln())
}

/// The connected clusters (along mesh edges) of the vertices with `log_ratio ≤ threshold`
/// not flagged in `excluded`, most extreme first (by their smallest log ratio; ties by
/// vertex).
pub fn extreme_clusters(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    log_ratio: &[f64],
    excluded: &[bool],
    threshold: f64,
) -> Vec<Cluster> {
    let n = mesh.num_vertices();
    let share = vertex_area_shares(mesh);
    let hot = |v: usize| !excluded[v] && log_ratio[v] <= threshold;
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    for start in 0..n {
        if seen[start] || !hot(start) {
            continue;
        }
        seen[start] = true;
        let mut members = vec![start as u32];
        let mut i = 0;
        while i < members.len() {
            for &w in adjacency.neighbors_of(members[i] as usize) {
                if !seen[w as usize] && hot(w as usize) {
                    seen[w as usize] = true;
                    members.push(w);
                }
            }
            i += 1;
        }
        let area: f64 = members.iter().map(|&v| share[v as usize]).sum();
        let mut centre = [0.0; 3];
        for &v in &members {
            let p = mesh.positions()[v as usize];
            for k in 0..3 {
                centre[k] += p[k] * share[v as usize] / area;
            }
        }
        let d2 = |v: u32| {
            let p = mesh.positions()[v as usize];
            (0..3).map(|k| (p[k] - centre[k]).powi(2)).sum::<f64>()
        };
        members.sort_by(|&a, &b| d2(a).total_cmp(&d2(b)).then(a.cmp(&b)));
        let min_log_ratio = members
            .iter()
            .map(|&v| log_ratio[v as usize])
            .fold(f64::INFINITY, f64::min);
        out.push(Cluster {
            by_distance: members,
            area_fraction: area,
            min_log_ratio,
        });
    }
    out.sort_by(|a, b| {
        a.min_log_ratio
            .total_cmp(&b.min_log_ratio)
            .then(a.by_distance[0].cmp(&b.by_distance[0]))
    });
    out
}
