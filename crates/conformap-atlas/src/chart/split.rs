//! Charts that overlap themselves are split: a flip-free layout of a disk is one-to-one
//! unless its boundary crosses itself, so where two boundary edges cross, the disk is cut
//! in two along the shortest interior path between them (the two crossing edges end up on
//! different sides) and the pieces keep their layout, to be packed apart: every seam keeps
//! its lengths exactly, the new ones too. Repeated until no piece overlaps itself.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use conformap_mesh::{TriMesh, NO_HALFEDGE};
use conformap_metrics::boundary_crossings;

use super::piece::{sub_piece, Piece};
use crate::error::AtlasError;

/// How deep splitting goes: at most 2^10 pieces from one chart (armadillo's folded-then-
/// unfolded chart needed more than 6 levels). A piece still overlapping then is grown
/// again into regions without overlap (`chart/regions.rs`).
pub const MAX_SPLIT_DEPTH: usize = 10;

/// Splits `piece` until no part of it overlaps itself.
///
/// # Errors
/// [`AtlasError::Mesh`] should a piece fail validation (pieces of a valid disk are valid).
pub fn split_overlapping(piece: Piece, depth: usize) -> Result<Vec<Piece>, AtlasError> {
    let loops = piece.mesh.boundary_loops().to_vec();
    let crossings = boundary_crossings(&piece.uv, &loops, 32);
    if crossings.is_empty() {
        return Ok(vec![piece]);
    }
    if depth >= MAX_SPLIT_DEPTH || loops.len() != 1 {
        return super::regions::regrow(&piece);
    }
    // the first crossing (and choice of its edges' ends) that a path can separate
    let lp = &loops[0];
    let m = lp.len();
    let groups = crossings.iter().find_map(|&((_, ka), (_, kb))| {
        [(ka, kb), (ka + 1, kb), (ka, kb + 1), (ka + 1, kb + 1)]
            .into_iter()
            .map(|(i, j)| (lp[i % m], lp[j % m]))
            .filter(|(a, b)| a != b)
            .find_map(|(a, b)| halves(&piece.mesh, a, b))
    });
    let Some(groups) = groups else {
        // no interior path separates a crossing (a strip one face wide)
        return super::regions::regrow(&piece);
    };
    let mut out = Vec::new();
    for group in groups {
        let sub = sub_piece(&piece, &group)?;
        out.extend(split_overlapping(sub, depth + 1)?);
    }
    Ok(out)
}

/// The faces on the sides of the shortest path of interior edges from boundary vertex `a`
/// to boundary vertex `b` (a boundary vertex on the way counts four times its edge's
/// length: thin strips may need one); `None` when there is no such path or it does not
/// separate.
pub(crate) fn halves(mesh: &TriMesh, a: u32, b: u32) -> Option<Vec<Vec<u32>>> {
    let path = shortest_path(mesh, &PathGraph::new(mesh), a, b)?;
    sides(mesh, &path)
}

/// The interior edges of a mesh as a graph for [`shortest_path`] (built once, searched
/// from many pairs): per vertex, its outgoing interior half-edges and their ends.
pub(crate) struct PathGraph {
    /// Offsets into `out` per vertex (compressed rows).
    start: Vec<usize>,
    /// (end vertex, half-edge).
    out: Vec<(u32, usize)>,
    on_boundary: Vec<bool>,
}

