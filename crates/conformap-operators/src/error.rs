//! The one error type of the operators crate.

/// Errors of the operators crate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OperatorError {
    /// The matrix is not positive definite: the Cholesky pivot at this (permuted) column was
    /// not positive. For a cotangent `L_II` this means the mesh has strongly negative
    /// cotangent weights (badly non-Delaunay) or an interior part cut off from the boundary.
    #[error("the matrix is not positive definite (Cholesky pivot {pivot} is not positive)")]
    NotPositiveDefinite {
        /// The failing pivot (in the permuted order).
        pivot: usize,
    },
    /// A matrix given to the solver is not square CSC.
    #[error("expected a square CSC matrix, got {rows} × {cols}")]
    NotSquareCsc {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
    },
    /// A matrix given to [`crate::SymbolicAnalysis::factor`] does not have the pattern analysed.
    #[error("the matrix does not have the sparsity pattern that was analysed")]
    PatternMismatch,
    /// An ordering name that [`crate::Ordering`]'s `FromStr` does not know. Fix: one of
    /// [`crate::Ordering::NAMES`].
    #[error("unknown ordering {name:?}; hint: use one of auto, amd, nd")]
    UnknownOrdering {
        /// The name given.
        name: String,
    },
    /// A custom ordering is not a permutation of `0..n`.
    #[error("the custom ordering is not a permutation of 0..{n}")]
    BadPermutation {
        /// Dimension.
        n: usize,
    },
    /// The intrinsic Delaunay flip loop ran out of its flip budget
    /// ([`crate::IntrinsicOptions::max_flips_per_edge`] per interior edge): a numerical cycle of
    /// flips. Fix: raise the budget or the Delaunay tolerance, or use the plain cotangent
    /// Laplacian.
    #[error("intrinsic Delaunay flips did not finish: {flips} flips reached the limit {limit}")]
    FlipLimit {
        /// Flips performed.
        flips: usize,
        /// The budget.
        limit: usize,
    },
    /// An option is out of range. Fix: see the option's documentation for its range.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What is required.
        reason: &'static str,
    },
    /// Memory for a factorization could not be allocated. Fix: a smaller mesh, more memory,
    /// or nested-dissection ordering (less fill on large meshes).
    #[error("out of memory for {what}")]
    OutOfMemory {
        /// What was being allocated (`"the Cholesky factor"`, `"the workspace"`).
        what: &'static str,
    },
    /// The matrix has more non-zeros (or its factor more fill) than the backend's index type
    /// can address. Fix: split the mesh.
    #[error("the matrix is too large for the sparse backend's indices ({stage})")]
    IndexOverflow {
        /// Which step overflowed.
        stage: &'static str,
    },
    /// The sparse LU found no pivot: the matrix is structurally singular (a column or row
    /// without entries the elimination can use).
    #[error("the matrix is structurally singular (no LU pivot at step {index})")]
    StructurallySingular {
        /// The elimination step without a pivot.
        index: usize,
    },
}

impl OperatorError {
    /// The error for a failure of the `faer` backend while doing `stage`.
    pub(crate) fn from_faer(e: faer::sparse::FaerError, stage: &'static str) -> Self {
        match e {
            faer::sparse::FaerError::IndexOverflow => Self::IndexOverflow { stage },
            _ => Self::OutOfMemory { what: stage },
        }
    }
}
