//! The cohomology basis dual to the tree–cotree generators, and the two bilinear forms of
//! closed 1-forms: the wedge integral `∫ α ∧ β` and the L² inner product `∫ α ∧ *β`.
//!
//! A 1-form is one value per edge of [`conformap_mesh::EdgeIndex`] (the integral along the
//! edge in its reference orientation). A closed form is the differential of a linear function
//! on each face, so both integrals are exact face sums.

use std::collections::VecDeque;

use conformap_mesh::{EdgeIndex, HomologyBasis, TriMesh, NO_HALFEDGE};
use conformap_operators::corner_cotangents;
use rayon::prelude::*;

/// A real 1-form: one value per edge.
pub type Cochain = Vec<f64>;

/// The closed 1-forms `ω_i`, one per generator, with `ω_i(e_j) = δ_ij` on the generator
/// edges, 0 on the tree, and the cotree edges fixed by closedness (`dω = 0` on every face),
/// peeled from the leaves of the dual tree to its root. Each `ω_i` integrates to `δ_ij`
/// along generator loop `j` (the loop crosses only tree edges and `e_j`), so the basis is
/// dual to the homology basis and no `ω_i` is exact.
///
/// Returns the forms and the largest `|dω|` left on the root face of the dual tree (which
/// closedness on all other faces determines; rounding level on a closed surface).
pub fn cohomology_basis(mesh: &TriMesh, basis: &HomologyBasis) -> (Vec<Cochain>, f64) {
    let edges = &basis.edges;
    let opp = mesh.opposite_halfedges();
    let nf = mesh.num_faces();
    // BFS over the dual tree from face 0: the order and the half-edge of each face that
    // crosses to its parent
    let mut parent_h = vec![u32::MAX; nf];
    let mut seen = vec![false; nf];
    let mut order = Vec::with_capacity(nf);
    let mut queue = VecDeque::from([0usize]);
    seen[0] = true;
    while let Some(f) = queue.pop_front() {
        order.push(f);
        for k in 0..3 {
            let h = 3 * f + k;
            if !basis.in_cotree[edges.edge_of[h] as usize] {
                continue;
            }
            let o = opp[h] as usize;
            let g = o / 3;
            if !seen[g] {
                seen[g] = true;
                parent_h[g] = o as u32;
                queue.push_back(g);
            }
        }
    }
    // the peeling schedule: per face, from the leaves of the dual tree to its root, the
    // edge set by closedness (with its sign) and the face's two other edges
    let step = |h: usize| (edges.edge_of[h], edges.sign(h));
    let schedule: Vec<[(u32, f64); 3]> = order
        .iter()
        .skip(1)
        .rev()
        .map(|&f| {
            let ph = parent_h[f] as usize;
            let mut others = (3 * f..3 * f + 3).filter(|&h| h != ph).map(step);
            let first = others.next().unwrap_or((0, 0.0));
            let second = others.next().unwrap_or((0, 0.0));
            [step(ph), first, second]
        })
        .collect();
    // one form per thread, form-major: each pass reads the schedule in order and touches
    // one `edges`-long vector, which stays in cache (the edge-major `edges × n` array of
    // all forms at once was read at random, a cache miss per row)
    let forms: Vec<Cochain> = basis
        .generators
        .par_iter()
        .map(|gen| {
            let mut w = vec![0.0; edges.len()];
            w[gen.edge as usize] = 1.0;
            for &[(e, sign), (e1, s1), (e2, s2)] in &schedule {
                // sign(ph) · w[e] + others = 0
                let others = 0.0 + s1 * w[e1 as usize] + s2 * w[e2 as usize];
                w[e as usize] = -others * sign;
            }
            w
        })
        .collect();
    let mut root_residual = 0.0f64;
    for w in &forms {
        let root: f64 = (0..3)
            .map(|h| edges.sign(h) * w[edges.edge_of[h] as usize])
            .sum();
        root_residual = root_residual.max(root.abs());
    }
    (forms, root_residual)
}

/// A closed form's nonzero values, `(edge, value)` in edge order.
///
/// The basis forms of [`cohomology_basis`] are sparse: zero on the tree, `±1` along the two
/// dual paths from their generator edge to the dual root (≤ 1200 of 260 000 edges on
/// armadillo's 15-slit covering), so the bilinear forms of the basis are sums over a few
/// hundred faces ([`wedge_matrix`], `conjugate::gram_matrix`).
pub type SparseCochain = Vec<(u32, f64)>;

/// The nonzero values of `form`.
pub fn sparse(form: &[f64]) -> SparseCochain {
    form.iter()
        .enumerate()
        .filter(|(_, x)| **x != 0.0)
        .map(|(e, &x)| (e as u32, x))
        .collect()
}

