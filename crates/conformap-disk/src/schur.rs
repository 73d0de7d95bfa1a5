//! The Schur complement `A = L_BB − L_IBᵀ L_II⁻¹ L_IB` of CCEM Eq. 3.15 (the discrete
//! Dirichlet-to-Neumann map of the boundary), applied to boundary vectors in one of two
//! ways:
//!
//! - **dense**: `A` formed once as an `n_B × n_B` matrix from blocked multi-column solves
//!   `X = L_II⁻¹ L_IB` with the existing factor of `L_II`; every product afterwards is
//!   boundary-sized work (`n_B²`), independent of the interior size.
//! - **implicit**: every product `A x` costs one sparse product with `L_IB`, one two-column
//!   solve with the factor of `L_II`, one product with `L_IBᵀ` and one with `L_BB`.
//!
//! Forming `A` costs about `n_B` column solves, but done in blocks of many columns the
//! solves run at dense-kernel speed, several times faster per column than the two-column
//! solves of the implicit path. The dense path therefore wins whenever the minimization
//! needs more than a few dozen products and `n_B²` is small against the factor's
//! non-zeros; on a long boundary around a small interior (maze.obj: 3,064 boundary
//! vertices, 3,056 interior ones) a dense product costs more than an implicit one and the
//! implicit path wins. [`SchurMode::Auto`] decides with the cost model of
//! [`SchurMode::resolve`].

use std::cell::Cell;
use std::time::Instant;

use conformap_operators::mul_complex;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::problem::DiskProblem;

/// How the Schur complement of CCEM Eq. 3.15 is applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum SchurMode {
    /// Pick by the cost model of [`SchurMode::resolve`] (default).
    #[default]
    Auto,
    /// Form `A` once (`n_B × n_B`, `8 n_B²` bytes) and multiply densely.
    Dense,
    /// Apply `A` through a solve with the factor of `L_II` on every product.
    Implicit,
}

/// Largest dense Schur complement [`SchurMode::Auto`] will form: 512 MiB
/// (`n_B` ≈ 8,200). Above it the implicit path is used whatever the cost model says.
pub const DENSE_SCHUR_MAX_BYTES: usize = 512 << 20;

/// Products of `A` [`SchurMode::Auto`] budgets for a run when it compares the two paths:
/// a converged CCEM-QN run on the class-a meshes needs 40–260 (one per line-search
/// evaluation).
pub const EXPECTED_SCHUR_PRODUCTS: usize = 200;

/// Relative cost of one column of a blocked solve, per factor non-zero (measured).
const BLOCKED_COLUMN_COST: f64 = 1.3;
/// Relative cost of one two-column solve, per factor non-zero (measured).
const TWO_COLUMN_SOLVE_COST: f64 = 8.0;
/// Relative cost of a dense product, per entry of `A` (measured).
const DENSE_ENTRY_COST: f64 = 1.2;

/// Columns per blocked solve when forming `A`: large enough for the supernodal solve to run
/// at matrix–matrix speed (measured on hand.obj: 15 ms per column in two-column solves,
/// 5.9 with 16 columns, 3.9 with 64, 3.6 with 256), each block's buffer capped at 64 MiB.
/// Blocks are solved in parallel, so `n_B` is split into at least two blocks per thread
/// (but not below 16 columns).
const BLOCK_COLUMNS: usize = 64;
const MIN_BLOCK_COLUMNS: usize = 16;
const BLOCK_BYTES: usize = 64 << 20;

impl SchurMode {
    /// The path actually used for a problem: `Dense` or `Implicit` (never `Auto`).
    ///
    /// Cost model, in milliseconds per non-zero of the factor of `L_II` (`nnz`) and per
    /// entry of a dense `A`, measured on the class-a meshes (2 cores; see the crate
    /// README): a column of a blocked solve costs `1.3e-6 nnz`, a two-column solve (one
    /// implicit product) `8e-6 nnz`, a dense product `1.2e-6 n_B²`. Dense is chosen when
    /// `1.3 n_B nnz + 1.2 P n_B² < 8 P nnz` for `P =` [`EXPECTED_SCHUR_PRODUCTS`], and
    /// `8 n_B²` ≤ [`DENSE_SCHUR_MAX_BYTES`]. The formation runs on all threads, which the
    /// model leaves out as a margin in favour of dense.
    pub fn resolve(self, problem: &DiskProblem<'_>) -> Self {
        match self {
            Self::Dense | Self::Implicit => self,
            _ => {
                let nb = problem.num_boundary() as f64;
                let nnz = problem.interior_factor().stats().nnz_factor as f64;
                let p = EXPECTED_SCHUR_PRODUCTS as f64;
                let bytes = 8.0 * nb * nb;
                let dense = BLOCKED_COLUMN_COST * nb * nnz + DENSE_ENTRY_COST * p * nb * nb;
                let implicit = TWO_COLUMN_SOLVE_COST * p * nnz;
                if bytes <= DENSE_SCHUR_MAX_BYTES as f64 && dense < implicit {
                    Self::Dense
                } else {
                    Self::Implicit
                }
            }
        }
    }

    /// The name used in reports: `"dense"`, `"implicit"` or `"auto"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dense => "dense",
            Self::Implicit => "implicit",
            _ => "auto",
        }
    }
}

