//! Slits: short cuts along mesh edges, each opening the surface into one new boundary loop
//! (the topological optimization of Jin, Wang, Yau and Gu 2004, §3.5).
//!
//! A slit is a path of vertices `p_0 … p_m` (`m ≥ 2` edges) along mesh edges. Cutting
//! duplicates its interior vertices `p_1 … p_{m−1}` (the tips `p_0`, `p_m` stay single), so
//! its two sides become one boundary loop of `2m` vertices; no face is added, removed or
//! renumbered. Each slit lowers the Euler characteristic by one and adds one boundary loop:
//! a sphere with `k` slits is a genus-0 surface with `k` loops, whose double covering has
//! genus `k − 1`.
//!
//! [`SlitPlanner`] keeps slits apart: no slit vertex may lie on or next to the boundary or
//! another slit, and no edge may join two non-consecutive vertices of one slit (a *chord*:
//! after cutting, both its ends are boundary vertices, which a double covering must split,
//! renumbering faces). [`SlitPlanner::propose`] builds a slit of a given length around a
//! centre vertex from two shortest paths leaving it in roughly opposite directions.

use std::collections::{BinaryHeap, HashMap, HashSet};

use crate::error::MeshError;
use crate::topology::UnionFind;
use crate::trimesh::{Adjacency, TriMesh, NO_HALFEDGE};

/// A mesh cut open along slits.
#[derive(Debug, Clone)]
pub struct SlitMesh {
    /// The opened mesh: face `f` is input face `f` (same corners, some renumbered to the
    /// copies of slit vertices), so per-corner values of this mesh are per-corner values of
    /// the input. Vertices `0..n` are the input's; `n..` the copies.
    pub mesh: TriMesh,
    /// For each vertex of [`Self::mesh`], the input vertex it is (a copy of).
    pub original: Vec<u32>,
    /// The slits cut, as vertex paths of the input.
    pub slits: Vec<Vec<u32>>,
}

/// Builds and checks a set of slits on one mesh, keeping them apart.
#[derive(Debug, Clone)]
pub struct SlitPlanner {
    adjacency: Adjacency,
    /// Vertices no new slit may use: boundary vertices, slit vertices and their 1-rings.
    blocked: Vec<bool>,
    slits: Vec<Vec<u32>>,
}

/// Dijkstra entry: `(−distance, vertex)`, ordered so that the heap pops the nearest.
#[derive(PartialEq)]
struct Near(f64, u32);

impl Eq for Near {}

