//! One Koebe step for one open loop: the filled planar mesh `M^(k)` (every loop but `k`
//! closed by its centroid fan, CEM Algorithm 2 step 8), its Laplacian, the disk map with
//! loop `k` on the unit circle (step 9), and the reuse of the symbolic factorization.
//!
//! For a given open loop the connectivity of `M^(k)` never changes, so the sparsity pattern
//! of its Laplacian is built once, with the slot of every contribution in the CSC value
//! array; each step only recomputes the values, and the Cholesky factor of `L_II` is
//! refactored numerically with the symbolic analysis of the first step (`Cholesky::refactor`).

use std::time::Instant;

use conformap_mesh::{centroid_fan_faces, TriMesh};
use conformap_operators::{Cholesky, LaplacianBlocks, Partition};
use num_complex::Complex64;
use sprs::CsMat;

use crate::error::DiskError;
use crate::koebe::step_newton::{minimize, NewtonOptions, NewtonResult};

/// Columns per blocked solve when forming the Schur complement: `64`, enough for the
/// multi-column solve to run at dense-kernel speed while the block (`64 n_I` values) stays
/// small against the factor.
const SCHUR_BLOCK: usize = 64;

/// Slots in the CSC value array of the four entries an edge `(i, j)` touches:
/// `(i, j)`, `(j, i)`, `(i, i)`, `(j, j)`.
type EdgeSlots = [usize; 4];

/// The filled mesh of one open loop and everything reusable about it.
#[derive(Debug)]
pub(crate) struct LoopSystem {
    /// The open loop (index into the input's boundary loops).
    pub open: usize,
    /// Loops closed by a centroid fan, in loop order; the centre of `filled[j]` is vertex
    /// `n + j`.
    pub filled: Vec<usize>,
    n_all: usize,
    indptr: Vec<usize>,
    indices: Vec<usize>,
    /// Every face of `M^(open)`: the input's, then the fans.
    planar_faces: Vec<[u32; 3]>,
    face_slots: Vec<[EdgeSlots; 3]>,
    partition: Partition,
    factor: Option<Cholesky>,
}

/// What one step computed.
#[derive(Debug)]
pub(crate) struct StepSolve {
    /// The disk map of the filled mesh (input vertices first, then the centres).
    pub map: Vec<Complex64>,
    /// The boundary minimization.
    pub newton: NewtonResult,
    /// Whether the factor of `L_II` was a numeric refactorization (symbolic analysis reused).
    pub refactored: bool,
    /// Milliseconds: assembly, factorization, Schur complement, minimization + extension.
    pub assemble_ms: f64,
    /// See `assemble_ms`.
    pub factor_ms: f64,
    /// See `assemble_ms`.
    pub schur_ms: f64,
    /// See `assemble_ms`.
    pub solve_ms: f64,
}

