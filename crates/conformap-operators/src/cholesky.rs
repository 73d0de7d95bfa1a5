//! The linear-solver facade: factor a sparse symmetric positive definite matrix once,
//! solve many right-hand sides.
//!
//! # Backend: faer, not sprs-ldl
//! The factorization is faer's sparse Cholesky (pure Rust, AMD fill-reducing ordering,
//! supernodal `LLᵀ`). sprs-ldl, on the design card, was measured on this class of machine
//! (2 cores) for a 1M-vertex cotangent `L_II`: 34 s to factor even with an AMD permutation
//! (faer: about 7–8 s), and with its default RCM ordering 16 s at 100k vertices and
//! 275 s / 6.6 GiB at 500k; it is also LGPL-2.1. sprs stays the assembly format: a sprs CSC
//! matrix is viewed by faer without a copy of its index arrays.
//!
//! Solves run sequentially ([`Par::Seq`]): faer's rayon-parallel supernodal solve was
//! measured about 10× slower than sequential on 2 cores. They are the facade's own
//! supernode loop (faer's kernels per supernode), whose forward pass skips the supernodes
//! a right-hand side never reaches: the harmonic extension's right-hand side lives on the
//! boundary's interior neighbours, and its solve costs 0.6–0.7 of a full one on 1M-face
//! meshes. The numeric factorization uses
//! [`CholeskyOptions::threads`] threads (default: all).

use std::time::Instant;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::reborrow::ReborrowMut;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use num_complex::Complex64;
use sprs::CsMat;

use crate::OperatorError;

mod inverse_gram;
mod nested_dissection;

pub use inverse_gram::InverseGram;

/// The fill-reducing ordering of a factorization.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Ordering {
    /// The facade's own policy (default): nested dissection from
    /// [`Ordering::NESTED_DISSECTION_MIN_DIM`] rows, approximate minimum degree below
    /// (see [`Ordering::resolve`]). Every solver that factors with the defaults (disk
    /// problems, sphere maps, …) inherits it.
    #[default]
    Auto,
    /// Approximate minimum degree.
    Amd,
    /// Nested dissection by breadth-first level structures (see
    /// [`Ordering::NestedDissection`]'s module notes in the facade docs).
    NestedDissection,
    /// No reordering.
    Identity,
    /// A caller-given permutation: `perm[k]` is the row eliminated at step `k`.
    Custom(Vec<usize>),
}

impl Ordering {
    /// Dimension (interior vertices, for `L_II`) from which [`Ordering::Auto`] orders by
    /// nested dissection: 200,000. Measured on the generated meshes (factor flops, ND
    /// against AMD): from 250k interior vertices nested dissection needs fewer on the square
    /// (2.9 against 3.1 Gflop at 250k, 7.7 against 9.7 at 500k, 23 against 36 at 1M), about
    /// as many on the disk (8.3 against 8.3 at 500k), half as many on the cut spheres (14
    /// against 29 at 500k, 40 against 99 at 1M), and 25–50 % fewer for forming the Schur
    /// complement; below 130k it needs more on the square and on hand.obj (0.95 against
    /// 0.87 Gflop at 126k, 0.43 against 0.31 on hand).
    pub const NESTED_DISSECTION_MIN_DIM: usize = 200_000;

    /// The ordering used for a matrix of dimension `n`: [`Ordering::Auto`] resolved by its
    /// policy, every other ordering itself.
    ///
    /// ```
    /// use conformap_operators::Ordering;
    /// assert_eq!(Ordering::Auto.resolve(130_000), Ordering::Amd);
    /// assert_eq!(Ordering::Auto.resolve(Ordering::NESTED_DISSECTION_MIN_DIM), Ordering::NestedDissection);
    /// assert_eq!(Ordering::Amd.resolve(1 << 20), Ordering::Amd);
    /// ```
    pub fn resolve(&self, n: usize) -> Self {
        match self {
            Self::Auto if n >= Self::NESTED_DISSECTION_MIN_DIM => Self::NestedDissection,
            Self::Auto => Self::Amd,
            other => other.clone(),
        }
    }

    /// The name used in [`FactorStats::ordering`] and reports: `amd`,
    /// `nested-dissection`, `identity` or `custom`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Amd => "amd",
            Self::NestedDissection => "nested-dissection",
            Self::Identity => "identity",
            Self::Custom(_) => "custom",
        }
    }

    /// The names a user gives on a command line (parsed by `FromStr`, written by
    /// `Display`): `auto` ([`Ordering::Auto`]), `amd` ([`Ordering::Amd`]) and `nd`
    /// ([`Ordering::NestedDissection`]).
    pub const NAMES: [&'static str; 3] = ["auto", "amd", "nd"];
}

