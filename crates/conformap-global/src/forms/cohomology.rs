//! The cohomology basis dual to the tree–cotree generators, and the two bilinear forms of
//! closed 1-forms: the wedge integral `∫ α ∧ β` and the L² inner product `∫ α ∧ *β`.
//!
//! A 1-form is one value per edge of [`conformap_mesh::EdgeIndex`] (the integral along the
//! edge in its reference orientation). A closed form is the differential of a linear function
//! on each face, so both integrals are exact face sums.

use std::collections::{BinaryHeap, HashMap, VecDeque};

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
/// Only the dual-tree ancestors of the two faces beside `e_i` can get a nonzero value (a
/// face's parent edge carries the sum over its other edges), and the two paths cancel
/// where they meet: `ω_i` is `±1` on the dual path between those faces and zero elsewhere.
/// Each form is peeled along those paths alone (faces taken deepest first, so a face's
/// children come before it), `O(path)` per form after one breadth-first search of the
/// dual tree, instead of a pass over every face per form.
///
/// Returns the forms by their nonzero values ([`SparseCochain`]) and the largest `|dω|` left
/// on the root face of the dual tree (which closedness on all other faces determines; 0 on a
/// closed surface: the values are integers).
pub fn cohomology_basis(mesh: &TriMesh, basis: &HomologyBasis) -> (Vec<SparseCochain>, f64) {
    let edges = &basis.edges;
    let opp = mesh.opposite_halfedges();
    let nf = mesh.num_faces();
    // BFS over the dual tree from face 0: the order, each face's place in it and the
    // half-edge of each face that crosses to its parent
    let mut parent_h = vec![u32::MAX; nf];
    let mut place = vec![u32::MAX; nf];
    let mut order = Vec::with_capacity(nf);
    let mut queue = VecDeque::from([0usize]);
    place[0] = 0;
    while let Some(f) = queue.pop_front() {
        order.push(f);
        for k in 0..3 {
            let h = 3 * f + k;
            if !basis.in_cotree[edges.edge_of[h] as usize] {
                continue;
            }
            let o = opp[h] as usize;
            let g = o / 3;
            if place[g] == u32::MAX {
                place[g] = (order.len() + queue.len()) as u32;
                parent_h[g] = o as u32;
                queue.push_back(g);
            }
        }
    }
    let step = |h: usize| (edges.edge_of[h] as usize, edges.sign(h));
    let forms: Vec<SparseCochain> = basis
        .generators
        .par_iter()
        .map(|gen| {
            let mut w: HashMap<usize, f64> = HashMap::from([(gen.edge as usize, 1.0)]);
            let h = edges.halfedge[gen.edge as usize] as usize;
            // faces by their place in the BFS order, deepest (latest) first
            let mut active: BinaryHeap<u32> = [h, opp[h] as usize]
                .into_iter()
                .filter(|&x| x != NO_HALFEDGE as usize)
                .map(|x| place[x / 3])
                .collect();
            while let Some(p) = active.pop() {
                while active.peek() == Some(&p) {
                    active.pop();
                }
                let f = order[p as usize];
                if p == 0 {
                    continue; // the root: no parent edge
                }
                let ph = parent_h[f] as usize;
                // sign(ph) · w[e] + others = 0
                let mut others = 0.0;
                for x in (3 * f..3 * f + 3).filter(|&x| x != ph) {
                    let (e, s) = step(x);
                    others += s * w.get(&e).copied().unwrap_or(0.0);
                }
                let (e, sign) = step(ph);
                let value = -others * sign;
                if value != 0.0 {
                    w.insert(e, value);
                    active.push(place[opp[ph] as usize / 3]);
                }
            }
            let mut support: SparseCochain = w.into_iter().map(|(e, x)| (e as u32, x)).collect();
            support.sort_unstable_by_key(|&(e, _)| e);
            support
        })
        .collect();
    let mut root_residual = 0.0f64;
    for w in &forms {
        let root: f64 = (0..3)
            .map(|h| {
                let (e, s) = step(h);
                s * w
                    .binary_search_by_key(&(e as u32), |&(e, _)| e)
                    .map_or(0.0, |i| w[i].1)
            })
            .sum();
        root_residual = root_residual.max(root.abs());
    }
    (forms, root_residual)
}

/// A closed form's nonzero values, `(edge, value)` in edge order.
///
/// The basis forms of [`cohomology_basis`] are sparse: `±1` on the dual path between the two
/// faces beside their generator edge (≤ 1200 of 260 000 edges on armadillo's 15-slit
/// covering), so the bilinear forms of the basis are sums over a few hundred faces
/// ([`wedge_matrix`], `conjugate::gram_matrix`).
pub type SparseCochain = Vec<(u32, f64)>;

/// `W_kj = ∫ ω_k ∧ ω_j` of the cohomology basis `forms` (row-major, exactly antisymmetric),
/// summed over the faces beside their supports.
///
/// On a closed surface this is also the wedge matrix of the harmonic forms `h = ω + d f`:
/// the face value `½(a₁b₂ − a₂b₁)` of `∫ d f ∧ β` equals `½ Σ (f_i + f_j) β(i → j)` over the
/// face's three edges, and every edge appears in two faces with opposite orientations, so
/// the sum over a closed surface vanishes for every edge function `β`. The basis values are
/// small integers, so `W` comes out exactly (the intersection numbers), where the face sums of
/// the projected forms carry rounding.
pub fn wedge_matrix(mesh: &TriMesh, edges: &EdgeIndex, forms: &[SparseCochain]) -> Vec<f64> {
    let n = forms.len();
    let opp = mesh.opposite_halfedges();
    // every form's value on every edge of the supports, and the faces beside them
    let mut on_edge: HashMap<u32, Vec<(usize, f64)>> = HashMap::new();
    let mut faces = Vec::new();
    for (k, form) in forms.iter().enumerate() {
        for &(e, x) in form {
            on_edge.entry(e).or_default().push((k, x));
            let h = edges.halfedge[e as usize];
            faces.extend(
                [h, opp[h as usize]]
                    .into_iter()
                    .filter(|&h| h != NO_HALFEDGE)
                    .map(|h| h as usize / 3),
            );
        }
    }
    faces.sort_unstable();
    faces.dedup();
    // X_kj = Σ_f ω_k(v0 → v1) ω_j(v0 → v2), with ω(v0 → v1) = ω(h0), ω(v0 → v2) = −ω(h2)
    let values = |h: usize, sign: f64| {
        let s = sign * edges.sign(h);
        on_edge
            .get(&edges.edge_of[h])
            .into_iter()
            .flatten()
            .map(move |&(k, x)| (k, s * x))
    };
    let mut x = vec![0.0; n * n];
    for f in faces {
        for (k, a1) in values(3 * f, 1.0) {
            for (j, a2) in values(3 * f + 2, -1.0) {
                x[k * n + j] += a1 * a2;
            }
        }
    }
    let mut w = vec![0.0; n * n];
    for i in 0..n {
        for j in i + 1..n {
            let v = 0.5 * (x[i * n + j] - x[j * n + i]);
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