/// The Schur complement `A` of one problem, ready to multiply boundary vectors.
#[derive(Debug)]
pub(crate) struct Schur<'a, 'm> {
    problem: &'a DiskProblem<'m>,
    /// Column-major `n_B × n_B` matrix when dense.
    dense: Option<Vec<f64>>,
    /// Milliseconds spent forming the dense matrix (0 when implicit).
    pub form_ms: f64,
    products: Cell<usize>,
}

impl<'a, 'm> Schur<'a, 'm> {
    /// Prepares `A` for `problem` in the given mode (`Auto` is resolved first).
    pub fn new(problem: &'a DiskProblem<'m>, mode: SchurMode) -> Self {
        let t0 = Instant::now();
        let dense = match mode.resolve(problem) {
            SchurMode::Dense => Some(form_dense(problem)),
            _ => None,
        };
        Self {
            problem,
            dense,
            form_ms: t0.elapsed().as_secs_f64() * 1e3,
            products: Cell::new(0),
        }
    }

    /// The path in use.
    pub fn mode(&self) -> SchurMode {
        if self.dense.is_some() {
            SchurMode::Dense
        } else {
            SchurMode::Implicit
        }
    }

    /// Products computed so far.
    pub fn products(&self) -> usize {
        self.products.get()
    }

    /// `A x` for a complex boundary vector (real and imaginary parts are independent
    /// columns: `A` is real).
    pub fn apply(&self, x: &[Complex64]) -> Vec<Complex64> {
        self.products.set(self.products.get() + 1);
        let nb = x.len();
        match &self.dense {
            Some(a) => {
                // A is symmetric: (A x)_j = column j · x, contiguous in memory.
                a.chunks_exact(nb)
                    .map(|col| {
                        let (mut re, mut im) = (0.0, 0.0);
                        for (&c, z) in col.iter().zip(x) {
                            re += c * z.re;
                            im += c * z.im;
                        }
                        Complex64::new(re, im)
                    })
                    .collect()
            }
            None => {
                let p = self.problem;
                let mut rhs = p.blocks().ib_mul(x);
                for z in &mut rhs {
                    *z = -*z;
                }
                let xi = p.interior_factor().solve_complex(&rhs);
                let mut y = mul_complex(&p.blocks().bb, x);
                for (yj, zj) in y.iter_mut().zip(p.blocks().bi_mul(&xi)) {
                    *yj += zj;
                }
                y
            }
        }
    }
}

/// Forms `A = L_BB − L_IBᵀ L_II⁻¹ L_IB` column-major, in blocks of columns solved at once
/// with the factor of `L_II`. The result is symmetrized and its diagonal set to minus the
/// off-diagonal row sums, so that `A 1 = 0` holds to rounding (the constant vector spans
/// the null space of A, CCEM §3), which keeps the energy exactly rotation invariant.
pub(crate) fn form_dense(problem: &DiskProblem<'_>) -> Vec<f64> {
    let ni = problem.blocks().ii.rows();
    let nb = problem.num_boundary();
    // at least two blocks per thread when n_B allows, at most BLOCK_COLUMNS, BLOCK_BYTES
    let per_thread = nb
        .div_ceil(2 * rayon::current_num_threads())
        .max(MIN_BLOCK_COLUMNS);
    let cols = per_thread
        .min(BLOCK_COLUMNS)
        .min((BLOCK_BYTES / (8 * ni.max(1))).max(1));
    let mut a = vec![0.0; nb * nb];
    // blocks of `cols` columns of A, solved in parallel (each solve is sequential)
    a.par_chunks_mut(cols * nb)
        .enumerate()
        .for_each(|(b, out)| dense_columns(problem, b * cols, out));
    // symmetrize and make rows sum to zero
    for j in 0..nb {
        for r in (j + 1)..nb {
            let s = 0.5 * (a[j * nb + r] + a[r * nb + j]);
            a[j * nb + r] = s;
            a[r * nb + j] = s;
        }
    }
    for j in 0..nb {
        let off: f64 = (0..nb).filter(|&r| r != j).map(|r| a[j * nb + r]).sum();
        a[j * nb + j] = -off;
    }
    a
}

/// Columns `start..start + out.len() / n_B` of `A`, written into `out` (column-major).
fn dense_columns(problem: &DiskProblem<'_>, start: usize, out: &mut [f64]) {
    let blocks = problem.blocks();
    let ni = blocks.ii.rows();
    let nb = problem.num_boundary();
    let k = out.len() / nb;
    let ib = &blocks.ib;
    let mut buf = vec![0.0; ni * k];
    for c in 0..k {
        if let Some(col) = ib.outer_view(start + c) {
            for (i, &v) in col.iter() {
                buf[c * ni + i] = v;
            }
        }
    }
    problem.interior_factor().solve_in_place(&mut buf, k);
    for (c, col_out) in out.chunks_exact_mut(nb).enumerate() {
        let x = &buf[c * ni..(c + 1) * ni];
        // −L_IBᵀ X_j: one sparse dot product per boundary row
        for (r, col) in ib.outer_iterator().enumerate() {
            col_out[r] = -col.iter().map(|(i, &v)| v * x[i]).sum::<f64>();
        }
        if let Some(col) = blocks.bb.outer_view(start + c) {
            for (r, &v) in col.iter() {
                col_out[r] += v;
            }
        }
    }
}