/// The command-line spelling: `auto`, `amd`, `nd` (see [`Ordering::NAMES`]); the orderings
/// a user cannot name show as `identity` and `custom`.
///
/// ```
/// use conformap_operators::Ordering;
/// for name in Ordering::NAMES {
///     assert_eq!(name.parse::<Ordering>()?.to_string(), name);
/// }
/// assert_eq!("nd".parse::<Ordering>()?, Ordering::NestedDissection);
/// assert!("metis".parse::<Ordering>().is_err());
/// # Ok::<(), conformap_operators::OperatorError>(())
/// ```
impl std::fmt::Display for Ordering {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::NestedDissection => "nd",
            other => other.name(),
        })
    }
}

impl std::str::FromStr for Ordering {
    type Err = OperatorError;

    /// Parses one of [`Ordering::NAMES`].
    fn from_str(s: &str) -> Result<Self, OperatorError> {
        match s {
            "auto" => Ok(Self::Auto),
            "amd" => Ok(Self::Amd),
            "nd" => Ok(Self::NestedDissection),
            _ => Err(OperatorError::UnknownOrdering {
                name: s.to_string(),
            }),
        }
    }
}

/// Options of [`Cholesky::factor_with`].
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct CholeskyOptions {
    /// Fill-reducing ordering. Default: [`Ordering::Auto`] (AMD below 200,000 rows, nested
    /// dissection from there).
    pub ordering: Ordering,
    /// Threads for the numeric factorization; 0 = all rayon threads. Default: 0.
    pub threads: usize,
}

impl CholeskyOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        ordering: Ordering::Auto,
        threads: 0,
    };

    /// Sets [`Self::ordering`].
    #[must_use]
    pub fn with_ordering(mut self, ordering: Ordering) -> Self {
        self.ordering = ordering;
        self
    }

    /// Sets [`Self::threads`].
    #[must_use]
    pub fn with_threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }
}

impl Default for CholeskyOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a factorization cost and produced.
#[derive(Debug, Clone, PartialEq)]
pub struct FactorStats {
    /// Matrix dimension.
    pub n: usize,
    /// Stored non-zeros of the input (full symmetric storage).
    pub nnz_matrix: usize,
    /// Non-zeros of the factor `L`.
    pub nnz_factor: usize,
    /// Whether faer chose the supernodal (vs simplicial) variant.
    pub supernodal: bool,
    /// Symbolic analysis (ordering + structure) time, milliseconds.
    pub analyse_ms: f64,
    /// Numeric factorization time, milliseconds.
    pub factor_ms: f64,
    /// The fill-reducing ordering used ([`Ordering::name`]).
    pub ordering: &'static str,
}

/// The symbolic analysis of [`Cholesky::analyse_with`], waiting for the values.
#[derive(Debug)]
pub struct SymbolicAnalysis(Cholesky, u64);

/// A fingerprint of a CSC pattern (dimensions, column pointers, row indices; FNV-1a).
fn pattern_fingerprint(a: &CsMat<f64>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |x: usize| {
        h ^= x as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    };
    eat(a.rows());
    eat(a.cols());
    for &p in a.indptr().raw_storage() {
        eat(p);
    }
    for &i in a.indices() {
        eat(i);
    }
    h
}

impl SymbolicAnalysis {
    /// Milliseconds the analysis took.
    pub fn analyse_ms(&self) -> f64 {
        self.0.stats.analyse_ms
    }

    /// The fill-reducing permutation chosen (see [`Cholesky::permutation`]).
    pub fn permutation(&self) -> Vec<usize> {
        self.0.permutation()
    }

    /// The numeric factorization of `a`, which must have exactly the pattern analysed.
    ///
    /// # Errors
    /// [`OperatorError::PatternMismatch`] when `a`'s pattern is not the analysed one (the
    /// caller then analyses `a` itself); else as [`Cholesky::refactor`].
    pub fn factor(mut self, a: &CsMat<f64>) -> Result<Cholesky, OperatorError> {
        if pattern_fingerprint(a) != self.1 {
            return Err(OperatorError::PatternMismatch);
        }
        self.0.stats.nnz_matrix = a.nnz();
        self.0.refactor(a)?;
        Ok(self.0)
    }
}