/// `W_kj = ∫ ω_k ∧ ω_j` of the cohomology basis (row-major, exactly antisymmetric), summed
/// over the faces next to each form's support (`sparse[k]`, with `closed[j]` read densely).
///
/// On a closed surface this is also the wedge matrix of the harmonic forms `h = ω + d f`:
/// the face value `½(a₁b₂ − a₂b₁)` of `∫ d f ∧ β` equals `½ Σ (f_i + f_j) β(i → j)` over the
/// face's three edges, and every edge appears in two faces with opposite orientations, so
/// the sum over a closed surface vanishes for every edge function `β`. The basis values are
/// small integers, so `W` comes out exactly (the intersection numbers), where the face sums of
/// the projected forms carry rounding.
pub fn wedge_matrix(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    closed: &[Cochain],
    sparse: &[SparseCochain],
) -> Vec<f64> {
    let n = closed.len();
    let opp = mesh.opposite_halfedges();
    let rows: Vec<Vec<f64>> = sparse
        .par_iter()
        .zip(closed)
        .map(|(support, own)| {
            let mut faces: Vec<usize> = support
                .iter()
                .flat_map(|&(e, _)| {
                    let h = edges.halfedge[e as usize];
                    [h, opp[h as usize]]
                })
                .filter(|&h| h != NO_HALFEDGE)
                .map(|h| h as usize / 3)
                .collect();
            faces.sort_unstable();
            faces.dedup();
            // ω(v0 → v1) = ω(h0), ω(v0 → v2) = −ω(h2)
            let ends = |form: &[f64], f: usize| {
                (
                    edges.on_halfedge(form, 3 * f),
                    -edges.on_halfedge(form, 3 * f + 2),
                )
            };
            closed
                .iter()
                .map(|other| {
                    faces
                        .iter()
                        .map(|&f| {
                            let (a1, a2) = ends(own, f);
                            let (b1, b2) = ends(other, f);
                            0.5 * (a1 * b2 - a2 * b1)
                        })
                        .sum()
                })
                .collect()
        })
        .collect();
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        for j in i + 1..n {
            let v = 0.5 * (rows[i][j] - rows[j][i]);
            w[i * n + j] = v;
            w[j * n + i] = -v;
        }
    }
    w
}

/// The cotangent weight `½(cot α + cot β)` of every edge (the negated off-diagonal of the
/// cotangent Laplacian, CEM Eq. 6; one angle's half on a boundary edge).
pub fn edge_weights(mesh: &TriMesh, basis: &HomologyBasis) -> Vec<f64> {
    let mut w = vec![0.0; basis.edges.len()];
    for (f, c) in corner_cotangents(mesh).iter().enumerate() {
        for k in 0..3 {
            // the corner k faces the half-edge from corner k + 1 to corner k + 2
            let h = 3 * f + (k + 1) % 3;
            w[basis.edges.edge_of[h] as usize] += 0.5 * c[k];
        }
    }
    w
}

/// `∫ α ∧ *β = Σ_e w_e α(e) β(e)` for closed forms: the L² inner product (the cotangent
/// formula for the Dirichlet energy of the face-wise linear primitives). The pair-by-pair
/// reference of the sparse `wedge_matrix` and `conjugate::gram_matrix` (tests only).
#[cfg(test)]
pub fn inner_product(weights: &[f64], a: &[f64], b: &[f64]) -> f64 {
    weights
        .iter()
        .zip(a.iter().zip(b))
        .map(|(w, (x, y))| w * x * y)
        .sum()
}

/// `∫ α ∧ β` for closed forms over the faces in `faces`: on face `(v0, v1, v2)` with
/// `a_k = α(v0 → v_k)`, `b_k = β(v0 → v_k)` it is `½(a_1 b_2 − a_2 b_1)`, the signed area of
/// the face's image under the primitive `(∫α, ∫β)`. The pair-by-pair reference of
/// the sparse `wedge_matrix` (tests only).
#[cfg(test)]
pub fn wedge(basis: &HomologyBasis, faces: std::ops::Range<usize>, a: &[f64], b: &[f64]) -> f64 {
    let e = &basis.edges;
    faces
        .map(|f| {
            // α(v0 → v1) = α(h0), α(v0 → v2) = −α(h2)
            let (a1, a2) = (e.on_halfedge(a, 3 * f), -e.on_halfedge(a, 3 * f + 2));
            let (b1, b2) = (e.on_halfedge(b, 3 * f), -e.on_halfedge(b, 3 * f + 2));
            0.5 * (a1 * b2 - a2 * b1)
        })
        .sum()
}
