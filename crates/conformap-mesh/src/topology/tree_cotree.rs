//! Homology generators of a closed surface by tree–cotree decomposition (Eppstein 2003;
//! Erickson and Whittlesey 2005): a shortest-path tree `T` of the vertices, a maximum
//! spanning tree `C` of the dual graph over the edges not in `T`, weighted by the length of
//! the loop each edge closes in `T`; the `2g` edges in neither close the generators.
//! Weighting the cotree by loop length leaves the shortest loops out of it, so the
//! generators are short (a greedy shortest system of loops through the root).

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use crate::error::MeshError;
use crate::topology::edges::EdgeIndex;
use crate::trimesh::{TriMesh, NO_HALFEDGE};

/// One homology generator: a closed loop of half-edges through the tree and one edge
/// outside both trees.
#[derive(Debug, Clone, PartialEq)]
pub struct Generator {
    /// The edge (of [`HomologyBasis::edges`]) outside tree and cotree that closes the loop;
    /// the loop crosses it in its reference orientation.
    pub edge: u32,
    /// The loop as consecutive half-edges (each ends where the next starts; the last ends
    /// where the first starts), without backtracking.
    pub halfedges: Vec<u32>,
    /// Euclidean length of the loop.
    pub length: f64,
}

/// A tree–cotree decomposition of a closed surface and its homology generators.
#[derive(Debug, Clone)]
pub struct HomologyBasis {
    /// The edge numbering all per-edge data refers to.
    pub edges: EdgeIndex,
    /// Root of the shortest-path tree.
    pub root: u32,
    /// For each vertex, the tree half-edge from its parent to it ([`NO_HALFEDGE`] at the
    /// root).
    pub parent_halfedge: Vec<u32>,
    /// Graph distance of each vertex from the root along the edges.
    pub distance: Vec<f64>,
    /// Per edge: in the shortest-path tree `T`.
    pub in_tree: Vec<bool>,
    /// Per edge: crossed by the dual spanning tree `C`.
    pub in_cotree: Vec<bool>,
    /// The `2g` generators, shortest first (ties by edge index).
    pub generators: Vec<Generator>,
}

/// Euclidean length of half-edge `h`.
pub(crate) fn halfedge_length(mesh: &TriMesh, h: usize) -> f64 {
    let (a, b) = mesh.halfedge_vertices(h);
    let (p, q) = (mesh.positions()[a as usize], mesh.positions()[b as usize]);
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The outgoing half-edges of every vertex in compressed rows (`offsets`, `halfedges`).
fn outgoing(mesh: &TriMesh) -> (Vec<usize>, Vec<u32>) {
    let n = mesh.num_vertices();
    let mut offsets = vec![0usize; n + 1];
    for t in mesh.faces() {
        for &v in t {
            offsets[v as usize + 1] += 1;
        }
    }
    for v in 0..n {
        offsets[v + 1] += offsets[v];
    }
    let mut fill = offsets.clone();
    let mut out = vec![0u32; offsets[n]];
    for (f, t) in mesh.faces().iter().enumerate() {
        for k in 0..3 {
            let v = t[k] as usize;
            out[fill[v]] = (3 * f + k) as u32;
            fill[v] += 1;
        }
    }
    (offsets, out)
}

/// Dijkstra from `root` along the edges: (distance, parent half-edge) per vertex.
fn shortest_path_tree(mesh: &TriMesh, root: usize) -> (Vec<f64>, Vec<u32>) {
    let n = mesh.num_vertices();
    let (offsets, out) = outgoing(mesh);
    let mut dist = vec![f64::INFINITY; n];
    let mut parent = vec![NO_HALFEDGE; n];
    let mut done = vec![false; n];
    // keys are non-negative finite distances, whose bit patterns order like the values
    let mut heap = BinaryHeap::new();
    dist[root] = 0.0;
    heap.push(Reverse((0u64, root)));
    while let Some(Reverse((_, v))) = heap.pop() {
        if done[v] {
            continue;
        }
        done[v] = true;
        for &h in &out[offsets[v]..offsets[v + 1]] {
            let (_, w) = mesh.halfedge_vertices(h as usize);
            let w = w as usize;
            let d = dist[v] + halfedge_length(mesh, h as usize);
            if !done[w] && d < dist[w] {
                dist[w] = d;
                parent[w] = h;
                heap.push(Reverse((d.to_bits(), w)));
            }
        }
    }
    (dist, parent)
}

/// Union–find with path halving.
pub(crate) struct UnionFind(Vec<u32>);

impl UnionFind {
    pub(crate) fn new(n: usize) -> Self {
        Self((0..n as u32).collect())
    }

    pub(crate) fn find(&mut self, mut x: usize) -> usize {
        while self.0[x] as usize != x {
            self.0[x] = self.0[self.0[x] as usize];
            x = self.0[x] as usize;
        }
        x
    }

    /// Joins the sets of `a` and `b`; `false` if they were one set already.
    pub(crate) fn union(&mut self, a: usize, b: usize) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
        self.0[hi] = lo as u32;
        true
    }
}