impl LoopSystem {
    /// The pattern of `M^(open)`'s Laplacian, with the slot of every face's contributions.
    pub(crate) fn new(mesh: &TriMesh, open: usize) -> Self {
        let n = mesh.num_vertices();
        let loops = mesh.boundary_loops();
        let mut planar_faces = mesh.faces().to_vec();
        let filled: Vec<usize> = (0..loops.len()).filter(|&l| l != open).collect();
        for (j, &l) in filled.iter().enumerate() {
            planar_faces.extend(centroid_fan_faces(&loops[l], (n + j) as u32));
        }
        let n_all = n + filled.len();
        // (column, row) pairs of the pattern
        let mut pairs: Vec<(usize, usize)> = Vec::new();
        for t in &planar_faces {
            for k in 0..3 {
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                pairs.extend([(j, i), (i, j), (i, i), (j, j)]);
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        let mut indptr = vec![0usize; n_all + 1];
        for &(c, _) in &pairs {
            indptr[c + 1] += 1;
        }
        for c in 0..n_all {
            indptr[c + 1] += indptr[c];
        }
        let indices: Vec<usize> = pairs.iter().map(|&(_, r)| r).collect();
        let slot = |row: usize, col: usize| -> usize {
            let s = &indices[indptr[col]..indptr[col + 1]];
            indptr[col] + s.partition_point(|&r| r < row)
        };
        let face_slots = planar_faces
            .iter()
            .map(|t| {
                std::array::from_fn(|k| {
                    let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                    [slot(i, j), slot(j, i), slot(i, i), slot(j, j)]
                })
            })
            .collect();
        let partition = Partition::new(n_all, &loops[open]);
        Self {
            open,
            filled,
            n_all,
            indptr,
            indices,
            planar_faces,
            face_slots,
            partition,
            factor: None,
        }
    }

    /// The Laplacian of `M^(open)` at the planar positions `w` (one per vertex of the filled
    /// mesh): `−½ cot` of every face angle on the opposite edge
    /// (the convention of `conformap_operators::cotan_laplacian`). Cotangents use the
    /// unsigned area, as for a surface: every face's stiffness block is then positive
    /// semidefinite and `L_II` positive definite even where an early, far-from-circular
    /// step leaves a folded image face or a fan centre outside a non-convex hole; once the
    /// holes are round and nothing is folded, signed and unsigned agree.
    fn laplacian(&self, w: &[Complex64]) -> Result<CsMat<f64>, DiskError> {
        let mut data = vec![0.0; self.indices.len()];
        for (t, slots) in self.planar_faces.iter().zip(&self.face_slots) {
            let p = t.map(|v| w[v as usize]);
            for k in 0..3 {
                let u = p[(k + 1) % 3] - p[k];
                let v = p[(k + 2) % 3] - p[k];
                let cot = (u.re * v.re + u.im * v.im) / (u.re * v.im - u.im * v.re).abs();
                if !cot.is_finite() {
                    return Err(DiskError::NonFinite {
                        vertex: t[k] as usize,
                        stage: "planar cotangent weights of a Koebe step",
                    });
                }
                let half = 0.5 * cot;
                let s = slots[k];
                data[s[0]] -= half;
                data[s[1]] -= half;
                data[s[2]] += half;
                data[s[3]] += half;
            }
        }
        Ok(CsMat::new_csc(
            (self.n_all, self.n_all),
            self.indptr.clone(),
            self.indices.clone(),
            data,
        ))
    }

    /// Maps `M^(open)`, laid out in the plane at `w` (loop `open` around the origin), onto
    /// the unit disk: assembles, (re)factors `L_II`, forms the dense Schur complement,
    /// minimizes the conformal energy on the boundary angles from `theta0`, and extends
    /// harmonically.
    pub(crate) fn solve(
        &mut self,
        w: &[Complex64],
        theta0: Vec<f64>,
        newton: &NewtonOptions,
    ) -> Result<StepSolve, DiskError> {
        let t0 = Instant::now();
        let l = self.laplacian(w)?;
        let blocks = LaplacianBlocks::new(&l, &self.partition);
        let assemble_ms = ms(t0);
        let t1 = Instant::now();
        let refactored = match &mut self.factor {
            Some(f) => {
                f.refactor(&blocks.ii)?;
                true
            }
            None => {
                self.factor = Some(Cholesky::factor(&blocks.ii)?);
                false
            }
        };
        let factor_ms = ms(t1);
        let Some(factor) = self.factor.as_ref() else {
            unreachable!("set above")
        };
        let t2 = Instant::now();
        let s = dense_schur(&blocks, factor);
        let schur_ms = ms(t2);
        let t3 = Instant::now();
        // the boundary's vertex mean stays where the start has it: a domain that is already
        // circular is then its own minimizer (the identity satisfies the constraint)
        let m = theta0.len() as f64;
        let mean = theta0
            .iter()
            .fold([0.0, 0.0], |a, t| [a[0] + t.cos() / m, a[1] + t.sin() / m]);
        let result = minimize(&s, theta0, mean, newton);
        let fb: Vec<Complex64> = result
            .theta
            .iter()
            .map(|&t| Complex64::from_polar(1.0, t))
            .collect();
        let mut rhs = blocks.ib_mul(&fb);
        for z in &mut rhs {
            *z = -*z;
        }
        let fi = factor.solve_complex(&rhs);
        let map = self.partition.assemble(&fi, &fb);
        if let Some(v) = map.iter().position(|z| !z.is_finite()) {
            return Err(DiskError::NonFinite {
                vertex: v,
                stage: "harmonic extension of a Koebe step",
            });
        }
        Ok(StepSolve {
            map,
            newton: result,
            refactored,
            assemble_ms,
            factor_ms,
            schur_ms,
            solve_ms: ms(t3),
        })
    }
}

/// `S = L_BB − L_IBᵀ L_II⁻¹ L_IB`, dense column-major `n_B × n_B`, from blocked
/// multi-column solves with the factor of `L_II`.
pub(crate) fn dense_schur(blocks: &LaplacianBlocks, factor: &Cholesky) -> Vec<f64> {
    let ni = blocks.ii.rows();
    let nb = blocks.bb.rows();
    let mut s = vec![0.0; nb * nb];
    for (c, col) in blocks.bb.outer_iterator().enumerate() {
        for (r, &v) in col.iter() {
            s[c * nb + r] += v;
        }
    }
    let ib_cols: Vec<Vec<(usize, f64)>> = blocks
        .ib
        .outer_iterator()
        .map(|col| col.iter().map(|(r, &v)| (r, v)).collect())
        .collect();
    let mut start = 0;
    while start < nb {
        let width = SCHUR_BLOCK.min(nb - start);
        let mut x = vec![0.0; ni * width];
        for j in 0..width {
            for &(r, v) in &ib_cols[start + j] {
                x[j * ni + r] = v;
            }
        }
        factor.solve_in_place(&mut x, width);
        for j in 0..width {
            let xj = &x[j * ni..(j + 1) * ni];
            let c = start + j;
            for (row, col) in ib_cols.iter().enumerate() {
                let dot: f64 = col.iter().map(|&(r, v)| v * xj[r]).sum();
                s[c * nb + row] -= dot;
            }
        }
        start += width;
    }
    // symmetrize the rounding
    for i in 0..nb {
        for j in i + 1..nb {
            let avg = 0.5 * (s[j * nb + i] + s[i * nb + j]);
            s[j * nb + i] = avg;
            s[i * nb + j] = avg;
        }
    }
    s
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
