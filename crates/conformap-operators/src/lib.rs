//! Discrete operators for conformap: cotangent Laplacian, its interior/boundary blocks,
//! areas, angles, and the sparse Cholesky facade.
//!
//! Depends on `conformap-mesh` (the validated [`conformap_mesh::TriMesh`]), `sprs` for
//! assembly and `faer` for factorization (see [`Cholesky`] for why faer and not sprs-ldl).
//! Never decides which map is computed and never touches files.
//!
//! # Example
//! ```
//! use conformap_mesh::TriMesh;
//! use conformap_operators::{cotan_laplacian, quadratic_form};
//! use num_complex::Complex64;
//! let mesh = TriMesh::try_new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     vec![[0, 1, 2], [0, 2, 3]],
//! )?;
//! let l = cotan_laplacian(&mesh);
//! // the Dirichlet energy of the identity map of a planar mesh is its area
//! let f: Vec<Complex64> = mesh.positions().iter().map(|p| Complex64::new(p[0], p[1])).collect();
//! assert!((quadratic_form(&l, &f) - 1.0).abs() < 1e-14);
//! # Ok::<(), conformap_mesh::MeshError>(())
//! ```

mod cholesky;
mod circle;
mod geometry;
mod intrinsic;
mod laplacian;
mod lu;
mod mean_value;
pub mod memory;

pub use cholesky::{
    relative_residual, solve_dense_spd, Cholesky, CholeskyOptions, DenseCholesky,
    DenseModifiedLblt, FactorStats, InverseGram, Ordering, SymbolicAnalysis,
};
pub use circle::{circle_residual, fit_circle, Circle, FIT_REFINE_STEPS};
pub use geometry::{
    corner_angles, corner_cotangents, face_areas, face_points, surface_area, triangle_angles,
    triangle_cotangents,
};
pub use intrinsic::{
    intrinsic_delaunay_laplacian, intrinsic_delaunay_laplacian_with, IntrinsicOptions,
    IntrinsicStats, IntrinsicTriangulation, INTRINSIC_DELAUNAY_TOL, INTRINSIC_MAX_FLIPS_PER_EDGE,
};
pub use laplacian::{
    cotan_laplacian, interior_pattern, mul_complex, quadratic_form, LaplacianBlocks, Partition,
};
pub use lu::LuSolver;
pub use mean_value::mean_value_matrix;
pub use memory::{available_memory, peak_rss_bytes, PeakMemory};

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
    /// A matrix given to [`SymbolicAnalysis::factor`] does not have the pattern analysed.
    #[error("the matrix does not have the sparsity pattern that was analysed")]
    PatternMismatch,
    /// A custom ordering is not a permutation of `0..n`.
    #[error("the custom ordering is not a permutation of 0..{n}")]
    BadPermutation {
        /// Dimension.
        n: usize,
    },
    /// The intrinsic Delaunay flip loop ran out of its flip budget
    /// ([`IntrinsicOptions::max_flips_per_edge`] per interior edge): a numerical cycle of
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
    /// The backend failed for another reason (e.g. out of memory).
    #[error("sparse factorization failed: {0}")]
    Factorization(String),
}
