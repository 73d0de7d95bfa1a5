//! The cotangent Laplacian (CEM Eq. 5–6) and its interior/boundary blocks (CEM Eq. 9).

use conformap_mesh::{TriMesh, NO_HALFEDGE};
use num_complex::Complex64;
use rayon::prelude::*;
use sprs::CsMat;

use crate::geometry::first_corner_cotangents;

/// Assembles the cotangent Laplacian of CEM Eq. 6 as a symmetric CSC matrix (full storage,
/// sorted row indices):
/// `L_ij = −½(cot α_ij + cot α_ji)` for an edge, `L_ii = −Σ_{j≠i} L_ij`.
///
/// Boundary-edge convention: an edge with a single opposite angle α gets `−½ cot α`
/// (CEM Eq. 6 with the missing angle's term absent). With it, `½ fᴴ L f` is exactly the
/// Dirichlet energy of the piecewise-linear map, and equals the surface area for the
/// identity map of a planar mesh. The metrics crate uses the same convention.
///
/// Assembled column by column without a triplet list (`O(nnz)` memory): the weight of every
/// edge from its one or two half-edges (in parallel blocks: the opposite face's cotangent
/// is the one random read), each edge bucketed into the columns of its two vertices (a
/// counting sort), then each column sorted by row; the diagonal is summed face by face. Scattering into a sorted pattern by binary search, as before, cost
/// several cache misses per entry: 4–5× slower on 53k-vertex meshes.
pub fn cotan_laplacian(mesh: &TriMesh) -> CsMat<f64> {
    cotan_laplacian_part(mesh, mesh.num_faces(), mesh.num_vertices())
}

/// The cotangent Laplacian ([`cotan_laplacian`]) of the first `faces` faces of `mesh` alone,
/// which must use only its first `vertices` vertices: an edge whose other face lies beyond
/// `faces` counts as a boundary edge. One copy of a symmetric double covering is its first
/// half (`conformap-global` factors that copy's Neumann and Dirichlet problems), built
/// without assembling the covering's whole matrix. `cotan_laplacian_part(mesh,
/// mesh.num_faces(), mesh.num_vertices())` is [`cotan_laplacian`], bit for bit.
///
/// # Panics
/// If `faces` exceeds the mesh's faces or a face among them uses a vertex `≥ vertices`.
///
/// # Examples
/// ```
/// use conformap_mesh::TriMesh;
/// use conformap_operators::{cotan_laplacian, cotan_laplacian_part};
/// let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let square = TriMesh::try_new(p.clone(), vec![[0, 1, 2], [0, 2, 3]])?;
/// assert_eq!(cotan_laplacian_part(&square, 2, 4), cotan_laplacian(&square));
/// // the first face alone is the Laplacian of that triangle as a mesh of its own
/// let triangle = TriMesh::try_new(p[..3].to_vec(), vec![[0, 1, 2]])?;
/// assert_eq!(cotan_laplacian_part(&square, 1, 3), cotan_laplacian(&triangle));
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn cotan_laplacian_part(mesh: &TriMesh, faces: usize, vertices: usize) -> CsMat<f64> {
    let n = vertices;
    let all = mesh.faces();
    assert!(faces <= all.len(), "{faces} faces of {}", all.len());
    let faces = &all[..faces];
    assert!(
        faces.iter().flatten().all(|&v| (v as usize) < n),
        "a face uses a vertex beyond {n}"
    );
    let cots = first_corner_cotangents(mesh, faces.len());
    let opposite = &mesh.opposite_halfedges()[..3 * faces.len()];
    let inside = 3 * faces.len() as u32;
    // half-edge h = 3f + k runs faces[f][k] → faces[f][k+1]; its opposite corner is k + 2
    let half = |h: usize| 0.5 * cots[h / 3][(h % 3 + 2) % 3];
    // (a, b, w) once per undirected edge: a boundary half-edge, or the smaller of a pair
    let edges: Vec<(u32, u32, f64)> = opposite
        .par_chunks(EDGE_BLOCK)
        .enumerate()
        .flat_map_iter(|(block, opp)| {
            opp.iter().enumerate().filter_map(move |(i, &o)| {
                let h = block * EDGE_BLOCK + i;
                // a half-edge whose opposite lies beyond the faces taken is a boundary
                let o = if o < inside { o } else { NO_HALFEDGE };
                if o != NO_HALFEDGE && o < h as u32 {
                    return None;
                }
                let f = faces[h / 3];
                let (a, b) = (f[h % 3], f[(h % 3 + 1) % 3]);
                let w = if o == NO_HALFEDGE {
                    half(h)
                } else {
                    half(h) + half(o as usize)
                };
                Some((a, b, w))
            })
        })
        .collect();
    let mut count = vec![0usize; n];
    for &(a, b, _) in &edges {
        count[a as usize] += 1;
        count[b as usize] += 1;
    }
    // column v: its neighbours and v itself
    let mut indptr = Vec::with_capacity(n + 1);
    indptr.push(0usize);
    let mut acc = 0;
    for c in &count {
        acc += c + 1;
        indptr.push(acc);
    }
    let mut fill: Vec<usize> = indptr[..n].to_vec();
    let mut entries = vec![(0u32, 0.0f64); acc];
    for &(a, b, w) in &edges {
        entries[fill[a as usize]] = (b, -w);
        fill[a as usize] += 1;
        entries[fill[b as usize]] = (a, -w);
        fill[b as usize] += 1;
    }
    // the diagonal summed face by face, corner by corner: the same bits as the intrinsic
    // Laplacian of an unflipped triangulation (and as this function's earlier scatter)
    let mut diagonal = vec![0.0f64; n];
    for (t, c) in faces.iter().zip(&cots) {
        for k in 0..3 {
            let w = 0.5 * c[k];
            diagonal[t[(k + 1) % 3] as usize] += w;
            diagonal[t[(k + 2) % 3] as usize] += w;
        }
    }
    let mut indices = Vec::with_capacity(acc);
    let mut data = Vec::with_capacity(acc);
    for v in 0..n {
        let col = &mut entries[indptr[v]..indptr[v + 1]];
        let (off, diag) = col.split_at_mut(col.len() - 1);
        off.sort_unstable_by_key(|e| e.0);
        diag[0] = (v as u32, diagonal[v]);
        let split = off.partition_point(|e| (e.0 as usize) < v);
        for &(r, x) in off[..split].iter().chain(&diag[..]).chain(&off[split..]) {
            indices.push(r as usize);
            data.push(x);
        }
    }
    CsMat::new_csc((n, n), indptr, indices, data)
}

