//! The quadratic objectives, solved exactly as symmetric eigenproblems in the whitened
//! coefficients: the emphasized area (Jin et al. 2004, Eq. 8–9) and the zero allocation
//! (Eq. 13–14).
//!
//! Both are ratios `λᵀ D λ / λᵀ C λ` of two `2g × 2g` forms (`C` the total layout area of
//! the user's faces); with `μ = C^{1/2} λ` the ratio is the Rayleigh quotient of
//! `D̃ = W D W`, whose extreme eigenvectors are the exact optima (no Newton needed, papers
//! README).

use conformap_mesh::{EdgeIndex, TriMesh};
use serde::{Deserialize, Serialize};

use crate::forms::dense::symmetric_eigen;
use crate::forms::optimal::products::AreaProducts;
use crate::forms::periods::ComplexCochain;

/// The emphasized-area result.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct EmphasisReport {
    /// Distinct faces in the region.
    pub region_faces: usize,
    /// Whether the region's share was maximized (else minimized).
    pub maximize: bool,
    /// The region's share of the parameter area of the user's faces for the chosen form.
    pub share: f64,
    /// The largest share any holomorphic form gives the region.
    pub share_max: f64,
    /// The smallest share.
    pub share_min: f64,
    /// The region's share of the surface area in `R³` (what a uniform map would give).
    pub surface_share: f64,
    /// All eigenvalues of the share form (ascending): for genus 1 they coincide.
    pub eigenvalues: Vec<f64>,
}

/// Extreme eigenpair of a symmetric `n × n` matrix: `(value, unit vector)`.
pub fn extreme_eigenpair(m: &[f64], n: usize, largest: bool) -> (f64, Vec<f64>, Vec<f64>) {
    let (eig, vecs) = symmetric_eigen(m, n);
    let pick = (0..n)
        .reduce(|a, b| {
            let better = if largest {
                eig[b] > eig[a]
            } else {
                eig[b] < eig[a]
            };
            if better {
                b
            } else {
                a
            }
        })
        .unwrap_or(0);
    let v = (0..n).map(|i| vecs[i * n + pick]).collect();
    let mut sorted = eig.clone();
    sorted.sort_by(f64::total_cmp);
    (eig[pick], v, sorted)
}

/// The form maximizing (or minimizing) the parameter-area share of `region` (a mask over
/// the user's faces): `(whitened coefficients, report)`.
pub fn emphasize(p: &AreaProducts, region: &[bool], maximize: bool) -> (Vec<f64>, EmphasisReport) {
    let n = p.n;
    let d = p.sum_over((0..p.faces()).filter(|&f| region[f]));
    let (share, mu, eigenvalues) = extreme_eigenpair(&d, n, maximize);
    let surface_share = (0..p.faces()).filter(|&f| region[f]).map(|f| p.s[f]).sum();
    let report = EmphasisReport {
        region_faces: region.iter().filter(|&&x| x).count(),
        maximize,
        share,
        share_max: eigenvalues.last().copied().unwrap_or(f64::NAN),
        share_min: eigenvalues.first().copied().unwrap_or(f64::NAN),
        surface_share,
        eigenvalues,
    };
    (mu, report)
}

/// `|ω(v)|²` of Eq. 14 made a quadratic form: the mean over the edges `e` at each target
/// of `|φ(e)|² / |e|²` (the square of the paper's edge mean, taken inside the mean so that
/// it is quadratic in the coefficients), summed over the targets, in whitened coordinates.
pub fn zero_form(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    forms: &[ComplexCochain],
    p: &AreaProducts,
    targets: &[usize],
) -> Vec<f64> {
    let n = p.n;
    let mut is_target = vec![false; mesh.num_vertices()];
    for &v in targets {
        is_target[v] = true;
    }
    let mut degree = vec![0usize; mesh.num_vertices()];
    let mut per_vertex: Vec<Option<Vec<f64>>> = vec![None; mesh.num_vertices()];
    for (e, &h) in edges.halfedge.iter().enumerate() {
        let (a, b) = mesh.halfedge_vertices(h as usize);
        if !(is_target[a as usize] || is_target[b as usize]) {
            continue;
        }
        let (pa, pb) = (mesh.positions()[a as usize], mesh.positions()[b as usize]);
        let len2 = (0..3).map(|i| (pa[i] - pb[i]).powi(2)).sum::<f64>();
        let z = p.whitened_edge(forms, e);
        for v in [a as usize, b as usize] {
            if !is_target[v] {
                continue;
            }
            degree[v] += 1;
            let m = per_vertex[v].get_or_insert_with(|| vec![0.0; n * n]);
            for k in 0..n {
                for j in 0..n {
                    m[k * n + j] += (z[k].conj() * z[j]).re / len2;
                }
            }
        }
    }
    let mut total = vec![0.0; n * n];
    for &v in targets {
        if let Some(m) = &per_vertex[v] {
            for (t, x) in total.iter_mut().zip(m) {
                *t += x / degree[v] as f64;
            }
        }
    }
    total
}

/// Edge-ring distance (breadth-first over the edges of `mesh`) from `source` to the nearest
/// vertex in `goal`, with that vertex; `None` if no goal vertex is reachable.
pub fn ring_distance(mesh: &TriMesh, source: usize, goal: &[bool]) -> Option<(usize, usize)> {
    let nv = mesh.num_vertices();
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for t in mesh.faces() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            adj[a as usize].push(b);
            adj[b as usize].push(a);
        }
    }
    let mut dist = vec![usize::MAX; nv];
    let mut queue = std::collections::VecDeque::from([source]);
    dist[source] = 0;
    while let Some(v) = queue.pop_front() {
        if goal[v] {
            return Some((dist[v], v));
        }
        for &w in &adj[v] {
            let w = w as usize;
            if dist[w] == usize::MAX {
                dist[w] = dist[v] + 1;
                queue.push_back(w);
            }
        }
    }
    None
}
