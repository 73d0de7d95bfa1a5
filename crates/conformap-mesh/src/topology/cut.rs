//! The cut graph of a tree–cotree decomposition and the cut mesh: the surface opened along
//! it into one topological disk (a fundamental domain).

use crate::error::MeshError;
use crate::topology::edges::EdgeIndex;
use crate::topology::tree_cotree::{HomologyBasis, UnionFind};
use crate::trimesh::{TriMesh, NO_HALFEDGE};

/// The edges not crossed by the cotree (the tree and the generator edges), with the tree
/// branches that close no loop pruned away: the union of the `2g` generator loops. Cutting
/// along it leaves the faces joined by the cotree edges only, which form a disk. One flag
/// per edge of [`HomologyBasis::edges`].
///
/// # Examples
/// See [`cut_mesh`].
pub fn cut_graph(mesh: &TriMesh, basis: &HomologyBasis) -> Vec<bool> {
    let ne = basis.edges.len();
    let mut on_cut: Vec<bool> = (0..ne).map(|e| !basis.in_cotree[e]).collect();
    let mut degree = vec![0u32; mesh.num_vertices()];
    let ends = |e: usize| mesh.halfedge_vertices(basis.edges.halfedge[e] as usize);
    for e in (0..ne).filter(|&e| on_cut[e]) {
        let (a, b) = ends(e);
        degree[a as usize] += 1;
        degree[b as usize] += 1;
    }
    // cut edges around each vertex (compressed rows), to peel dangling branches leaf by
    // leaf
    let mut offsets = Vec::with_capacity(degree.len() + 1);
    offsets.push(0usize);
    for &d in &degree {
        offsets.push(offsets[offsets.len() - 1] + d as usize);
    }
    let mut fill = offsets[..degree.len()].to_vec();
    let mut incident = vec![0u32; offsets[degree.len()]];
    for e in (0..ne).filter(|&e| on_cut[e]) {
        let (a, b) = ends(e);
        for v in [a as usize, b as usize] {
            incident[fill[v]] = e as u32;
            fill[v] += 1;
        }
    }
    let mut leaves: Vec<u32> = (0..mesh.num_vertices() as u32)
        .filter(|&v| degree[v as usize] == 1)
        .collect();
    while let Some(v) = leaves.pop() {
        let v = v as usize;
        if degree[v] != 1 {
            continue;
        }
        let around = &incident[offsets[v]..offsets[v + 1]];
        let Some(&e) = around.iter().find(|&&e| on_cut[e as usize]) else {
            continue;
        };
        on_cut[e as usize] = false;
        let (a, b) = ends(e as usize);
        let w = if a as usize == v { b } else { a } as usize;
        degree[v] -= 1;
        degree[w] -= 1;
        if degree[w] == 1 {
            leaves.push(w as u32);
        }
    }
    on_cut
}

/// A mesh opened along a cut graph.
#[derive(Debug, Clone)]
pub struct CutMesh {
    /// The opened mesh: face `f` is input face `f` with its corners renumbered to cut
    /// vertices (so `mesh.faces()[f][k]` is the cut vertex of corner `(f, k)`). A
    /// topological disk when cut along [`cut_graph`] of a closed surface of genus ≥ 1.
    pub mesh: TriMesh,
    /// For each cut vertex, the input vertex it is a copy of.
    pub original: Vec<u32>,
    /// Per input edge: whether it is a seam (on the cut).
    pub on_cut: Vec<bool>,
}

/// Opens `mesh` along the edges flagged in `on_cut` (indexed by `basis.edges`): the corners
/// around each input vertex are grouped into fans separated by cut edges, and each fan
/// becomes one cut vertex (numbered in the order of its first corner, `3 f + k`).
///
/// # Errors
/// [`MeshError`] if the opened mesh fails validation (a cut that does not leave a manifold,
/// e.g. one that is not the cut graph of this mesh).
///
/// # Examples
/// ```
/// use conformap_mesh::{cut_graph, cut_mesh, homology_basis, Topology};
/// # let torus = conformap_mesh::doc_torus();
/// // `torus`: a closed genus-1 mesh
/// let basis = homology_basis(&torus, None)?;
/// let cut = cut_mesh(&torus, &basis, cut_graph(&torus, &basis))?;
/// assert_eq!(cut.mesh.topology(), Topology::Disk); // the fundamental domain
/// assert_eq!(cut.original.len(), cut.mesh.num_vertices());
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn cut_mesh(
    mesh: &TriMesh,
    basis: &HomologyBasis,
    on_cut: Vec<bool>,
) -> Result<CutMesh, MeshError> {
    cut_mesh_along(mesh, &basis.edges, on_cut)
}

/// Opens `mesh` along the edges flagged in `on_cut` (indexed by `edges`), as [`cut_mesh`]
/// does, for any cut of any surface (a tree of paths through cones, a surface with
/// boundary): no homology basis needed.
///
/// # Errors
/// As [`cut_mesh`].
pub fn cut_mesh_along(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    on_cut: Vec<bool>,
) -> Result<CutMesh, MeshError> {
    let faces = mesh.faces();
    let opp = mesh.opposite_halfedges();
    let mut corners = UnionFind::new(3 * faces.len());
    for (h, &o) in opp.iter().enumerate() {
        if o == NO_HALFEDGE || (o as usize) < h || on_cut[edges.edge_of[h] as usize] {
            continue;
        }
        // h = a → b in face f, o = b → a in face g: glue the corners of a and of b
        let (f, k) = (h / 3, h % 3);
        let (g, m) = (o as usize / 3, o as usize % 3);
        corners.union(3 * f + k, 3 * g + (m + 1) % 3);
        corners.union(3 * f + (k + 1) % 3, 3 * g + m);
    }
    let mut id_of_root = vec![u32::MAX; 3 * faces.len()];
    let mut original = Vec::new();
    let mut positions = Vec::new();
    let mut cut_faces = Vec::with_capacity(faces.len());
    for (f, t) in faces.iter().enumerate() {
        let mut nt = [0u32; 3];
        for k in 0..3 {
            let r = corners.find(3 * f + k);
            if id_of_root[r] == u32::MAX {
                id_of_root[r] = original.len() as u32;
                original.push(t[k]);
                positions.push(mesh.positions()[t[k] as usize]);
            }
            nt[k] = id_of_root[r];
        }
        cut_faces.push(nt);
    }
    // the opened mesh's half-edge matching: the input's, except across an opened edge
    // (whose two sides got distinct copies of an end; a flagged edge whose sides still
    // share both ends stays matched, as a fresh matching would find it)
    let opposite: Vec<u32> = opp
        .iter()
        .enumerate()
        .map(|(h, &o)| {
            if o == NO_HALFEDGE || !on_cut[edges.edge_of[h] as usize] {
                return o;
            }
            let (f, k, g, m) = (h / 3, h % 3, o as usize / 3, o as usize % 3);
            let glued = cut_faces[f][k] == cut_faces[g][(m + 1) % 3]
                && cut_faces[f][(k + 1) % 3] == cut_faces[g][m];
            if glued {
                o
            } else {
                NO_HALFEDGE
            }
        })
        .collect();
    let cut = TriMesh::opened(positions, cut_faces, opposite)?;
    Ok(CutMesh {
        mesh: cut,
        original,
        on_cut,
    })
}
