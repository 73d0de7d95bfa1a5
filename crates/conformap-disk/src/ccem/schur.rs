//! The Schur complement `A = L_BB − L_IBᵀ L_II⁻¹ L_IB` of CCEM Eq. 3.15 (the discrete
//! Dirichlet-to-Neumann map of the boundary), applied to boundary vectors in one of two
//! ways:
//!
//! - **dense**: `A` formed once as an `n_B × n_B` matrix by one forward solve restricted to
//!   the supernodes that the boundary's interior neighbours reach on their way to the root
//!   of the elimination tree ([`conformap_operators::Cholesky::inverse_gram`]: `A = L_BB −
//!   WᵀW`, `W = G⁻¹ P L_IB`, no backward solve); every product afterwards is
//!   boundary-sized work (`n_B²`), independent of the interior size.
//! - **implicit**: every product `A x` costs one sparse product with `L_IB`, one two-column
//!   solve with the factor of `L_II`, one product with `L_IBᵀ` and one with `L_BB`.
//!
//! On the class-a meshes forming `A` costs 2–10% of one factorization (it used to cost 3–5
//! factorizations as `n_B` blocked column solves); on a long boundary around a small
//! interior (maze.obj: 3,064 boundary vertices, 3,056 interior ones, `W` nearly dense) a
//! dense product and the formation cost more than implicit products and the implicit path
//! wins. [`SchurMode::Auto`] decides with the cost model of [`SchurMode::resolve`].

use std::cell::Cell;
use std::time::Instant;

use conformap_operators::mul_complex;
use num_complex::Complex64;
use sprs::CsMat;

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

/// Nanoseconds per multiply–add of the formation of `A` (dense kernels on supernodes;
/// measured 0.1–0.4 on 2 cores, depending on the machine's load).
const FORM_NS_PER_MULADD: f64 = 0.2;
/// Nanoseconds per factor non-zero of one two-column solve (memory-bound; measured 8).
const SOLVE_NS_PER_NNZ: f64 = 8.0;
/// Nanoseconds per entry of `A` of one dense product (memory-bound; measured 0.3–0.6).
const PRODUCT_NS_PER_ENTRY: f64 = 0.5;
/// Nanoseconds per multiply–add of a dense Cholesky factorization (the Angenent start and
/// the Hessian preconditioner, `n_B³ / 6` each; measured 0.03–0.1).
const DENSE_FACTOR_NS_PER_MULADD: f64 = 0.1;

impl SchurMode {
    /// Largest dense Schur complement [`SchurMode::Auto`] will form: 512 MiB
    /// (`n_B` ≈ 8,200). Above it the implicit path is used whatever the cost model says.
    pub const DENSE_MAX_BYTES: usize = 512 << 20;

    /// Products of `A` [`SchurMode::Auto`] budgets for a run when it compares the two paths:
    /// a converged CCEM-QN run needs 10–60 with the Hessian preconditioner (dense only), 40–550
    /// without (one per line-search evaluation); the model charges this many to both paths,
    /// which favours implicit.
    pub const EXPECTED_PRODUCTS: usize = 200;