/// The approximate minimum degree ordering of the symmetric pattern of `a` (one
/// triangle or both; values ignored) alone, without the symbolic factorization that
/// [`Cholesky::analyse_with`] builds on it: the permutation `Ordering::Amd` would choose
/// (faer's AMD with its default control on the same pattern). For an ordering computed
/// on a smaller graph and expanded (`Ordering::Custom`), as the 2 × 2 blocks of a planar
/// layout's unknowns: on spot's 3,046-vertex chart 2.0 ms as an analysis, the order alone
/// a third of that.
///
/// # Errors
/// [`OperatorError::NotSquareCsc`] when `a` is not square CSC; the faer error when its
/// workspace cannot be allocated.
pub fn amd_permutation(a: &CsMat<f64>) -> Result<Vec<usize>, OperatorError> {
    let mat = view(a)?;
    let n = a.rows();
    let mut fwd = vec![0usize; n];
    let mut inv = vec![0usize; n];
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_maybe_unsorted_scratch::<
        usize,
    >(n, a.nnz()))
    .map_err(|_| OperatorError::from_faer(faer::sparse::FaerError::OutOfMemory, "the ordering"))?;
    faer::sparse::linalg::amd::order_maybe_unsorted(
        &mut fwd,
        &mut inv,
        mat.symbolic(),
        Default::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| OperatorError::from_faer(e, "the ordering"))?;
    Ok(fwd)
}

/// A sparse Cholesky factorization `A = LLᵀ` (with fill-reducing permutation), reusable for
/// any number of solves and refactorizable for a new matrix with the same pattern.
#[derive(Debug)]
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    par: Par,
    stats: FactorStats,
}

fn par_for(threads: usize) -> Par {
    if threads == 1 {
        Par::Seq
    } else {
        Par::rayon(threads)
    }
}

fn view(a: &CsMat<f64>) -> Result<SparseColMatRef<'_, usize, f64>, OperatorError> {
    if !a.is_csc() || a.rows() != a.cols() {
        return Err(OperatorError::NotSquareCsc {
            rows: a.rows(),
            cols: a.cols(),
        });
    }
    let (rows, cols) = (a.rows(), a.cols());
    let (col_ptr, indices, data) = a.view().into_raw_storage();
    if col_ptr.first() != Some(&0) {
        return Err(OperatorError::NotSquareCsc { rows, cols });
    }
    let symbolic = SymbolicSparseColMatRef::new_checked(rows, cols, col_ptr, None, indices);
    Ok(SparseColMatRef::new(symbolic, data))
}

impl Cholesky {
    /// Factors the symmetric positive definite matrix `a` (CSC, full or upper storage;
    /// only the upper triangle is read) with the default options.
    ///
    /// # Errors
    /// [`OperatorError::NotPositiveDefinite`] with the failing pivot, or
    /// [`OperatorError::OutOfMemory`] if faer runs out of memory.
    ///
    /// # Examples
    /// ```
    /// use conformap_operators::Cholesky;
    /// use sprs::TriMat;
    /// let mut t = TriMat::new((2, 2));
    /// t.add_triplet(0, 0, 4.0);
    /// t.add_triplet(1, 0, 1.0);
    /// t.add_triplet(0, 1, 1.0);
    /// t.add_triplet(1, 1, 3.0);
    /// let a = t.to_csc();
    /// let chol = Cholesky::factor(&a).unwrap();
    /// let mut x = vec![1.0, 2.0];
    /// chol.solve_in_place(&mut x, 1);
    /// assert!((4.0 * x[0] + x[1] - 1.0).abs() < 1e-14);
    /// assert!((x[0] + 3.0 * x[1] - 2.0).abs() < 1e-14);
    /// ```
    pub fn factor(a: &CsMat<f64>) -> Result<Self, OperatorError> {
        Self::factor_with(a, &CholeskyOptions::DEFAULT)
    }

    /// Factors `a` with the given options.
    ///
    /// # Errors
    /// See [`Cholesky::factor`]; also [`OperatorError::BadPermutation`] for an invalid
    /// custom ordering.
    pub fn factor_with(a: &CsMat<f64>, options: &CholeskyOptions) -> Result<Self, OperatorError> {
        let mut chol = Self::analyse_with(a, options)?.0;
        chol.refactor(a)?;
        Ok(chol)
    }