/// The tree–cotree decomposition of a closed connected mesh with the shortest-path tree
/// rooted at `root` (vertex 0 if `None`), and its `2g` generators.
///
/// # Errors
/// [`MeshError::NotClosedSurface`] unless the mesh is one connected closed surface.
///
/// # Examples
/// ```
/// use conformap_mesh::{homology_basis, TriMesh};
/// // a 4 × 4 grid torus
/// let (n, m) = (4usize, 4usize);
/// let id = |i: usize, j: usize| ((j % m) * n + i % n) as u32;
/// let mut positions = Vec::new();
/// for j in 0..m {
///     for i in 0..n {
///         let (p, t) = (i as f64 * std::f64::consts::TAU / n as f64, j as f64 * std::f64::consts::TAU / m as f64);
///         positions.push([(2.0 + t.cos()) * p.cos(), (2.0 + t.cos()) * p.sin(), t.sin()]);
///     }
/// }
/// let mut faces = Vec::new();
/// for j in 0..m {
///     for i in 0..n {
///         faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
///         faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
///     }
/// }
/// let torus = TriMesh::try_new(positions, faces)?;
/// let basis = homology_basis(&torus, None)?;
/// assert_eq!(basis.generators.len(), 2); // 2g
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn homology_basis(mesh: &TriMesh, root: Option<usize>) -> Result<HomologyBasis, MeshError> {
    if mesh.num_components() != 1 || !mesh.boundary_loops().is_empty() {
        return Err(MeshError::NotClosedSurface {
            components: mesh.num_components(),
            boundaries: mesh.boundary_loops().len(),
        });
    }
    let root = root.unwrap_or(0).min(mesh.num_vertices() - 1);
    let edges = EdgeIndex::new(mesh);
    let (distance, parent_halfedge) = shortest_path_tree(mesh, root);
    let mut in_tree = vec![false; edges.len()];
    for &h in &parent_halfedge {
        if h != NO_HALFEDGE {
            in_tree[edges.edge_of[h as usize] as usize] = true;
        }
    }
    // maximum dual spanning tree over the non-tree edges, weighted by loop length
    let loop_length = |e: usize| -> f64 {
        let h = edges.halfedge[e] as usize;
        let (a, b) = mesh.halfedge_vertices(h);
        distance[a as usize] + distance[b as usize] + halfedge_length(mesh, h)
    };
    let mut candidates: Vec<(f64, usize)> = (0..edges.len())
        .filter(|&e| !in_tree[e])
        .map(|e| (loop_length(e), e))
        .collect();
    candidates.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.cmp(&y.1)));
    let opp = mesh.opposite_halfedges();
    let mut faces = UnionFind::new(mesh.num_faces());
    let mut in_cotree = vec![false; edges.len()];
    let mut leftover = Vec::new();
    for &(len, e) in &candidates {
        let h = edges.halfedge[e] as usize;
        let o = opp[h] as usize;
        if faces.union(h / 3, o / 3) {
            in_cotree[e] = true;
        } else {
            leftover.push((len, e));
        }
    }
    leftover.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    let generators = leftover
        .iter()
        .map(|&(_, e)| generator_loop(mesh, &edges, &parent_halfedge, &distance, e))
        .collect();
    Ok(HomologyBasis {
        edges,
        root: root as u32,
        parent_halfedge,
        distance,
        in_tree,
        in_cotree,
        generators,
    })
}

/// The loop `LCA → a`, `a → b`, `b → LCA` through the tree for edge `e = (a → b)`.
fn generator_loop(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    parent: &[u32],
    distance: &[f64],
    e: usize,
) -> Generator {
    let h = edges.halfedge[e] as usize;
    let (a, b) = mesh.halfedge_vertices(h);
    let up = |v: u32| -> u32 {
        let p = parent[v as usize];
        mesh.halfedge_vertices(p as usize).0
    };
    // climb from both ends to the lowest common ancestor, deeper end first
    let (mut x, mut y) = (a, b);
    let mut down_a = Vec::new(); // tree half-edges parent → child on the a side, bottom up
    let mut up_b = Vec::new(); // tree half-edges parent → child on the b side, bottom up
    while x != y {
        if distance[x as usize] >= distance[y as usize] && parent[x as usize] != NO_HALFEDGE {
            down_a.push(parent[x as usize]);
            x = up(x);
        } else {
            up_b.push(parent[y as usize]);
            y = up(y);
        }
    }
    let opp = mesh.opposite_halfedges();
    let mut halfedges: Vec<u32> = down_a.iter().rev().copied().collect();
    halfedges.push(h as u32);
    halfedges.extend(up_b.iter().map(|&t| opp[t as usize]));
    let length = halfedges
        .iter()
        .map(|&t| halfedge_length(mesh, t as usize))
        .sum();
    Generator {
        edge: e as u32,
        halfedges,
        length,
    }
}
