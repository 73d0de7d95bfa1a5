//! Integration of a closed complex 1-form over the fundamental domain (the cut mesh): one
//! UV per cut vertex, hence per corner; across every seam the two sides differ by a pure
//! translation (a period).

use std::collections::VecDeque;

use conformap_mesh::{CutMesh, EdgeIndex, TriMesh};
use num_complex::Complex64;

/// A layout of the cut mesh.
#[derive(Debug, Clone)]
pub struct Layout {
    /// UV of every corner: `corner_uv[3 f + k]` for corner `k` of face `f`.
    pub corner_uv: Vec<Complex64>,
    /// Diagonal of the layout's bounding box.
    pub diagonal: f64,
    /// Largest `|t_a − t_b|` over seam edges `(a, b)`, where `t_x` is the offset between the
    /// two copies of `x` across the seam, divided by [`Self::diagonal`]: 0 for a pure
    /// translation, rounding level in practice.
    pub seam_residual: f64,
    /// Seam edges.
    pub seam_edges: usize,
}

/// Integrates `form` (one value per input edge of `edges`) from cut vertex 0 (at UV 0)
/// along a breadth-first tree of the cut mesh's edges. The cut mesh's half-edge `3 f + k`
/// is the input's, so `form` is read through the input edge numbering.
pub fn integrate(mesh: &TriMesh, cut: &CutMesh, edges: &EdgeIndex, form: &[Complex64]) -> Layout {
    let cm = &cut.mesh;
    let nv = cm.num_vertices();
    // outgoing half-edges of each cut vertex
    let mut offsets = vec![0usize; nv + 1];
    for t in cm.faces() {
        for &v in t {
            offsets[v as usize + 1] += 1;
        }
    }
    for v in 0..nv {
        offsets[v + 1] += offsets[v];
    }
    let mut fill = offsets.clone();
    let mut out = vec![0u32; offsets[nv]];
    for (f, t) in cm.faces().iter().enumerate() {
        for k in 0..3 {
            out[fill[t[k] as usize]] = (3 * f + k) as u32;
            fill[t[k] as usize] += 1;
        }
    }
    let value = |h: usize| edges.sign(h) * form[edges.edge_of[h] as usize];
    let mut uv = vec![Complex64::new(0.0, 0.0); nv];
    let mut seen = vec![false; nv];
    let mut queue = VecDeque::from([0usize]);
    seen[0] = true;
    while let Some(v) = queue.pop_front() {
        for &h in &out[offsets[v]..offsets[v + 1]] {
            let (_, w) = cm.halfedge_vertices(h as usize);
            let w = w as usize;
            if !seen[w] {
                seen[w] = true;
                uv[w] = uv[v] + value(h as usize);
                queue.push_back(w);
            }
        }
    }
    let corner_uv: Vec<Complex64> = cm
        .faces()
        .iter()
        .flat_map(|t| t.iter().map(|&v| uv[v as usize]))
        .collect();
    let (mut lo, mut hi) = (
        Complex64::new(f64::INFINITY, f64::INFINITY),
        Complex64::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for z in &uv {
        lo = Complex64::new(lo.re.min(z.re), lo.im.min(z.im));
        hi = Complex64::new(hi.re.max(z.re), hi.im.max(z.im));
    }
    let diagonal = (hi - lo).norm();
    let (seam_residual, seam_edges) = seam_check(mesh, cut, edges, &corner_uv);
    Layout {
        corner_uv,
        diagonal,
        seam_residual: if diagonal > 0.0 {
            seam_residual / diagonal
        } else {
            seam_residual
        },
        seam_edges,
    }
}

/// The largest difference between the offsets at the two ends of a seam edge.
fn seam_check(
    mesh: &TriMesh,
    cut: &CutMesh,
    edges: &EdgeIndex,
    corner_uv: &[Complex64],
) -> (f64, usize) {
    let opp = mesh.opposite_halfedges();
    let mut worst = 0.0f64;
    let mut count = 0;
    for (e, &h) in edges.halfedge.iter().enumerate() {
        if !cut.on_cut[e] || opp[h as usize] == conformap_mesh::NO_HALFEDGE {
            continue;
        }
        count += 1;
        let (h, o) = (h as usize, opp[h as usize] as usize);
        // h = a → b in face f (corners k, k+1); o = b → a in face g (corners m, m+1)
        let (f, k, g, m) = (h / 3, h % 3, o / 3, o % 3);
        let ta = corner_uv[3 * g + (m + 1) % 3] - corner_uv[3 * f + k];
        let tb = corner_uv[3 * g + m] - corner_uv[3 * f + (k + 1) % 3];
        worst = worst.max((ta - tb).norm());
    }
    (worst, count)
}