impl PartialOrd for Near {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Near {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

fn dist(mesh: &TriMesh, a: u32, b: u32) -> f64 {
    let (p, q) = (mesh.positions()[a as usize], mesh.positions()[b as usize]);
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

impl SlitPlanner {
    /// A planner with no slit yet; the boundary vertices of `mesh` and their 1-rings are
    /// blocked.
    pub fn new(mesh: &TriMesh) -> Self {
        let adjacency = mesh.vertex_adjacency();
        let mut blocked = vec![false; mesh.num_vertices()];
        for l in mesh.boundary_loops() {
            for &v in l {
                blocked[v as usize] = true;
                for &w in adjacency.neighbors_of(v as usize) {
                    blocked[w as usize] = true;
                }
            }
        }
        Self {
            adjacency,
            blocked,
            slits: Vec::new(),
        }
    }

    /// The vertex adjacency of the mesh the planner was made for (computed once by
    /// [`Self::new`]).
    pub fn adjacency(&self) -> &Adjacency {
        &self.adjacency
    }

    /// The slits accepted so far.
    pub fn slits(&self) -> &[Vec<u32>] {
        &self.slits
    }

    /// Whether a new slit may use vertex `v`.
    pub fn is_free(&self, v: usize) -> bool {
        v < self.blocked.len() && !self.blocked[v]
    }

    /// Whether `path` may be added: at least two edges, every vertex free (not on or next
    /// to the boundary or an accepted slit) and used once, consecutive vertices joined by an
    /// edge, and no chord (an edge between two non-consecutive vertices of the path).
    ///
    /// # Errors
    /// [`MeshError::InvalidSlit`] (with `slit` = the index it would get) naming the first
    /// offending vertex.
    pub fn check(&self, path: &[u32]) -> Result<(), MeshError> {
        let slit = self.slits.len();
        let bad = |vertex: u32, reason| MeshError::InvalidSlit {
            slit,
            vertex,
            reason,
        };
        if path.len() < 3 {
            return Err(bad(
                path.first().copied().unwrap_or(0),
                "fewer than two edges",
            ));
        }
        let mut at = HashMap::with_capacity(path.len());
        for (i, &v) in path.iter().enumerate() {
            if !self.is_free(v as usize) {
                return Err(bad(v, "on or next to the boundary or another slit"));
            }
            if at.insert(v, i).is_some() {
                return Err(bad(v, "repeated vertex"));
            }
        }
        for (i, &v) in path.iter().enumerate() {
            let nb = self.adjacency.neighbors_of(v as usize);
            if i + 1 < path.len() && nb.binary_search(&path[i + 1]).is_err() {
                return Err(bad(v, "no edge to the next vertex"));
            }
            // every edge to another slit vertex must join consecutive vertices
            if nb
                .iter()
                .any(|w| at.get(w).is_some_and(|&j| j + 1 != i && i + 1 != j))
            {
                return Err(bad(v, "an edge joins two non-consecutive slit vertices"));
            }
        }
        Ok(())
    }

    /// Checks `path` against the mesh and the slits accepted so far, then accepts it and
    /// blocks its vertices and their 1-rings.
    ///
    /// # Errors
    /// As [`Self::check`].
    pub fn add(&mut self, path: Vec<u32>) -> Result<(), MeshError> {
        self.check(&path)?;
        for &v in &path {
            self.blocked[v as usize] = true;
            for &w in self.adjacency.neighbors_of(v as usize) {
                self.blocked[w as usize] = true;
            }
        }
        self.slits.push(path);
        Ok(())
    }

    /// A slit of 3D length about `length` through `centre`: two shortest paths (Dijkstra
    /// over edge lengths, free vertices only) of length up to `length / 2` leaving `centre`,
    /// the first to the farthest vertex reached, the second to the vertex farthest (in 3D)
    /// from the first end among those whose path shares only `centre` with the first and
    /// stays off its 1-ring. Each half reaches at least one neighbour of `centre`, so a
    /// slit has at least two edges whatever the mesh resolution. `None` when `centre` is
    /// not free or no valid slit of two edges exists there. The slit is not added.
    pub fn propose(&self, mesh: &TriMesh, centre: u32, length: f64) -> Option<Vec<u32>> {
        let c = centre as usize;
        if !self.is_free(c) {
            return None;
        }
        let radius = 0.5 * length;
        let n = mesh.num_vertices();
        let mut best = HashMap::new();
        let mut parent: HashMap<u32, u32> = HashMap::new();
        let mut settled: Vec<(u32, f64)> = Vec::new();
        let mut done = HashSet::new();
        let mut heap = BinaryHeap::new();
        best.insert(centre, 0.0);
        heap.push(Near(0.0, centre));
        while let Some(Near(d, v)) = heap.pop() {
            if !done.insert(v) {
                continue;
            }
            settled.push((v, d));
            for &w in self.adjacency.neighbors_of(v as usize) {
                if (w as usize) >= n || !self.is_free(w as usize) || done.contains(&w) {
                    continue;
                }
                let nd = d + dist(mesh, v, w);
                // the 1-ring of the centre is always reachable
                if nd > radius && v != centre {
                    continue;
                }
                if best.get(&w).is_none_or(|&b| nd < b) {
                    best.insert(w, nd);
                    parent.insert(w, v);
                    heap.push(Near(nd, w));
                }
            }
        }
        let path_to = |v: u32| {
            let mut p = vec![v];
            while let Some(&u) = parent.get(p.last()?) {
                p.push(u);
            }
            p.reverse();
            Some(p)
        };
        let (end1, _) = settled
            .iter()
            .skip(1)
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))?;
        let half1 = path_to(*end1)?;
        let mut near1 = HashSet::new();
        for &v in &half1[1..] {
            near1.insert(v);
            near1.extend(self.adjacency.neighbors_of(v as usize).iter().copied());
        }
        let far = |v: u32| dist(mesh, v, *end1);
        let end2 = settled
            .iter()
            .skip(1)
            .filter(|(v, _)| path_to(*v).is_some_and(|p| p[1..].iter().all(|u| !near1.contains(u))))
            .max_by(|a, b| far(a.0).total_cmp(&far(b.0)).then(b.0.cmp(&a.0)));
        let mut both = Vec::new();
        if let Some(p) = end2.and_then(|(v, _)| path_to(*v)) {
            both.extend(p.iter().rev());
            both.extend(&half1[1..]);
        }
        [both, half1]
            .into_iter()
            .find(|p| p.len() >= 3 && self.check(p).is_ok())
    }

