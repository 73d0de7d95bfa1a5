//! The cut of a closed surface into a disk: the handle loops of a tree–cotree
//! decomposition (genus ≥ 1) and a tree of shortest paths joining every cone to them (or,
//! on a sphere, to each other).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use conformap_mesh::{EdgeIndex, TriMesh};

/// A total order on non-negative finite distances, for the heap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Dist(f64);
impl Eq for Dist {}
impl PartialOrd for Dist {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Dist {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// Half-edges leaving each vertex (compressed rows), with their edge and 3D length.
pub(crate) struct Graph {
    offsets: Vec<usize>,
    /// `(to, edge, length)`.
    out: Vec<(u32, u32, f64)>,
}

impl Graph {
    pub(crate) fn new(mesh: &TriMesh, edges: &EdgeIndex) -> Self {
        let n = mesh.num_vertices();
        let p = mesh.positions();
        // counted, then scattered: each vertex's edges in the order of the edge index
        let ends = |h: u32| mesh.halfedge_vertices(h as usize);
        let mut offsets = vec![0usize; n + 1];
        for &h in &edges.halfedge {
            let (a, b) = ends(h);
            offsets[a as usize + 1] += 1;
            offsets[b as usize + 1] += 1;
        }
        for v in 0..n {
            offsets[v + 1] += offsets[v];
        }
        let mut fill = offsets.clone();
        let mut out = vec![(0u32, 0u32, 0.0f64); offsets[n]];
        for (e, &h) in edges.halfedge.iter().enumerate() {
            let (a, b) = ends(h);
            let (pa, pb) = (p[a as usize], p[b as usize]);
            let len = ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2))
                .sqrt();
            out[fill[a as usize]] = (b, e as u32, len);
            fill[a as usize] += 1;
            out[fill[b as usize]] = (a, e as u32, len);
            fill[b as usize] += 1;
        }
        Self { offsets, out }
    }

    fn around(&self, v: u32) -> &[(u32, u32, f64)] {
        &self.out[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }
}

/// Adds to `on_cut` (one flag per edge) shortest paths that join every vertex of `targets`
/// to the cut: grown from the vertices already on it and the `seeds` (a boundary), or
/// from the first target when there are none, one multi-source Dijkstra per target
/// reached, nearest first. Returns the 3D length added.
pub(crate) fn join_to_cut(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    graph: &Graph,
    on_cut: &mut [bool],
    targets: &[u32],
    seeds: &[u32],
) -> f64 {
    let n = mesh.num_vertices();
    let mut in_tree = vec![false; n];
    for &s in seeds {
        in_tree[s as usize] = true;
    }
    for (e, &c) in on_cut.iter().enumerate() {
        if c {
            let (a, b) = mesh.halfedge_vertices(edges.halfedge[e] as usize);
            in_tree[a as usize] = true;
            in_tree[b as usize] = true;
        }
    }
    if !in_tree.iter().any(|&t| t) {
        if let Some(&first) = targets.first() {
            in_tree[first as usize] = true;
        }
    }
    let mut pending: Vec<u32> = targets
        .iter()
        .copied()
        .filter(|&t| !in_tree[t as usize])
        .collect();
    let mut added = 0.0;
    // one Dijkstra search grown from the tree, continued after each path joins it: the
    // path's vertices enter at distance 0 and whatever they bring nearer is searched again
    // (distances only fall as the tree grows), instead of a new search from the whole tree
    // per target
    let mut dist = vec![f64::INFINITY; n];
    let mut parent: Vec<(u32, u32)> = vec![(u32::MAX, u32::MAX); n];
    let mut heap = BinaryHeap::new();
    for v in 0..n {
        if in_tree[v] {
            dist[v] = 0.0;
            heap.push(Reverse((Dist(0.0), v as u32)));
        }
    }
    while !pending.is_empty() {
        let mut reached = None;
        while let Some(Reverse((Dist(d), v))) = heap.pop() {
            if d > dist[v as usize] {
                continue;
            }
            if pending.contains(&v) {
                reached = Some(v);
                break;
            }
            for &(w, e, len) in graph.around(v) {
                let nd = d + len;
                if nd < dist[w as usize] {
                    dist[w as usize] = nd;
                    parent[w as usize] = (v, e);
                    heap.push(Reverse((Dist(nd), w)));
                }
            }
        }
        let Some(t) = reached else {
            break; // another component: nothing to join
        };
        let mut v = t;
        let mut path = Vec::new();
        while !in_tree[v as usize] {
            in_tree[v as usize] = true;
            let (p, e) = parent[v as usize];
            on_cut[e as usize] = true;
            added += dist[v as usize] - dist[p as usize];
            path.push(v);
            v = p;
        }
        for v in path {
            dist[v as usize] = 0.0;
            heap.push(Reverse((Dist(0.0), v)));
        }
        pending.retain(|&x| x != t);
    }
    added
}

/// Every seam edge of `cut` (the surface `mesh` opened along its cut, faces in `mesh`'s
/// order) as `[a, b, a′, b′]`: the copies of one edge `a → b` on one side and of the same
/// edge on the other side, where its opposite half-edge runs `b′ → a′`.
pub(crate) fn seam_edges(mesh: &TriMesh, cut: &TriMesh) -> Vec<[u32; 4]> {
    let start = |h: usize| cut.faces()[h / 3][h % 3];
    let end = |h: usize| cut.faces()[h / 3][(h + 1) % 3];
    mesh.opposite_halfedges()
        .iter()
        .enumerate()
        .filter(|&(h, &o)| o != conformap_mesh::NO_HALFEDGE && h < o as usize)
        .map(|(h, &o)| [start(h), end(h), end(o as usize), start(o as usize)])
        .filter(|&[a, b, a2, b2]| a != a2 || b != b2)
        .collect()
}
