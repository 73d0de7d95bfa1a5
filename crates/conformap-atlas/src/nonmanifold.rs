//! Non-manifold input made manifold for the atlas: a vertex whose faces form several fans
//! becomes one vertex per fan, and an edge of three or more faces is cut into manifold
//! sheets. Every face is kept, with its orientation; only vertex indices change.
//!
//! 1. **Edges.** At an edge of `k ≥ 3` faces, faces running the edge one way are paired in
//!    input order with faces running it the other way (a consistently oriented sheet); the
//!    faces left unpaired see the edge as boundary. Edges of one or two faces stay as they
//!    are (two faces of the same direction are an orientation defect for the validation to
//!    name, not something to split).
//! 2. **Vertices.** The faces around each vertex are grouped by the glued edges through it
//!    (faces sharing a glued edge at the vertex are one fan); the first group keeps the
//!    vertex, every further group gets a copy (appended after the input's vertices).

use serde::Serialize;

/// How many split input vertices a [`NonManifoldSplit`] lists by index (the count is
/// always whole): 20, enough to find them in a modeller without flooding a report.
pub const SPLIT_LIST_CAP: usize = 20;

/// The input made manifold by [`split_non_manifold`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct NonManifoldSplit {
    /// Positions: the input's, then one copy per added vertex.
    pub positions: Vec<[f64; 3]>,
    /// The faces, in input order and orientation, on the split vertices.
    pub faces: Vec<[u32; 3]>,
    /// For each output vertex, its input vertex (the identity on the input's vertices).
    pub vertex_to_input: Vec<u32>,
    /// Where the input was split, for reports.
    pub report: SplitReport,
}

/// Where a non-manifold input was split.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Default)]
#[non_exhaustive]
pub struct SplitReport {
    /// Input vertices given more than one copy.
    pub vertices_split: usize,
    /// Vertex copies added.
    pub vertices_added: usize,
    /// Edges of three or more faces cut into sheets.
    pub edges_split: usize,
    /// The first [`SPLIT_LIST_CAP`] split input vertices, ascending.
    pub split_vertices: Vec<u32>,
}

/// Splits the non-manifold vertices and edges of `faces` (indices into `positions`, any
/// number of components) as the module docs say. A manifold input comes back unchanged
/// (no vertex added).
pub fn split_non_manifold(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> NonManifoldSplit {
    use std::collections::HashMap;
    let n = positions.len();
    // half-edges by undirected edge: (face, corner k: the edge t[k] → t[k+1])
    let mut by_edge: HashMap<(u32, u32), Vec<(u32, u8)>> = HashMap::new();
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            by_edge
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push((f as u32, k as u8));
        }
    }
    // the glued neighbour across each half-edge (face, corner), or none
    let mut glued: HashMap<(u32, u8), u32> = HashMap::new();
    let mut edges_split = 0;
    for (&(lo, _), sides) in &by_edge {
        let forward = |&(f, k): &(u32, u8)| faces[f as usize][k as usize] == lo;
        if sides.len() == 2 {
            glued.insert(sides[0], sides[1].0);
            glued.insert(sides[1], sides[0].0);
            continue;
        }
        if sides.len() < 3 {
            continue;
        }
        edges_split += 1;
        let ups: Vec<_> = sides.iter().filter(|s| forward(s)).collect();
        let downs: Vec<_> = sides.iter().filter(|s| !forward(s)).collect();
        for (u, d) in ups.iter().zip(&downs) {
            glued.insert(**u, d.0);
            glued.insert(**d, u.0);
        }
    }
    // fans: union-find over the corners of each vertex, joined through glued edges
    let corner = |f: u32, k: usize| 3 * f as usize + k;
    let mut parent: Vec<usize> = (0..3 * faces.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for (&(f, k), &g) in &glued {
        let t = faces[f as usize];
        let s = faces[g as usize];
        // the edge t[k] → t[k+1]: join the corners of both ends in f and g
        for v in [t[k as usize], t[(k as usize + 1) % 3]] {
            let kf = corner(f, k_of(t, v));
            let kg = corner(g, k_of(s, v));
            let (a, b) = (find(&mut parent, kf), find(&mut parent, kg));
            if a != b {
                parent[a.max(b)] = a.min(b);
            }
        }
    }
    let mut positions = positions.to_vec();
    let mut vertex_to_input: Vec<u32> = (0..n as u32).collect();
    let mut first_fan: Vec<Option<usize>> = vec![None; n];
    let mut copy_of: HashMap<usize, u32> = HashMap::new();
    let mut split = std::collections::BTreeSet::new();
    let mut out = faces.to_vec();
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            let v = t[k] as usize;
            let fan = find(&mut parent, corner(f as u32, k));
            match first_fan[v] {
                None => first_fan[v] = Some(fan),
                Some(r) if r == fan => {}
                Some(_) => {
                    let id = *copy_of.entry(fan).or_insert_with(|| {
                        positions.push(positions[v]);
                        vertex_to_input.push(v as u32);
                        split.insert(v as u32);
                        (positions.len() - 1) as u32
                    });
                    out[f][k] = id;
                }
            }
        }
    }
    let report = SplitReport {
        vertices_split: split.len(),
        vertices_added: positions.len() - n,
        edges_split,
        split_vertices: split.iter().take(SPLIT_LIST_CAP).copied().collect(),
    };
    NonManifoldSplit {
        positions,
        faces: out,
        vertex_to_input,
        report,
    }
}

/// The corner of `t` at vertex `v`.
fn k_of(t: [u32; 3], v: u32) -> usize {
    t.iter().position(|&w| w == v).unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tetrahedra sharing vertex 0 and a book of three triangles on edge 0–1.
    #[test]
    fn a_shared_vertex_and_a_book_are_split() {
        let p = vec![[0.0; 3]; 7];
        // tetrahedra (0,1,2,3) and (0,4,5,6), outward or not: orientation consistent
        let tet = |a: u32, b: u32, c: u32, d: u32| vec![[a, c, b], [a, b, d], [b, c, d], [c, a, d]];
        let mut faces = tet(0, 1, 2, 3);
        faces.extend(tet(0, 4, 5, 6));
        let s = split_non_manifold(&p, &faces);
        assert_eq!(s.report.vertices_split, 1);
        assert_eq!(s.report.split_vertices, vec![0]);
        assert_eq!(s.report.edges_split, 0);
        assert_eq!(s.positions.len(), 8);
        assert_eq!(s.vertex_to_input[7], 0);
        // the second tetrahedron's corners at 0 moved to the copy
        assert!(s.faces[4..].iter().all(|t| !t.contains(&0)));
        assert!(s.faces[4..].iter().filter(|t| t.contains(&7)).count() == 3);

        // a book: three triangles on edge 0–1, two one way, one the other
        let book = vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]];
        let s = split_non_manifold(&p, &book);
        assert_eq!(s.report.edges_split, 1);
        // faces 0 and 1 form a sheet; face 2 gets its own copies of 0 and 1
        assert_eq!(s.faces[0], [0, 1, 2]);
        assert_eq!(s.faces[1], [1, 0, 3]);
        assert_eq!(s.faces[2], [7, 8, 4]);
        assert_eq!(s.report.vertices_split, 2);
    }
}
