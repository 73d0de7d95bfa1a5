//! The last resort of the overlap splits ([`super::split::split_overlapping`]): a piece
//! whose boundary still crosses itself where no interior path separates the crossing (a
//! strip one face wide, a piece with a hole) or after [`super::split::MAX_SPLIT_DEPTH`]
//! levels is grown again from its faces into regions whose triangles have pairwise
//! disjoint interiors. Every face keeps its layout, so the seams between regions keep
//! their lengths exactly; a region takes a face across one of its edges only when the
//! face's other vertices are not in it yet (or are the ends of edges it shares too), so
//! every region is a manifold, never pinched at a vertex.

use std::collections::VecDeque;

use conformap_mesh::NO_HALFEDGE;
use num_complex::Complex64;

use super::piece::{sub_piece, Piece};
use crate::error::AtlasError;

/// `piece` as regions without overlap (see the module).
///
/// # Errors
/// [`AtlasError::Mesh`] should a region fail validation (regions are manifold by
/// construction).
pub(crate) fn regrow(piece: &Piece) -> Result<Vec<Piece>, AtlasError> {
    let mesh = &piece.mesh;
    let faces = mesh.faces();
    let opp = mesh.opposite_halfedges();
    let tri = |f: usize| faces[f].map(|v| piece.uv[v as usize]);
    let mut region = vec![usize::MAX; faces.len()];
    // the region a vertex was last put in
    let mut stamp = vec![usize::MAX; mesh.num_vertices()];
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for seed in 0..faces.len() {
        if region[seed] != usize::MAX {
            continue;
        }
        let id = groups.len();
        region[seed] = id;
        faces[seed].iter().for_each(|&v| stamp[v as usize] = id);
        let mut group = vec![seed as u32];
        let mut boxes = vec![bounds(&tri(seed))];
        let mut queue = VecDeque::from([seed]);
        // a face turned over joins nothing (it is the flips' count, not an overlap)
        if signed_area(&tri(seed)) <= 0.0 {
            queue.clear();
        }
        while let Some(f) = queue.pop_front() {
            for k in 0..3 {
                let o = opp[3 * f + k];
                if o == NO_HALFEDGE || region[o as usize / 3] != usize::MAX {
                    continue;
                }
                let g = o as usize / 3;
                let t = tri(g);
                if signed_area(&t) <= 0.0 {
                    continue;
                }
                // the ends of g's edges shared with the region: g's only vertices there
                let mut shared = [false; 3];
                for j in 0..3 {
                    let h = opp[3 * g + j];
                    if h != NO_HALFEDGE && region[h as usize / 3] == id {
                        shared[j] = true;
                        shared[(j + 1) % 3] = true;
                    }
                }
                let pinch = (0..3).any(|j| !shared[j] && stamp[faces[g][j] as usize] == id);
                if pinch {
                    continue;
                }
                let b = bounds(&t);
                let overlaps = group
                    .iter()
                    .zip(&boxes)
                    .any(|(&h, bh)| boxes_meet(&b, bh) && interiors_meet(&t, &tri(h as usize)));
                if overlaps {
                    continue;
                }
                region[g] = id;
                faces[g].iter().for_each(|&v| stamp[v as usize] = id);
                group.push(g as u32);
                boxes.push(b);
                queue.push_back(g);
            }
        }
        groups.push(group);
    }
    groups.iter().map(|g| sub_piece(piece, g)).collect()
}

fn signed_area(t: &[Complex64; 3]) -> f64 {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    0.5 * (e1.re * e2.im - e1.im * e2.re)
}

fn bounds(t: &[Complex64; 3]) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for z in t {
        b = [
            b[0].min(z.re),
            b[1].min(z.im),
            b[2].max(z.re),
            b[3].max(z.im),
        ];
    }
    b
}

fn boxes_meet(a: &[f64; 4], b: &[f64; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// Whether two counter-clockwise triangles' interiors meet: no edge of either has the
/// other on its outer side (up to rounding: a shared vertex or edge, which has the same
/// coordinates in both, is no overlap).
pub(crate) fn interiors_meet(a: &[Complex64; 3], b: &[Complex64; 3]) -> bool {
    let extent = a
        .iter()
        .chain(b)
        .map(|z| (z - a[0]).norm())
        .fold(0.0f64, f64::max);
    let separates = |t: &[Complex64; 3], other: &[Complex64; 3]| {
        (0..3).any(|k| {
            let (p, q) = (t[k], t[(k + 1) % 3]);
            let d = q - p;
            let tol = 1e-12 * d.norm() * extent;
            other.iter().all(|z| {
                let w = z - p;
                d.re * w.im - d.im * w.re <= tol
            })
        })
    };
    !(separates(a, b) || separates(b, a))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(p: [(f64, f64); 3]) -> [Complex64; 3] {
        p.map(|(x, y)| Complex64::new(x, y))
    }

    #[test]
    fn triangles_meet_only_when_their_interiors_do() {
        let a = t([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)]);
        // sharing an edge, on the other side
        assert!(!interiors_meet(
            &a,
            &t([(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
        ));
        // sharing a vertex only
        assert!(!interiors_meet(
            &a,
            &t([(1.0, 0.0), (2.0, 0.0), (1.5, 1.0)])
        ));
        // apart
        assert!(!interiors_meet(
            &a,
            &t([(2.0, 2.0), (3.0, 2.0), (2.0, 3.0)])
        ));
        // crossing
        assert!(interiors_meet(&a, &t([(0.2, 0.2), (1.2, 0.2), (0.2, 1.2)])));
        // one inside the other
        assert!(interiors_meet(&a, &t([(0.1, 0.1), (0.3, 0.1), (0.1, 0.3)])));
        // a shared edge, the second on the first's side of it
        assert!(interiors_meet(&a, &t([(1.0, 0.0), (0.0, 1.0), (0.2, 0.2)])));
    }
}