    /// The symbolic analysis alone (fill-reducing ordering, supernodal structure) of a
    /// matrix with the pattern of `a` (its values are not read): the numeric factorization
    /// follows with [`SymbolicAnalysis::factor`] for any matrix of exactly this pattern.
    /// The analysis needs only the pattern, so it can run while the values are still being
    /// computed (the disk solver overlaps it with the assembly of the Laplacian).
    ///
    /// # Errors
    /// [`OperatorError::NotSquareCsc`], [`OperatorError::BadPermutation`] for an invalid
    /// custom ordering, [`OperatorError::OutOfMemory`] or [`OperatorError::IndexOverflow`] if faer's analysis fails.
    pub fn analyse_with(
        a: &CsMat<f64>,
        options: &CholeskyOptions,
    ) -> Result<SymbolicAnalysis, OperatorError> {
        let t0 = Instant::now();
        let mat = view(a)?;
        let n = a.rows();
        let (fwd, inv);
        let resolved = options.ordering.resolve(n);
        let ordering = match &resolved {
            Ordering::Amd | Ordering::Auto => SymmetricOrdering::Amd,
            // faer's `SymmetricOrdering::Identity` skips the step that reduces a full
            // symmetric matrix to one triangle and then fails on full storage (measured:
            // "not positive definite" on an SPD L_II); an explicit identity permutation
            // takes the normal path.
            Ordering::Identity | Ordering::Custom(_) | Ordering::NestedDissection => {
                let p: Vec<usize> = match &resolved {
                    Ordering::Custom(p) => p.clone(),
                    Ordering::NestedDissection => {
                        nested_dissection::nested_dissection(mat.symbolic())
                    }
                    _ => (0..n).collect(),
                };
                if p.len() != n {
                    return Err(OperatorError::BadPermutation { n });
                }
                let mut seen = vec![usize::MAX; n];
                for (k, &i) in p.iter().enumerate() {
                    if i >= n || seen[i] != usize::MAX {
                        return Err(OperatorError::BadPermutation { n });
                    }
                    seen[i] = k;
                }
                fwd = p;
                inv = seen;
                SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(&fwd, &inv, n))
            }
        };
        let symbolic = factorize_symbolic_cholesky(
            mat.symbolic(),
            Side::Upper,
            ordering,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| OperatorError::from_faer(e, "the symbolic analysis"))?;
        let analyse_ms = t0.elapsed().as_secs_f64() * 1e3;
        let chol = Self {
            values: Vec::new(),
            par: par_for(options.threads),
            stats: FactorStats {
                n,
                nnz_matrix: a.nnz(),
                nnz_factor: symbolic.len_val(),
                supernodal: matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_)),
                analyse_ms,
                factor_ms: 0.0,
                ordering: resolved.name(),
            },
            symbolic,
        };
        Ok(SymbolicAnalysis(chol, pattern_fingerprint(a)))
    }

    /// Numeric refactorization for a matrix with the same sparsity pattern as the one
    /// first factored (symbolic analysis reused).
    ///
    /// # Errors
    /// As [`Cholesky::factor`].
    pub fn refactor(&mut self, a: &CsMat<f64>) -> Result<(), OperatorError> {
        let t0 = Instant::now();
        let mat = view(a)?;
        if a.rows() != self.stats.n {
            return Err(OperatorError::NotSquareCsc {
                rows: a.rows(),
                cols: a.cols(),
            });
        }
        let len = self.symbolic.len_val();
        self.values.clear();
        self.values
            .try_reserve_exact(len)
            .map_err(|_| OperatorError::OutOfMemory {
                what: "the Cholesky factor",
            })?;
        self.values.resize(len, 0.0);
        let scratch = self
            .symbolic
            .factorize_numeric_llt_scratch::<f64>(self.par, Default::default());
        let mut mem = MemBuffer::try_new(scratch).map_err(|_| OperatorError::OutOfMemory {
            what: "the workspace",
        })?;
        self.symbolic
            .factorize_numeric_llt::<f64>(
                &mut self.values,
                mat,
                Side::Upper,
                Default::default(),
                self.par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| {
                let faer::linalg::solvers::LltError::NonPositivePivot { index } = e;
                OperatorError::NotPositiveDefinite { pivot: index }
            })?;
        self.stats.factor_ms = t0.elapsed().as_secs_f64() * 1e3;
        Ok(())
    }

    /// The fill-reducing permutation of the factorization: `perm[k]` is the row eliminated
    /// at step `k` (as [`Ordering::Custom`] takes it; the identity when there is none).
    /// An ordering computed once can so be reused for related matrices (a principal
    /// submatrix keeps the order of its rows).
    pub fn permutation(&self) -> Vec<usize> {
        match self.symbolic.perm() {
            Some(p) => p.arrays().0.to_vec(),
            None => (0..self.stats.n).collect(),
        }
    }

    /// Dimension of the factored matrix.
    pub fn dim(&self) -> usize {
        self.stats.n
    }

    /// Sizes and timings of the factorization.
    pub fn stats(&self) -> &FactorStats {
        &self.stats
    }

    /// Solves `A X = B` in place for `ncols` right-hand sides stored column-major in `rhs`
    /// (`rhs.len() == dim * ncols`). Sequential (see the module docs).
    ///
    /// # Panics
    /// If `rhs.len() != self.dim() * ncols` (a caller bug, never user data).
    pub fn solve_in_place(&self, rhs: &mut [f64], ncols: usize) {
        let n = self.stats.n;
        assert_eq!(rhs.len(), n * ncols, "right-hand side has the wrong length");
        if n == 0 || ncols == 0 {
            return;
        }
        // faer's own solve visits every supernode; this one skips, in the forward pass,
        // the supernodes a right-hand side supported near the boundary never reaches
        // (harmonic extension, Schur products): 87 → 61 ms on a 1M-face square, 114 → 72
        // ms on a 1M-face cap, the same on a dense right-hand side, identical results
        inverse_gram::solve_skipping_zeros(&self.symbolic, &self.values, rhs, ncols);
    }

    /// `Rᵀ A⁻¹ R` for a sparse `R` (CSC, `dim` rows) with few non-zeros per column: one
    /// forward solve `W = G⁻¹ P R` restricted to the supernodes on the elimination-tree
    /// paths of `R`'s non-zeros (no backward solve), then `WᵀW`. With `A = L_II` and
    /// `R = L_IB` it gives the Schur complement `L_BB − Rᵀ A⁻¹ R` (CCEM Eq. 3.15) at a
    /// fraction of the cost of `k` column solves: the work is that of the supernodes the
    /// paths visit, with dense kernels on all of `R`'s columns that reach each one.
    ///
    /// Memory: `8 k²` bytes for the result, plus the rows of `W` of the supernodes still
    /// waiting for their update (`W` is never stored whole).
    ///
    /// # Errors
    /// [`OperatorError::NotSquareCsc`] if `r` is not CSC with [`Self::dim`] rows.
    ///
    /// # Examples
    /// ```
    /// use conformap_operators::Cholesky;
    /// use sprs::{CsMat, TriMat};
    /// // A = [[4, 1], [1, 3]], R = e₀: Rᵀ A⁻¹ R = (A⁻¹)₀₀ = 3 / 11
    /// let mut t = TriMat::new((2, 2));
    /// for (i, j, v) in [(0, 0, 4.0), (1, 0, 1.0), (0, 1, 1.0), (1, 1, 3.0)] {
    ///     t.add_triplet(i, j, v);
    /// }
    /// let chol = Cholesky::factor(&t.to_csc())?;
    /// let r = CsMat::new_csc((2, 1), vec![0, 1], vec![0], vec![1.0]);
    /// let g = chol.inverse_gram(&r)?;
    /// assert!((g.get(0, 0) - 3.0 / 11.0).abs() < 1e-15);
    /// # Ok::<(), conformap_operators::OperatorError>(())
    /// ```
    pub fn inverse_gram(&self, r: &CsMat<f64>) -> Result<InverseGram, OperatorError> {
        let plan = self.inverse_gram_plan(r)?;
        Ok(inverse_gram::inverse_gram(plan, r.cols(), self.par))
    }

    /// The multiply–adds [`Self::inverse_gram`] would spend on `r`, from its symbolic pass
    /// alone (which supernodes the columns of `r` reach): for choosing between forming a
    /// Schur complement and applying it through solves.
    ///
    /// # Errors
    /// As [`Self::inverse_gram`].
    pub fn inverse_gram_cost(&self, r: &CsMat<f64>) -> Result<f64, OperatorError> {
        Ok(self.inverse_gram_plan(r)?.multiply_adds())
    }

    /// The symbolic pass of [`Self::inverse_gram`] (which panels each column of `r`
    /// reaches), after checking that `r` is CSC with [`Self::dim`] rows.
    fn inverse_gram_plan(&self, r: &CsMat<f64>) -> Result<inverse_gram::Plan<'_>, OperatorError> {
        if !r.is_csc() || r.rows() != self.stats.n {
            return Err(OperatorError::NotSquareCsc {
                rows: r.rows(),
                cols: r.cols(),
            });
        }
        let perm_inv = self.perm_inv();
        Ok(inverse_gram::Plan::new(
            &self.symbolic,
            &self.values,
            &perm_inv,
            r,
        ))
    }

    /// The multiply–adds of this factor's numeric factorization, counted from its
    /// structure: per supernode of width `w` with `p` rows below it, `w³/6` (its diagonal
    /// block), `w²p/2` (the triangular solve of the rows below) and `wp²/2` (its update of
    /// the ancestors); per column of a simplicial factor with `c` entries below the
    /// diagonal, `c²/2 + c`. For comparing the work of a factorization with that of
    /// [`Self::inverse_gram`] ([`Self::inverse_gram_cost`]) in the same units.
    pub fn factor_cost(&self) -> f64 {
        inverse_gram::factor_cost(&self.symbolic, &self.values)
    }

    /// `perm_inv[i]`: the position of row `i` in the elimination order.
    fn perm_inv(&self) -> std::borrow::Cow<'_, [usize]> {
        match self.symbolic.perm() {
            Some(p) => std::borrow::Cow::Borrowed(p.arrays().1),
            None => std::borrow::Cow::Owned((0..self.stats.n).collect()),
        }
    }

    /// Solves `A z = b` for complex `b` (real and imaginary parts as two columns).
    pub fn solve_complex(&self, b: &[Complex64]) -> Vec<Complex64> {
        let n = self.stats.n;
        let mut buf = Vec::with_capacity(2 * n);
        buf.extend(b.iter().map(|z| z.re));
        buf.extend(b.iter().map(|z| z.im));
        self.solve_in_place(&mut buf, 2);
        (0..n).map(|i| Complex64::new(buf[i], buf[n + i])).collect()
    }
}

