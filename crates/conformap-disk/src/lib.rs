//! Disk conformal maps for conformap: Angenent initial map, harmonic extension, CEM and
//! CCEM.
//!
//! Depends on `conformap-mesh` (validated meshes) and `conformap-operators` (Laplacian,
//! factorizations); never touches files, spheres or 1-forms. Entry point:
//! [`DiskProblem::new`] checks the topology, assembles and factors once; the methods
//! ([`harmonic_arc_length`], [`cem`], [`ccem`]) then reuse that factorization.
//! [`compute_disk_map`] does both for a [`DiskMethod`]; the default, CCEM with BFGS
//! ([`DiskMethod::CcemQn`]), gives the most conformal map (lowest `E_C`) of the four.
//! [`koebe`] maps a genus-0 mesh with several boundary loops onto the unit disk with
//! circular holes (CEM §3.3, Algorithm 2: Koebe's iteration, then the circle-domain map of
//! least conformal energy).
//!
//! # Example
//! ```
//! use conformap_disk::{cem, CemOptions, DiskProblem};
//! use conformap_mesh::TriMesh;
//! // a bumpy hexagonal patch: a centre vertex and two rings
//! let mut pos = vec![[0.0, 0.0, 0.3]];
//! for r in 1..=2 {
//!     for k in 0..6 * r {
//!         let t = k as f64 * std::f64::consts::TAU / (6 * r) as f64;
//!         pos.push([r as f64 * t.cos(), r as f64 * t.sin(), 0.1 * (3.0 * t).sin()]);
//!     }
//! }
//! # let faces = conformap_disk::doc_support::two_ring_faces();
//! let mesh = TriMesh::try_new(pos, faces)?;
//! let mut problem = DiskProblem::new(&mesh)?;
//! let out = cem(&mut problem, &CemOptions::DEFAULT)?;
//! // boundary on the unit circle, energy never above the initial map's
//! for &v in &mesh.boundary_loops()[0] {
//!     assert!((out.map[v as usize].norm() - 1.0).abs() < 1e-12);
//! }
//! let h = &out.report.energy_history;
//! assert!(h[out.report.best_iteration] <= h[0]);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod angles;
mod ccem;
mod ccem_options;
#[cfg(test)]
mod ccem_tests;
mod cem;
mod circle_fit;
mod circle_newton;
mod circle_polish;
mod descent;
mod energy;
mod error;
mod harmonic;
mod hessian;
mod initial;
mod koebe;
mod koebe_options;
mod koebe_polish;
mod koebe_report;
mod koebe_step;
mod laplacian_choice;
mod line_search;
mod memory;
mod method;
mod mobius_align;
mod problem;
mod qn;
mod report;
mod schur;
#[cfg(test)]
mod speed_tests;
mod unfold;

#[doc(hidden)]
pub mod doc_support;

pub use ccem::{ccem, GAP_FLOOR_MAX, GAP_FLOOR_STEP};
pub use ccem_options::{
    CcemOptions, CcemStart, CcemVariant, CCEM_BANDED_HESSIAN_MIN_NB, CCEM_GAMMA1, CCEM_GAMMA2,
    CCEM_MAX_ITER, CCEM_MAX_LINE_EVALS, CCEM_MIN_GAP, CCEM_QN_MEMORY, CCEM_RHO, CCEM_TOL,
};
pub use cem::{cem, interior_residual, CemOptions, CEM_MAX_ITER, CEM_TOL};
pub use error::DiskError;
pub use harmonic::harmonic_arc_length;
pub use initial::{
    angenent_boundary, angenent_rhs, arc_length_boundary, centralize_normalize, centre_face,
    InitialBoundary,
};
pub use koebe::koebe;
pub use koebe_options::{
    KoebeError, KoebeOptions, KOEBE_MAX_SWEEPS, KOEBE_NEWTON_MAX_ITER, KOEBE_NEWTON_STEP_TOL,
    KOEBE_TOL, KOEBE_TOL_WITHOUT_POLISH,
};
pub use koebe_polish::POLISH_MAX_ITER;
pub use koebe_report::{
    CircleDomainMap, KoebeReport, KoebeStepRecord, KoebeTimings, LoopCircleFit, PolishReport,
};
pub use laplacian_choice::{
    FactorOrdering, GuardedExtension, InteriorOperator, LaplacianKind, ProblemOptions,
    NESTED_DISSECTION_MIN_INTERIOR,
};
pub use memory::{koebe_peak_bytes, CEM_EXTRA_BYTES_PER_VERTEX};
pub use method::{compute_disk_map, run_disk_method, DiskMethod, DiskOptions};
pub use problem::{polygon_area, polygon_area_of, DiskProblem};
pub use report::{
    BoundaryReport, CcemStages, DiskMap, LineSearchReport, SchurReport, SolverReport, StepRecord,
    Timings,
};
pub use schur::{SchurMode, DENSE_SCHUR_MAX_BYTES, EXPECTED_SCHUR_PRODUCTS};
pub use unfold::{unfold_disk_map, Unfolded, UNFOLD_MIN_GAP};