/// Half-edges per parallel block of [`cotan_laplacian`]'s edge weights: far more work than
/// a task hand-off, and enough blocks to balance two cores on 10⁴-face meshes.
const EDGE_BLOCK: usize = 1 << 14;

/// Adds the weight `w` of the edge `ij` to the values of a Laplacian in CSC form: `−w` at
/// `(i, j)` and `(j, i)`, `+w` at `(i, i)` and `(j, j)`; `pos(col, row)` is the index in
/// `data` of that entry of the pattern.
pub(crate) fn add_edge_weight(
    data: &mut [f64],
    pos: &impl Fn(usize, usize) -> usize,
    i: usize,
    j: usize,
    w: f64,
) {
    data[pos(j, i)] -= w;
    data[pos(i, j)] -= w;
    data[pos(i, i)] += w;
    data[pos(j, j)] += w;
}

/// The sparsity pattern of the interior block `L_II` of [`cotan_laplacian`] for `part`
/// (exactly that of [`LaplacianBlocks::ii`]: every interior vertex's interior neighbours
/// and itself), with all values 1. It needs only the connectivity, so the symbolic
/// analysis of `L_II` can run on it while the cotangent weights are computed.
pub fn interior_pattern(mesh: &TriMesh, part: &Partition) -> CsMat<f64> {
    let adj = mesh.vertex_adjacency();
    let n = part.interior.len();
    let mut indptr = Vec::with_capacity(n + 1);
    let mut indices = Vec::with_capacity(adj.neighbors.len() + n);
    indptr.push(0usize);
    for &v in &part.interior {
        let v = v as usize;
        let nb = adj.neighbors_of(v);
        let split = nb.partition_point(|&w| (w as usize) < v);
        let local = |w: u32| part.local[w as usize] as usize;
        let interior = |w: &&u32| part.is_interior[**w as usize];
        indices.extend(nb[..split].iter().filter(interior).map(|&w| local(w)));
        indices.push(part.local[v] as usize);
        indices.extend(nb[split..].iter().filter(interior).map(|&w| local(w)));
        indptr.push(indices.len());
    }
    let data = vec![1.0; indices.len()];
    CsMat::new_csc((n, n), indptr, indices, data)
}

/// `½ fᴴ L f` for a real symmetric `L` and a complex vector `f` (the Dirichlet energy of CEM
/// Eq. 5 when `L` is [`cotan_laplacian`]).
pub fn quadratic_form(l: &CsMat<f64>, f: &[Complex64]) -> f64 {
    let mut acc = 0.0;
    for (j, col) in l.outer_iterator().enumerate() {
        let fj = f[j];
        let mut s = Complex64::new(0.0, 0.0);
        for (i, &v) in col.iter() {
            s += f[i] * v;
        }
        acc += (fj.conj() * s).re;
    }
    0.5 * acc
}

/// `y = L x` for a CSC matrix and complex `x`.
pub fn mul_complex(l: &CsMat<f64>, x: &[Complex64]) -> Vec<Complex64> {
    let mut y = vec![Complex64::new(0.0, 0.0); l.rows()];
    for (j, col) in l.outer_iterator().enumerate() {
        let xj = x[j];
        for (i, &v) in col.iter() {
            y[i] += xj * v;
        }
    }
    y
}