    /// Cuts `mesh` (the mesh this planner was made for) along the accepted slits.
    ///
    /// # Errors
    /// [`MeshError`] if the opened mesh fails validation (never for slits this planner
    /// accepted on this mesh).
    pub fn cut(&self, mesh: &TriMesh) -> Result<SlitMesh, MeshError> {
        let mut on_slit = HashSet::new();
        for p in &self.slits {
            for w in p.windows(2) {
                on_slit.insert((w[0].min(w[1]), w[0].max(w[1])));
            }
        }
        let faces = mesh.faces();
        let mut corners = UnionFind::new(3 * faces.len());
        for (h, &o) in mesh.opposite_halfedges().iter().enumerate() {
            if o == NO_HALFEDGE || (o as usize) < h {
                continue;
            }
            let (a, b) = mesh.halfedge_vertices(h);
            if on_slit.contains(&(a.min(b), a.max(b))) {
                continue;
            }
            let (f, k) = (h / 3, h % 3);
            let (g, m) = (o as usize / 3, o as usize % 3);
            corners.union(3 * f + k, 3 * g + (m + 1) % 3);
            corners.union(3 * f + (k + 1) % 3, 3 * g + m);
        }
        let n = mesh.num_vertices();
        let mut original: Vec<u32> = (0..n as u32).collect();
        let mut positions = mesh.positions().to_vec();
        let mut root_of_vertex = vec![usize::MAX; n];
        let mut copy_of_root: HashMap<usize, u32> = HashMap::new();
        let mut cut_faces = Vec::with_capacity(faces.len());
        for (f, t) in faces.iter().enumerate() {
            let mut nt = *t;
            for k in 0..3 {
                let (v, r) = (t[k] as usize, corners.find(3 * f + k));
                if root_of_vertex[v] == usize::MAX {
                    root_of_vertex[v] = r;
                } else if root_of_vertex[v] != r {
                    nt[k] = *copy_of_root.entry(r).or_insert_with(|| {
                        original.push(t[k]);
                        positions.push(mesh.positions()[v]);
                        (original.len() - 1) as u32
                    });
                }
            }
            cut_faces.push(nt);
        }
        Ok(SlitMesh {
            mesh: TriMesh::try_new(positions, cut_faces)?,
            original,
            slits: self.slits.clone(),
        })
    }
}

/// Cuts `mesh` along `slits` (vertex paths), checking them as [`SlitPlanner::add`] does.
///
/// # Errors
/// [`MeshError::InvalidSlit`] for the first slit that is not usable.
///
/// # Examples
/// ```
/// use conformap_mesh::{cut_slits, TriMesh};
/// # let torus = conformap_mesh::doc_torus();
/// // `torus`: a closed genus-1 mesh (an 8 × 6 grid); a slit of two edges along a row
/// let slit = cut_slits(&torus, &[vec![0, 1, 2]])?;
/// assert_eq!(slit.mesh.boundary_loops().len(), 1);
/// assert_eq!(slit.mesh.boundary_loops()[0].len(), 4); // 0, 1, 2 and the copy of 1
/// assert_eq!(slit.mesh.num_vertices(), torus.num_vertices() + 1);
/// assert_eq!(slit.mesh.num_faces(), torus.num_faces());
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn cut_slits(mesh: &TriMesh, slits: &[Vec<u32>]) -> Result<SlitMesh, MeshError> {
    let mut planner = SlitPlanner::new(mesh);
    for s in slits {
        planner.add(s.clone())?;
    }
    planner.cut(mesh)
}

#[cfg(test)]
#[path = "slit_tests.rs"]
mod tests;
