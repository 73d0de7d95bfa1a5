//! The cotangent Laplacian (CEM Eq. 5–6) and its interior/boundary blocks (CEM Eq. 9).

use conformap_mesh::TriMesh;
use num_complex::Complex64;
use sprs::CsMat;

use crate::geometry::corner_cotangents;

/// Assembles the cotangent Laplacian of CEM Eq. 6 as a symmetric CSC matrix (full storage,
/// sorted row indices):
/// `L_ij = −½(cot α_ij + cot α_ji)` for an edge, `L_ii = −Σ_{j≠i} L_ij`.
///
/// Boundary-edge convention: an edge with a single opposite angle α gets `−½ cot α`
/// (CEM Eq. 6 with the missing angle's term absent). With it, `½ fᴴ L f` is exactly the
/// Dirichlet energy of the piecewise-linear map, and equals the surface area for the
/// identity map of a planar mesh. The metrics crate uses the same convention.
///
/// Assembled in place from the vertex adjacency (no triplet list): `O(nnz)` memory.
pub fn cotan_laplacian(mesh: &TriMesh) -> CsMat<f64> {
    let n = mesh.num_vertices();
    let adj = mesh.vertex_adjacency();
    // column v holds rows: neighbours of v and v itself, sorted
    let mut indptr = Vec::with_capacity(n + 1);
    let mut indices = Vec::with_capacity(adj.neighbors.len() + n);
    indptr.push(0usize);
    for v in 0..n {
        let nb = adj.neighbors_of(v);
        let split = nb.partition_point(|&w| (w as usize) < v);
        indices.extend(nb[..split].iter().map(|&w| w as usize));
        indices.push(v);
        indices.extend(nb[split..].iter().map(|&w| w as usize));
        indptr.push(indices.len());
    }
    let mut data = vec![0.0; indices.len()];
    let pos = |col: usize, row: usize| -> usize {
        let s = &indices[indptr[col]..indptr[col + 1]];
        // the pattern was built from the same faces, so the entry exists
        indptr[col] + s.partition_point(|&r| r < row)
    };
    let cots = corner_cotangents(mesh);
    for (t, c) in mesh.faces().iter().zip(&cots) {
        for k in 0..3 {
            let i = t[(k + 1) % 3] as usize;
            let j = t[(k + 2) % 3] as usize;
            add_edge_weight(&mut data, &pos, i, j, 0.5 * c[k]);
        }
    }
    CsMat::new_csc((n, n), indptr, indices, data)
}

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
