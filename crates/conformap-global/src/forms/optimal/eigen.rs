//! The quadratic objectives, solved exactly as symmetric eigenproblems in the whitened
//! coefficients: the emphasized area (Jin et al. 2004, Eq. 8–9) and the zero allocation
//! (Eq. 13–14).
//!
//! Both are ratios `λᵀ D λ / λᵀ C λ` of two `2g × 2g` forms (`C` the total layout area of
//! the user's faces); with `μ = C^{1/2} λ` the ratio is the Rayleigh quotient of
//! `D̃ = W D W`, whose extreme eigenvectors are the exact optima (no Newton needed, papers
//! README).

use conformap_mesh::TriMesh;
use serde::{Deserialize, Serialize};

use crate::forms::dense::symmetric_eigen;
use crate::forms::optimal::products::AreaProducts;

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