impl PathGraph {
    /// The graph of `mesh`'s interior edges.
    pub(crate) fn new(mesh: &TriMesh) -> Self {
        let n = mesh.num_vertices();
        let mut on_boundary = vec![false; n];
        for &v in mesh.boundary_loops().iter().flatten() {
            on_boundary[v as usize] = true;
        }
        let opp = mesh.opposite_halfedges();
        let mut start = vec![0usize; n + 1];
        for (h, &o) in opp.iter().enumerate() {
            if o != NO_HALFEDGE {
                start[mesh.halfedge_vertices(h).0 as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut out = vec![(0u32, 0usize); start[n]];
        for (h, &o) in opp.iter().enumerate() {
            if o != NO_HALFEDGE {
                let (x, y) = mesh.halfedge_vertices(h);
                out[fill[x as usize]] = (y, h);
                fill[x as usize] += 1;
            }
        }
        Self {
            start,
            out,
            on_boundary,
        }
    }
}

/// The half-edges of the shortest path of interior edges of `mesh` (its [`PathGraph`]
/// `graph`) from boundary vertex `a` to boundary vertex `b`, from `a` on (a boundary
/// vertex on the way counts four times its edge's length); `None` when there is none.
///
/// A* search: the straight distance to `b` (shrunk by [`HEURISTIC_SHRINK`]) never
/// exceeds the length of a path there, so the path is a shortest one as Dijkstra's
/// search finds it, with the vertices farther from the line between `a` and `b` never
/// looked at (a neck's path is short beside its chart: david_head's 16 neck candidates
/// took 98M instructions by Dijkstra's search).
pub(crate) fn shortest_path(
    mesh: &TriMesh,
    graph: &PathGraph,
    a: u32,
    b: u32,
) -> Option<Vec<usize>> {
    let n = mesh.num_vertices();
    let on_boundary = &graph.on_boundary;
    let p = mesh.positions();
    let len = |x: u32, y: u32| {
        let (q, r) = (p[x as usize], p[y as usize]);
        ((q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) + (q[2] - r[2]).powi(2)).sqrt()
    };
    let to_b = |v: u32| HEURISTIC_SHRINK * len(v, b);
    let mut dist = vec![f64::INFINITY; n];
    let mut via = vec![usize::MAX; n];
    let mut heap = BinaryHeap::new();
    dist[a as usize] = 0.0;
    heap.push(Reverse((Ord64(to_b(a)), a)));
    while let Some(Reverse((Ord64(key), v))) = heap.pop() {
        let d = dist[v as usize];
        if key > d + to_b(v) {
            continue;
        }
        if v == b {
            break;
        }
        // prefer interior vertices: a boundary vertex on the way costs a detour's worth
        let row = graph.start[v as usize]..graph.start[v as usize + 1];
        for &(w, h) in &graph.out[row] {
            let nd = d + len(v, w)
                * if on_boundary[w as usize] && w != b {
                    4.0
                } else {
                    1.0
                };
            if nd < dist[w as usize] {
                dist[w as usize] = nd;
                via[w as usize] = h;
                heap.push(Reverse((Ord64(nd + to_b(w)), w)));
            }
        }
    }
    if !dist[b as usize].is_finite() {
        return None;
    }
    let mut path = Vec::new();
    let mut v = b;
    while v != a {
        let h = via[v as usize];
        path.push(h);
        v = mesh.halfedge_vertices(h).0;
    }
    path.reverse();
    Some(path)
}

/// The A* heuristic of [`shortest_path`] is the straight distance times this: 1 − 1e-9,
/// so that rounding in it never makes it exceed a path's length (which would let the
/// search stop before the shortest path).
const HEURISTIC_SHRINK: f64 = 1.0 - 1e-9;

/// The faces on the two sides of `path` (half-edges of interior edges), flooded across
/// every interior edge not on it; `None` when it does not separate.
pub(crate) fn sides(mesh: &TriMesh, path: &[usize]) -> Option<Vec<Vec<u32>>> {
    let opp = mesh.opposite_halfedges();
    let mut on_path = vec![false; opp.len()];
    for &h in path {
        on_path[h] = true;
        on_path[opp[h] as usize] = true;
    }
    // faces flooded across every interior edge not on the path
    let nf = mesh.num_faces();
    let mut group = vec![u32::MAX; nf];
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for start in 0..nf {
        if group[start] != u32::MAX {
            continue;
        }
        let g = groups.len() as u32;
        let mut stack = vec![start];
        group[start] = g;
        let mut members = Vec::new();
        while let Some(f) = stack.pop() {
            members.push(f as u32);
            for k in 0..3 {
                let h = 3 * f + k;
                let o = opp[h];
                if o == NO_HALFEDGE || on_path[h] {
                    continue;
                }
                let nb = o as usize / 3;
                if group[nb] == u32::MAX {
                    group[nb] = g;
                    stack.push(nb);
                }
            }
        }
        members.sort_unstable();
        groups.push(members);
    }
    (groups.len() >= 2).then_some(groups)
}

/// A total order on finite distances, for the heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Ord64(f64);
impl Eq for Ord64 {}
impl PartialOrd for Ord64 {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Ord64 {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The length of `path` with [`shortest_path`]'s weights.
    fn weighted(mesh: &TriMesh, graph: &PathGraph, path: &[usize], b: u32) -> f64 {
        let p = mesh.positions();
        path.iter()
            .map(|&h| {
                let (x, y) = mesh.halfedge_vertices(h);
                let (q, r) = (p[x as usize], p[y as usize]);
                let l =
                    ((q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) + (q[2] - r[2]).powi(2)).sqrt();
                l * if graph.on_boundary[y as usize] && y != b {
                    4.0
                } else {
                    1.0
                }
            })
            .sum()
    }

    /// Dijkstra's distances from `a` with the same weights, every vertex settled.
    fn dijkstra(mesh: &TriMesh, graph: &PathGraph, a: u32, b: u32) -> Vec<f64> {
        let p = mesh.positions();
        let mut dist = vec![f64::INFINITY; mesh.num_vertices()];
        let mut heap = BinaryHeap::new();
        dist[a as usize] = 0.0;
        heap.push(Reverse((Ord64(0.0), a)));
        while let Some(Reverse((Ord64(d), v))) = heap.pop() {
            if d > dist[v as usize] {
                continue;
            }
            for &(w, _) in &graph.out[graph.start[v as usize]..graph.start[v as usize + 1]] {
                let (q, r) = (p[v as usize], p[w as usize]);
                let l =
                    ((q[0] - r[0]).powi(2) + (q[1] - r[1]).powi(2) + (q[2] - r[2]).powi(2)).sqrt();
                let nd = d + l * if graph.on_boundary[w as usize] && w != b {
                    4.0
                } else {
                    1.0
                };
                if nd < dist[w as usize] {
                    dist[w as usize] = nd;
                    heap.push(Reverse((Ord64(nd), w)));
                }
            }
        }
        dist
    }

    /// The A* search's paths are as short as Dijkstra's, between boundary vertices far
    /// apart and near, on a real disk (alligator: 3,208 vertices, a long jagged outline).
    #[test]
    fn the_a_star_paths_are_shortest() {
        let path = format!(
            "{}/../../fixtures/alligator.obj",
            env!("CARGO_MANIFEST_DIR")
        );
        let mesh = conformap_io::read_mesh(path).expect("fixture reads").mesh;
        let graph = PathGraph::new(&mesh);
        let lp = mesh.boundary_loops()[0].clone();
        let m = lp.len();
        let mut checked = 0;
        for (i, j) in [
            (0, m / 2),
            (0, m / 7),
            (m / 3, m - 5),
            (m / 5, m / 5 + 9),
            (1, m - 1),
        ] {
            let (a, b) = (lp[i], lp[j]);
            let found = shortest_path(&mesh, &graph, a, b).expect("a path");
            // a connected chain of half-edges from a to b
            assert_eq!(mesh.halfedge_vertices(found[0]).0, a);
            assert_eq!(mesh.halfedge_vertices(*found.last().unwrap()).1, b);
            for w in found.windows(2) {
                assert_eq!(
                    mesh.halfedge_vertices(w[0]).1,
                    mesh.halfedge_vertices(w[1]).0
                );
            }
            let best = dijkstra(&mesh, &graph, a, b)[b as usize];
            let len = weighted(&mesh, &graph, &found, b);
            assert!(
                (len - best).abs() <= 1e-12 * best,
                "{i}–{j}: {len} against {best}"
            );
            checked += 1;
        }
        assert_eq!(checked, 5);
    }
}