/// A dense Cholesky factorization `A = L Lᵀ` of a symmetric positive definite matrix, for
/// boundary-sized systems (e.g. a Schur complement): factor once, solve many times.
#[derive(Debug, Clone)]
pub struct DenseCholesky {
    n: usize,
    /// The factor `L`, column-major, in the lower triangle.
    l: Vec<f64>,
    par: Par,
}

impl DenseCholesky {
    /// Factors `a` (`n × n`, column-major; only its lower triangle is read) on `threads`
    /// threads (0 = all), in place: `a` becomes the factor.
    ///
    /// # Errors
    /// [`OperatorError::NotPositiveDefinite`] with the failing pivot;
    /// [`OperatorError::NotSquareCsc`] if `a.len() != n²`.
    pub fn factor(mut a: Vec<f64>, n: usize, threads: usize) -> Result<Self, OperatorError> {
        if a.len() != n * n {
            return Err(OperatorError::NotSquareCsc {
                rows: n,
                cols: a.len() / n.max(1),
            });
        }
        let par = par_for(threads);
        if n > 0 {
            let l = MatMut::from_column_major_slice_mut(&mut a, n, n);
            let params = Default::default();
            let scratch = faer::linalg::cholesky::llt::factor::cholesky_in_place_scratch::<f64>(
                n, par, params,
            );
            let mut mem = MemBuffer::try_new(scratch).map_err(|_| OperatorError::OutOfMemory {
                what: "the workspace",
            })?;
            faer::linalg::cholesky::llt::factor::cholesky_in_place(
                l,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                params,
            )
            .map_err(|e| {
                let faer::linalg::solvers::LltError::NonPositivePivot { index } = e;
                OperatorError::NotPositiveDefinite { pivot: index }
            })?;
        }
        Ok(Self { n, l: a, par })
    }