/// An ordering of the vertices into interior and boundary sets (CEM Eq. 9).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Partition {
    /// Interior vertices, ascending.
    pub interior: Vec<u32>,
    /// Boundary vertices in the given order (e.g. along the loop).
    pub boundary: Vec<u32>,
    /// For every vertex: its index within `interior` or within `boundary`.
    pub local: Vec<u32>,
    /// For every vertex: whether it is interior.
    pub is_interior: Vec<bool>,
}

impl Partition {
    /// Interior = every vertex not in `boundary`; `boundary` keeps its order.
    pub fn new(num_vertices: usize, boundary: &[u32]) -> Self {
        let mut is_interior = vec![true; num_vertices];
        let mut local = vec![0u32; num_vertices];
        for (k, &b) in boundary.iter().enumerate() {
            is_interior[b as usize] = false;
            local[b as usize] = k as u32;
        }
        let interior: Vec<u32> = (0..num_vertices as u32)
            .filter(|&v| is_interior[v as usize])
            .collect();
        for (k, &v) in interior.iter().enumerate() {
            local[v as usize] = k as u32;
        }
        Self {
            interior,
            boundary: boundary.to_vec(),
            local,
            is_interior,
        }
    }

    /// Scatters interior and boundary values back into one vector in vertex order.
    pub fn assemble<T: Copy + Default>(&self, interior: &[T], boundary: &[T]) -> Vec<T> {
        let mut out = vec![T::default(); self.local.len()];
        for (k, &v) in self.interior.iter().enumerate() {
            out[v as usize] = interior[k];
        }
        for (k, &v) in self.boundary.iter().enumerate() {
            out[v as usize] = boundary[k];
        }
        out
    }

    /// Gathers the boundary values of a full vector.
    pub fn boundary_values<T: Copy>(&self, full: &[T]) -> Vec<T> {
        self.boundary.iter().map(|&v| full[v as usize]).collect()
    }

    /// Gathers the interior values of a full vector.
    pub fn interior_values<T: Copy>(&self, full: &[T]) -> Vec<T> {
        self.interior.iter().map(|&v| full[v as usize]).collect()
    }
}

/// The blocks `L_II`, `L_IB` and `L_BB` of a Laplacian for a [`Partition`] (CEM Eq. 9).
#[derive(Debug, Clone)]
pub struct LaplacianBlocks {
    /// Interior–interior block, symmetric, `n_I × n_I`.
    pub ii: CsMat<f64>,
    /// Interior–boundary block, `n_I × n_B` (its transpose is `L_BI`).
    pub ib: CsMat<f64>,
    /// Boundary–boundary block, symmetric, `n_B × n_B`.
    pub bb: CsMat<f64>,
}

impl LaplacianBlocks {
    /// Extracts the blocks of the CSC matrix `l` for `part`.
    pub fn new(l: &CsMat<f64>, part: &Partition) -> Self {
        let ni = part.interior.len();
        let nb = part.boundary.len();
        Self {
            ii: extract(l, part, &part.interior, true, ni),
            ib: extract(l, part, &part.boundary, true, ni),
            bb: extract(l, part, &part.boundary, false, nb),
        }
    }

    /// `L_IB x` for a boundary vector `x`.
    pub fn ib_mul(&self, x: &[Complex64]) -> Vec<Complex64> {
        mul_complex(&self.ib, x)
    }

    /// `L_BI y = L_IBᵀ y` for an interior vector `y`.
    pub fn bi_mul(&self, y: &[Complex64]) -> Vec<Complex64> {
        self.ib
            .outer_iterator()
            .map(|col| col.iter().map(|(i, &v)| y[i] * v).sum())
            .collect()
    }
}

/// The submatrix of `l` with columns `cols` (global ids) and the rows of one side of `part`.
fn extract(
    l: &CsMat<f64>,
    part: &Partition,
    cols: &[u32],
    rows_interior: bool,
    nrows: usize,
) -> CsMat<f64> {
    let mut indptr = Vec::with_capacity(cols.len() + 1);
    let mut indices = Vec::new();
    let mut data = Vec::new();
    indptr.push(0);
    let mut col_buf: Vec<(usize, f64)> = Vec::new();
    for &c in cols {
        col_buf.clear();
        if let Some(col) = l.outer_view(c as usize) {
            for (r, &v) in col.iter() {
                if part.is_interior[r] == rows_interior {
                    col_buf.push((part.local[r] as usize, v));
                }
            }
        }
        col_buf.sort_unstable_by_key(|e| e.0);
        for &(r, v) in &col_buf {
            indices.push(r);
            data.push(v);
        }
        indptr.push(indices.len());
    }
    CsMat::new_csc((nrows, cols.len()), indptr, indices, data)
}