    /// The path actually used for a problem: `Dense` or `Implicit` (never `Auto`).
    ///
    /// Cost model (nanoseconds, measured on 2 cores; see the constants): dense costs the
    /// formation (its multiply–adds `F` counted exactly by
    /// [`conformap_operators::Cholesky::inverse_gram_cost`]) at 0.2 ns, two dense
    /// factorizations of `n_B³ / 6` at 0.1 ns, and `P` products of `n_B²` entries at
    /// 0.5 ns; implicit costs `P` two-column solves of `nnz` (the factor's non-zeros) at
    /// 8 ns, `P =` [`Self::EXPECTED_PRODUCTS`]. Dense is chosen when cheaper and
    /// `8 n_B²` ≤ [`Self::DENSE_MAX_BYTES`].
    pub fn resolve(self, problem: &DiskProblem<'_>) -> Self {
        match self {
            Self::Dense | Self::Implicit => self,
            _ => {
                let nb = problem.num_boundary() as f64;
                if 8.0 * nb * nb > Self::DENSE_MAX_BYTES as f64 {
                    return Self::Implicit;
                }
                let factor = problem.interior_factor();
                let nnz = factor.stats().nnz_factor as f64;
                let p = Self::EXPECTED_PRODUCTS as f64;
                let implicit = SOLVE_NS_PER_NNZ * p * nnz;
                let Ok(form) = factor.inverse_gram_cost(&problem.blocks().ib) else {
                    return Self::Implicit;
                };
                let dense = FORM_NS_PER_MULADD * form
                    + DENSE_FACTOR_NS_PER_MULADD * nb * nb * nb / 3.0
                    + PRODUCT_NS_PER_ENTRY * p * nb * nb;
                if dense < implicit {
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
    /// `L_BI L_II⁻¹ b_I` for the interior part of the right-hand side given to
    /// [`Schur::with_rhs`] (dense mode only).
    coupling: Option<Vec<Complex64>>,
    /// Milliseconds spent forming the dense matrix (0 when implicit).
    pub form_ms: f64,
    products: Cell<usize>,
}

impl<'a, 'm> Schur<'a, 'm> {
    /// Prepares `A` for `problem` in the given mode (`Auto` is resolved first).
    pub fn new(problem: &'a DiskProblem<'m>, mode: SchurMode) -> Self {
        Self::with_rhs(problem, mode, &[])
    }

    /// As [`Self::new`]; when dense, also computes `L_BI L_II⁻¹ b_I` for the sparse
    /// right-hand side `rhs` (vertex, value) in the same pass (entries at boundary
    /// vertices are ignored): the boundary part of a solve with the full Laplacian.
    pub fn with_rhs(
        problem: &'a DiskProblem<'m>,
        mode: SchurMode,
        rhs: &[(u32, Complex64)],
    ) -> Self {
        let t0 = Instant::now();
        let (dense, coupling) = match mode.resolve(problem) {
            SchurMode::Dense => match form_dense(problem, rhs) {
                Some((a, c)) => (Some(a), Some(c)),
                None => (None, None),
            },
            _ => (None, None),
        };
        Self {
            problem,
            dense,
            coupling,
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

    /// The dense matrix (column-major `n_B × n_B`), when formed.
    pub fn dense(&self) -> Option<&[f64]> {
        self.dense.as_deref()
    }

    /// `L_BI L_II⁻¹ b_I` for the right-hand side given to [`Self::with_rhs`], when dense.
    pub fn coupling(&self) -> Option<&[Complex64]> {
        self.coupling.as_deref()
    }

    /// Products computed so far.
    pub fn products(&self) -> usize {
        self.products.get()
    }

    /// `A x` for a complex boundary vector (real and imaginary parts are independent
    /// columns: `A` is real).
    pub fn apply(&self, x: &[Complex64]) -> Vec<Complex64> {
        self.products.set(self.products.get() + 1);
        match &self.dense {
            Some(a) => dense_product(a, x),
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

/// `A x` for a dense symmetric `A` (column-major), reading only its lower triangle (half
/// the memory traffic of a full product, which is what a product costs): column `j`
/// contributes `Σ_{i≥j} a_ij x_i` to `y_j` and `a_ij x_j` to `y_i`, `i > j`, in one pass,
/// for the real and imaginary parts at once, with four independent partial sums so that
/// the loop vectorizes. On one thread (see the body for why).
fn dense_product(a: &[f64], x: &[Complex64]) -> Vec<Complex64> {
    let nb = x.len();
    let re: Vec<f64> = x.iter().map(|z| z.re).collect();
    let im: Vec<f64> = x.iter().map(|z| z.im).collect();
    // one thread: measured inside a run (the rayon workers asleep between products),
    // splitting the columns over two threads was slower at every size, 0.66 against 0.43
    // ms at n_B = 896 and 6.6 against 6.1 ms at 2,828 (it wins only in a tight loop with
    // the workers spinning)
    let (yr, yi) = {
        let (mut yr, mut yi) = (vec![0.0; nb], vec![0.0; nb]);
        for j in 0..nb {
            let col = &a[j * nb + j..(j + 1) * nb];
            let (xr, xi) = (re[j], im[j]);
            let (mut sr, mut si) = ([0.0f64; 4], [0.0f64; 4]);
            // the diagonal entry: dot only
            let (d, below) = (col[0], &col[1..]);
            let rr = &re[j + 1..];
            let ri = &im[j + 1..];
            let (yr_b, yi_b) = (&mut yr[j + 1..], &mut yi[j + 1..]);
            let n4 = below.len() / 4 * 4;
            let (yr4, yr_t) = yr_b.split_at_mut(n4);
            let (yi4, yi_t) = yi_b.split_at_mut(n4);
            for ((((c, r), i), yrc), yic) in below[..n4]
                .chunks_exact(4)
                .zip(rr[..n4].chunks_exact(4))
                .zip(ri[..n4].chunks_exact(4))
                .zip(yr4.chunks_exact_mut(4))
                .zip(yi4.chunks_exact_mut(4))
            {
                for l in 0..4 {
                    sr[l] += c[l] * r[l];
                    si[l] += c[l] * i[l];
                    yrc[l] += c[l] * xr;
                    yic[l] += c[l] * xi;
                }
            }
            let (mut tr, mut ti) = (d * xr, d * xi);
            for ((((&c, &r), &i), yrc), yic) in below[n4..]
                .iter()
                .zip(&rr[n4..])
                .zip(&ri[n4..])
                .zip(yr_t.iter_mut())
                .zip(yi_t.iter_mut())
            {
                tr += c * r;
                ti += c * i;
                *yrc += c * xr;
                *yic += c * xi;
            }
            yr[j] += (sr[0] + sr[1]) + (sr[2] + sr[3]) + tr;
            yi[j] += (si[0] + si[1]) + (si[2] + si[3]) + ti;
        }
        (yr, yi)
    };
    yr.into_iter()
        .zip(yi)
        .map(|(r, i)| Complex64::new(r, i))
        .collect()
}

/// Forms `A = L_BB − L_IBᵀ L_II⁻¹ L_IB` column-major with one restricted forward solve
/// over the supernodes the boundary's neighbours reach
/// ([`conformap_operators::Cholesky::inverse_gram`] with `R = [L_IB | b_I]`), and
/// `L_BI L_II⁻¹ b_I` for the interior part `b_I` of `rhs`. The result is symmetric and its
/// diagonal set to minus the off-diagonal row sums, so that `A 1 = 0` holds to rounding
/// (the constant vector spans the null space of A, CCEM §3), which keeps the energy
/// exactly rotation invariant. `None` if the factor refuses `R` (never for a problem's
/// own blocks).
pub(crate) fn form_dense(
    problem: &DiskProblem<'_>,
    rhs: &[(u32, Complex64)],
) -> Option<(Vec<f64>, Vec<Complex64>)> {
    let blocks = problem.blocks();
    let part = problem.partition();
    let ni = blocks.ii.rows();
    let nb = problem.num_boundary();
    // R = [L_IB | Re b_I | Im b_I]
    let ib = blocks.ib.view();
    let (ptr, idx, val) = ib.into_raw_storage();
    let mut indptr = ptr.to_vec();
    let mut indices = idx.to_vec();
    let mut data = val.to_vec();
    let interior_rhs: Vec<(usize, Complex64)> = rhs
        .iter()
        .filter(|(v, _)| part.is_interior[*v as usize])
        .map(|&(v, z)| (part.local[v as usize] as usize, z))
        .collect();
    for part_of in [|z: Complex64| z.re, |z: Complex64| z.im] {
        let mut col: Vec<(usize, f64)> =
            interior_rhs.iter().map(|&(i, z)| (i, part_of(z))).collect();
        col.sort_unstable_by_key(|e| e.0);
        for (i, v) in col {
            if indices.len() > *indptr.last().unwrap_or(&0) && indices.last() == Some(&i) {
                if let Some(d) = data.last_mut() {
                    *d += v;
                }
            } else {
                indices.push(i);
                data.push(v);
            }
        }
        indptr.push(indices.len());
    }
    let r = CsMat::new_csc((ni, nb + 2), indptr, indices, data);
    let gram = problem.interior_factor().inverse_gram(&r).ok()?;
    let k = nb + 2;
    let coupling = (0..nb)
        .map(|j| Complex64::new(gram.get(j, nb), gram.get(j, nb + 1)))
        .collect();
    // A in place of the Gram matrix: column j moves from offset j·k to j·n_B (never
    // forward of its source, so a front-to-back pass is safe). A second n_B² buffer would
    // cost its memory and, on fresh pages, more time than the copy (30 of 434 ms on the
    // 1M square).
    let mut a = gram.values;
    for j in 0..nb {
        a.copy_within(j * k..j * k + nb, j * nb);
        let dst = &mut a[j * nb..(j + 1) * nb];
        for d in dst.iter_mut() {
            *d = -*d;
        }
        if let Some(col) = blocks.bb.outer_view(j) {
            for (i, &v) in col.iter() {
                dst[i] += v;
            }
        }
    }
    a.truncate(nb * nb);
    a.shrink_to_fit();
    // the Gram part is exactly symmetric (mirrored); only L_BB's entries can differ from
    // their transposes by rounding
    for (j, col) in blocks.bb.outer_iterator().enumerate() {
        for (i, _) in col.iter().filter(|&(i, _)| i > j) {
            let s = 0.5 * (a[j * nb + i] + a[i * nb + j]);
            a[j * nb + i] = s;
            a[i * nb + j] = s;
        }
    }
    set_null_space_diagonal(&mut a, nb);
    Some((a, coupling))
}

/// Sets the diagonal of the symmetric `a` (`n × n`, column-major) to minus the
/// off-diagonal column sums.
fn set_null_space_diagonal(a: &mut [f64], nb: usize) {
    for j in 0..nb {
        let col = &a[j * nb..(j + 1) * nb];
        let off: f64 = col
            .iter()
            .enumerate()
            .filter(|&(r, _)| r != j)
            .map(|(_, &v)| v)
            .sum();
        a[j * nb + j] = -off;
    }
}

/// Symmetrizes `a` (`n × n`, column-major) and sets its diagonal to minus the off-diagonal
/// column sums.
#[cfg(test)]
fn symmetrize_null_space(a: &mut [f64], nb: usize) {
    for j in 0..nb {
        for r in (j + 1)..nb {
            let s = 0.5 * (a[j * nb + r] + a[r * nb + j]);
            a[j * nb + r] = s;
            a[r * nb + j] = s;
        }
    }
    set_null_space_diagonal(a, nb);
}

/// The former way of forming `A` (kept as the reference of the tests): blocked
/// multi-column solves `L_II⁻¹ L_IB` with the factor, in parallel.
#[cfg(test)]
pub(crate) fn form_dense_by_solves(problem: &DiskProblem<'_>) -> Vec<f64> {
    let blocks = problem.blocks();
    let ni = blocks.ii.rows();
    let nb = problem.num_boundary();
    let mut a = vec![0.0; nb * nb];
    let mut buf = vec![0.0; ni];
    for j in 0..nb {
        buf.fill(0.0);
        if let Some(col) = blocks.ib.outer_view(j) {
            for (i, &v) in col.iter() {
                buf[i] = v;
            }
        }
        problem.interior_factor().solve_in_place(&mut buf, 1);
        let out = &mut a[j * nb..(j + 1) * nb];
        for (r, col) in blocks.ib.outer_iterator().enumerate() {
            out[r] = -col.iter().map(|(i, &v)| v * buf[i]).sum::<f64>();
        }
        if let Some(col) = blocks.bb.outer_view(j) {
            for (r, &v) in col.iter() {
                out[r] += v;
            }
        }
    }
    symmetrize_null_space(&mut a, nb);
    a
}