    /// First non-zero shift of [`Self::factor_shifted`], relative to the largest diagonal
    /// entry `t`: `1e-10 t`, far below the curvature of any direction that matters, so a
    /// barely indefinite Hessian keeps its Newton step.
    pub const SHIFT_FIRST: f64 = 1e-10;
    /// Largest shift [`Self::factor_shifted`] tries, relative to `t`: `1e3 t`; a matrix
    /// still not positive definite then has non-finite entries.
    pub const SHIFT_MAX: f64 = 1e3;

    /// The factorization of `A + μ I` with the smallest shift
    /// `μ ∈ {0, 1e-10 t, 1e-9 t, …, 1e3 t}` (`t` the largest diagonal entry in absolute
    /// value) that is positive definite — the Levenberg–Marquardt shift of a Newton step
    /// whose Hessian is not positive definite — and that `μ`. `a` is `n × n` symmetric
    /// (only its lower triangle is read); one thread (boundary-sized Newton systems).
    ///
    /// # Errors
    /// [`OperatorError::NotPositiveDefinite`] with the failing pivot at the largest shift
    /// (the matrix has non-finite entries); [`OperatorError::NotSquareCsc`] if
    /// `a.len() != n²`.
    ///
    /// # Examples
    /// ```
    /// use conformap_operators::DenseCholesky;
    /// // indefinite: eigenvalues 3 and −1
    /// let a = vec![1.0, 2.0, 2.0, 1.0];
    /// let (f, mu) = DenseCholesky::factor_shifted(&a, 2, 1)?;
    /// assert!(mu > 0.0 && f.dim() == 2);
    /// # Ok::<(), conformap_operators::OperatorError>(())
    /// ```
    pub fn factor_shifted(
        a: &[f64],
        n: usize,
        threads: usize,
    ) -> Result<(Self, f64), OperatorError> {
        if a.len() != n * n {
            return Err(OperatorError::NotSquareCsc {
                rows: n,
                cols: a.len() / n.max(1),
            });
        }
        let top = (0..n)
            .fold(0.0f64, |m, i| m.max(a[i * n + i].abs()))
            .max(f64::MIN_POSITIVE);
        let mut mu = 0.0;
        loop {
            let mut shifted = a.to_vec();
            for i in 0..n {
                shifted[i * n + i] += mu;
            }
            match Self::factor(shifted, n, threads) {
                Ok(f) => return Ok((f, mu)),
                Err(e) => {
                    mu = if mu == 0.0 {
                        Self::SHIFT_FIRST * top
                    } else {
                        mu * 10.0
                    };
                    if mu > Self::SHIFT_MAX * top || !mu.is_finite() {
                        return Err(e);
                    }
                }
            }
        }
    }

