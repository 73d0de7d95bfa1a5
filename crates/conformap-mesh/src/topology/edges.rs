//! Undirected edge numbering with an orientation per edge: the index space of 1-forms.

use crate::trimesh::{TriMesh, NO_HALFEDGE};

/// The undirected edges of a mesh, each with a reference orientation.
///
/// Edge `e` runs along its representative half-edge [`EdgeIndex::halfedge`]`[e]` (the
/// smaller of a pair, or the boundary half-edge); edges are numbered in increasing order of
/// that half-edge, so the numbering is deterministic. A 1-form (1-cochain) is one `f64` per
/// edge, its value on the edge in the reference orientation; on half-edge `h` it is
/// `sign(h) · ω[edge(h)]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EdgeIndex {
    /// Representative half-edge of each edge.
    pub halfedge: Vec<u32>,
    /// Edge of each half-edge (`3 f + k`).
    pub edge_of: Vec<u32>,
}

impl EdgeIndex {
    /// Numbers the edges of `mesh`.
    ///
    /// # Examples
    /// ```
    /// use conformap_mesh::{EdgeIndex, TriMesh};
    /// let mesh = TriMesh::try_new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [0, 2, 3]],
    /// )?;
    /// let edges = EdgeIndex::new(&mesh);
    /// assert_eq!(edges.len(), 5);
    /// // the diagonal 0–2 is half-edge 2 (2 → 0) of face 0 and half-edge 3 (0 → 2) of face 1
    /// assert_eq!(edges.edge_of[2], edges.edge_of[3]);
    /// assert_eq!(edges.sign(2), -edges.sign(3));
    /// # Ok::<(), conformap_mesh::MeshError>(())
    /// ```
    pub fn new(mesh: &TriMesh) -> Self {
        let opp = mesh.opposite_halfedges();
        let mut edge_of = vec![0u32; opp.len()];
        let mut halfedge = Vec::with_capacity(mesh.num_edges());
        for (h, &o) in opp.iter().enumerate() {
            if o == NO_HALFEDGE || (h as u32) < o {
                let e = halfedge.len() as u32;
                halfedge.push(h as u32);
                edge_of[h] = e;
                if o != NO_HALFEDGE {
                    edge_of[o as usize] = e;
                }
            }
        }
        Self { halfedge, edge_of }
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.halfedge.len()
    }

    /// Whether there are no edges (never, for a valid mesh).
    pub fn is_empty(&self) -> bool {
        self.halfedge.is_empty()
    }

    /// `+1.0` if half-edge `h` runs along its edge's reference orientation, else `-1.0`.
    pub fn sign(&self, h: usize) -> f64 {
        if self.halfedge[self.edge_of[h] as usize] as usize == h {
            1.0
        } else {
            -1.0
        }
    }

    /// The value of the 1-form `omega` (one value per edge) on half-edge `h`.
    pub fn on_halfedge(&self, omega: &[f64], h: usize) -> f64 {
        self.sign(h) * omega[self.edge_of[h] as usize]
    }
}
