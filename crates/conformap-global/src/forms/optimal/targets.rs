//! Zero allocation (Jin et al. 2004, §3.6, Eq. 13–14) as linear conditions: the value
//! `ω(v)` of a form at a vertex, and the most uniform form among those vanishing at the
//! targets.
//!
//! Near a vertex `v` a holomorphic form is `ω = c dz` in a conformal chart: on each edge
//! `e` of the star, `φ(e) ≈ c · ẽ`, where `ẽ` is the edge vector projected to the tangent
//! plane as a complex number (the frame oriented by the surface's normal, so that a
//! positive layout area means `c` and not `c̄`). The least-squares fit
//! `c(v) = Σ conj(ẽ) φ(e) / Σ |ẽ|²` is linear in the coefficients, so "a zero at `v`" is
//! two real linear equations (`Re c = Im c = 0`). With `t` targets on a genus-`g` surface
//! the forms satisfying them form a subspace of dimension `2g − 2t` (even: the conditions
//! are invariant under `φ → iφ`); for `t ≤ g − 1` it is not empty, and the most uniform form
//! in it is found by the same multistart as [`super::Objective::Uniform`], on the
//! restricted area forms. Minimizing `Σ |ω(v_i)|²` instead (the paper's Eq. 14 as a
//! Rayleigh quotient) lets the form shrink a whole tube around a target, without a zero at
//! it (measured on fertility: 2 of 20 targets 5 and 16 edge rings from the nearest zero);
//! the exact conditions put a zero at the target by construction. Beyond `g − 1` targets
//! no form vanishes at all of them and the Rayleigh quotient's minimum is the compromise.

use conformap_mesh::{EdgeIndex, TriMesh};
use conformap_operators::vec3::{cross, dot, sub};
use num_complex::Complex64;

use crate::forms::dense::symmetric_eigen;
use crate::forms::optimal::products::AreaProducts;
use crate::forms::periods::ComplexCochain;

/// `c_k(v)` for each whitened basis form `k`: the fitted value `ω(v)` at vertex `v`.
pub fn vertex_values(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    forms: &[ComplexCochain],
    p: &AreaProducts,
    v: usize,
) -> Vec<Complex64> {
    let pos = mesh.positions();
    // the area-weighted normal of the star, oriented as the faces are
    let mut normal = [0.0; 3];
    for t in mesh.faces() {
        if t.contains(&(v as u32)) {
            let [a, b, c] = t.map(|i| pos[i as usize]);
            let x = cross(sub(b, a), sub(c, a));
            for i in 0..3 {
                normal[i] += x[i];
            }
        }
    }
    let len = dot(normal, normal).sqrt();
    let n = normal.map(|x| x / len);
    // a tangent frame (t1, t2 = n × t1)
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t1 = {
        let x = cross(helper, n);
        let l = dot(x, x).sqrt();
        x.map(|c| c / l)
    };
    let t2 = cross(n, t1);
    let mut num = vec![Complex64::default(); p.n];
    let mut den = 0.0;
    for (e, &h) in edges.halfedge.iter().enumerate() {
        let (a, b) = mesh.halfedge_vertices(h as usize);
        let (from, to, sign) = if a as usize == v {
            (a, b, 1.0)
        } else if b as usize == v {
            (b, a, -1.0)
        } else {
            continue;
        };
        let d = sub(pos[to as usize], pos[from as usize]);
        let z = Complex64::new(dot(d, t1), dot(d, t2));
        den += z.norm_sqr();
        for (acc, phi) in num.iter_mut().zip(p.whitened_edge(forms, e)) {
            *acc += z.conj() * phi * sign;
        }
    }
    num.into_iter().map(|x| x / den).collect()
}

/// The conditions `Re c(v_i) = Im c(v_i) = 0` as the Gram matrix `Σ rᵀr` of their rows
/// (`n × n`, whitened coordinates): `μᵀ M μ = Σ_i |ω(v_i)|²`.
pub fn condition_gram(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    forms: &[ComplexCochain],
    p: &AreaProducts,
    targets: &[usize],
) -> Vec<f64> {
    let n = p.n;
    let mut m = vec![0.0; n * n];
    for &v in targets {
        let c = vertex_values(mesh, edges, forms, p, v);
        for i in 0..n {
            for j in 0..n {
                m[i * n + j] += (c[i].conj() * c[j]).re;
            }
        }
    }
    m
}

/// An orthonormal basis (`n × d`, row-major) of the `d` eigenvectors of the smallest
/// eigenvalues of the symmetric `m`: the forms (nearly) satisfying the conditions.
pub fn null_space(m: &[f64], n: usize, d: usize) -> Vec<f64> {
    let (eig, vecs) = symmetric_eigen(m, n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig[a].total_cmp(&eig[b]));
    let mut basis = vec![0.0; n * d];
    for (col, &k) in order.iter().take(d).enumerate() {
        for i in 0..n {
            basis[i * d + col] = vecs[i * n + k];
        }
    }
    basis
}

/// `p` restricted to the subspace `μ = N ν` (`N` orthonormal, `n × d`): per-face forms
/// `Nᵀ Q̃_f N`, whose sum is again the identity, so the unit sphere of `ν` is the area
/// constraint. Its `w` is the identity: its "basis forms" are the columns of `N`.
pub fn restricted(p: &AreaProducts, basis: &[f64], d: usize) -> AreaProducts {
    let n = p.n;
    let mut q = vec![0.0; p.faces() * d * d];
    let mut qn = vec![0.0; n * d];
    for f in 0..p.faces() {
        let src = p.face(f);
        for i in 0..n {
            for c in 0..d {
                qn[i * d + c] = (0..n).map(|k| src[i * n + k] * basis[k * d + c]).sum();
            }
        }
        let dst = &mut q[f * d * d..(f + 1) * d * d];
        for r in 0..d {
            for c in 0..d {
                dst[r * d + c] = (0..n).map(|k| basis[k * d + r] * qn[k * d + c]).sum();
            }
        }
    }
    let mut w = vec![0.0; d * d];
    for i in 0..d {
        w[i * d + i] = 1.0;
    }
    AreaProducts {
        n: d,
        q,
        s: p.s.clone(),
        w,
    }
}

/// `μ = N ν`.
pub fn lift(basis: &[f64], nu: &[f64], n: usize) -> Vec<f64> {
    let d = nu.len();
    (0..n)
        .map(|i| (0..d).map(|c| basis[i * d + c] * nu[c]).sum())
        .collect()
}