    /// Dimension.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Solves `A X = B` in place for `ncols` right-hand sides (column-major `n × ncols`).
    ///
    /// # Panics
    /// If `rhs.len() != dim * ncols` (a caller bug, never user data).
    pub fn solve_in_place(&self, rhs: &mut [f64], ncols: usize) {
        let n = self.n;
        assert_eq!(rhs.len(), n * ncols, "right-hand side has the wrong length");
        if n == 0 || ncols == 0 {
            return;
        }
        // the two triangular solves are memory-bound on few columns: one thread
        let par = if ncols >= 16 { self.par } else { Par::Seq };
        let l = faer::MatRef::from_column_major_slice(&self.l, n, n);
        let mut x = MatMut::from_column_major_slice_mut(rhs, n, ncols);
        faer::linalg::triangular_solve::solve_lower_triangular_in_place(l, x.rb_mut(), par);
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            l.transpose(),
            x.rb_mut(),
            par,
        );
    }
}

/// A symmetric positive definite approximation `M = P L |D| Lᵀ Pᵀ` of a dense symmetric
/// matrix `A = P L D Lᵀ Pᵀ` (Bunch–Kaufman, `D` block diagonal with 1×1 and 2×2 blocks),
/// with every eigenvalue of `D`'s blocks replaced by its absolute value, at least
/// `floor`: the modified factorization of Cheng and Higham (1998) for preconditioning
/// Newton-type steps on a non-convex function. One factorization, never fails; equals `A`
/// where `A` is positive definite enough.
#[derive(Debug, Clone)]
pub struct DenseModifiedLblt {
    n: usize,
    l: Vec<f64>,
    diag: Vec<f64>,
    subdiag: Vec<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    /// Eigenvalues of `D`'s blocks that were negative or below the floor.
    pub modified: usize,
}

