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
mod error;
mod geometry;
mod intrinsic;
mod laplacian;
mod lu;
mod mean_value;
pub mod memory;
pub mod primitives;
mod quality;
mod summary;

pub use cholesky::{
    amd_permutation, relative_residual, solve_dense_spd, Cholesky, CholeskyOptions, DenseCholesky,
    DenseModifiedLblt, FactorStats, InverseGram, Ordering, SymbolicAnalysis,
};
pub use circle::{circle_residual, fit_circle, Circle, LoopCircle, FIT_REFINE_STEPS};
pub use error::OperatorError;
pub use geometry::{
    corner_angles, corner_cotangents, face_areas, face_points, surface_area, triangle_angles,
    triangle_cotangents,
};
pub use intrinsic::{
    intrinsic_delaunay_laplacian, intrinsic_delaunay_laplacian_with, IntrinsicOptions,
    IntrinsicStats, IntrinsicTriangulation, INTRINSIC_DELAUNAY_TOL, INTRINSIC_MAX_FLIPS_PER_EDGE,
};
pub use laplacian::{
    cotan_laplacian, cotan_laplacian_part, interior_pattern, mul_complex, quadratic_form,
    LaplacianBlocks, Partition,
};
pub use lu::LuSolver;
pub use mean_value::mean_value_matrix;
pub use memory::{available_memory, peak_rss_bytes, PeakMemory};
pub use primitives::{planar, vec3};
pub use quality::{mesh_quality, MeshQuality, FOLD_NORMAL_COS};
pub use summary::SolverSummary;