impl DenseModifiedLblt {
    /// Factors `a` (`n × n`, column-major, lower triangle read) on `threads` threads
    /// (0 = all). `floor ≥ 0` is absolute.
    ///
    /// # Errors
    /// [`OperatorError::NotSquareCsc`] if `a.len() != n²`.
    pub fn factor(
        mut a: Vec<f64>,
        n: usize,
        threads: usize,
        floor: f64,
    ) -> Result<Self, OperatorError> {
        use faer::linalg::cholesky::lblt::factor as bk;
        if a.len() != n * n {
            return Err(OperatorError::NotSquareCsc {
                rows: n,
                cols: a.len() / n.max(1),
            });
        }
        let par = par_for(threads);
        let mut subdiag = vec![0.0; n];
        let mut perm = vec![0usize; n];
        let mut perm_inv = vec![0usize; n];
        if n > 0 {
            let params = Default::default();
            let scratch = bk::cholesky_in_place_scratch::<usize, f64>(n, par, params);
            let mut mem = MemBuffer::try_new(scratch).map_err(|_| OperatorError::OutOfMemory {
                what: "the workspace",
            })?;
            let m = MatMut::from_column_major_slice_mut(&mut a, n, n);
            let sub = faer::ColMut::from_slice_mut(&mut subdiag).as_diagonal_mut();
            bk::cholesky_in_place(
                m,
                sub,
                &mut perm,
                &mut perm_inv,
                par,
                MemStack::new(&mut mem),
                params,
            );
        }
        let mut diag: Vec<f64> = (0..n).map(|i| a[i * n + i]).collect();
        let mut modified = 0;
        let mut i = 0;
        while i < n {
            if i + 1 < n && subdiag[i] != 0.0 {
                let (p, b, c): (f64, f64, f64) = (diag[i], subdiag[i], diag[i + 1]);
                let phi = 0.5 * (2.0 * b).atan2(p - c);
                let (sn, cs) = phi.sin_cos();
                let l1 = p * cs * cs + 2.0 * b * cs * sn + c * sn * sn;
                let l2 = p * sn * sn - 2.0 * b * cs * sn + c * cs * cs;
                let fix = |l: f64, modified: &mut usize| {
                    if !(l > floor) {
                        *modified += 1;
                    }
                    l.abs().max(floor)
                };
                let (m1, m2) = (fix(l1, &mut modified), fix(l2, &mut modified));
                diag[i] = m1 * cs * cs + m2 * sn * sn;
                diag[i + 1] = m1 * sn * sn + m2 * cs * cs;
                subdiag[i] = (m1 - m2) * cs * sn;
                i += 2;
            } else {
                if !(diag[i] > floor) {
                    modified += 1;
                }
                diag[i] = diag[i].abs().max(floor);
                if !diag[i].is_finite() {
                    diag[i] = 1.0;
                }
                i += 1;
            }
        }
        Ok(Self {
            n,
            l: a,
            diag,
            subdiag,
            perm,
            perm_inv,
            modified,
        })
    }

    /// Solves `M x = b` in place for one right-hand side.
    ///
    /// # Panics
    /// If `x.len()` is not the dimension (a caller bug).
    pub fn solve_in_place(&self, x: &mut [f64]) {
        use faer::linalg::cholesky::lblt::solve as bks;
        let n = self.n;
        assert_eq!(x.len(), n, "right-hand side has the wrong length");
        if n == 0 {
            return;
        }
        let scratch = bks::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq);
        let mut mem = MemBuffer::new(scratch);
        bks::solve_in_place_with_conj(
            faer::MatRef::from_column_major_slice(&self.l, n, n),
            faer::ColRef::from_slice(&self.diag).as_diagonal(),
            faer::ColRef::from_slice(&self.subdiag).as_diagonal(),
            Conj::No,
            faer::perm::PermRef::new_checked(&self.perm, &self.perm_inv, n),
            MatMut::from_column_major_slice_mut(x, n, 1),
            Par::Seq,
            MemStack::new(&mut mem),
        );
    }
}

/// Solves `A X = B` in place for a dense symmetric positive definite `A` (`n × n`,
/// column-major; only its lower triangle is read, and it is overwritten by its Cholesky
/// factor) and `ncols` right-hand sides in `rhs` (column-major, `n × ncols`), on
/// `threads` threads (0 = all). For boundary-sized systems, e.g. a Schur complement.
///
/// # Errors
/// [`OperatorError::NotPositiveDefinite`] with the failing pivot;
/// [`OperatorError::NotSquareCsc`] if the slices do not have the sizes given.
///
/// # Examples
/// ```
/// let mut a = vec![4.0, 1.0, 1.0, 3.0];
/// let mut b = vec![1.0, 2.0];
/// conformap_operators::solve_dense_spd(&mut a, 2, &mut b, 1, 1)?;
/// assert!((4.0 * b[0] + b[1] - 1.0).abs() < 1e-14 && (b[0] + 3.0 * b[1] - 2.0).abs() < 1e-14);
/// # Ok::<(), conformap_operators::OperatorError>(())
/// ```
pub fn solve_dense_spd(
    a: &mut [f64],
    n: usize,
    rhs: &mut [f64],
    ncols: usize,
    threads: usize,
) -> Result<(), OperatorError> {
    if a.len() != n * n || rhs.len() != n * ncols {
        return Err(OperatorError::NotSquareCsc {
            rows: n,
            cols: a.len() / n.max(1),
        });
    }
    let chol = DenseCholesky::factor(a.to_vec(), n, threads)?;
    chol.solve_in_place(rhs, ncols);
    a.copy_from_slice(&chol.l);
    Ok(())
}

/// Relative residual `‖A x − b‖∞ / max(‖b‖∞, tiny)` of a complex solve.
pub fn relative_residual(a: &CsMat<f64>, x: &[Complex64], b: &[Complex64]) -> f64 {
    let ax = crate::laplacian::mul_complex(a, x);
    let num = ax
        .iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    let den = b
        .iter()
        .map(|q| q.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    num / den
}
