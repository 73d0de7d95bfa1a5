//! Disk conformal maps for conformap: Angenent initial map, harmonic extension, CEM and
//! CCEM, and boundary first flattening.
//!
//! Depends on `conformap-mesh` (validated meshes), `conformap-operators` (Laplacian,
//! factorizations) and `conformap-metrics` (the flattening's report); never touches files,
//! spheres or 1-forms. Entry point:
//! [`DiskProblem::new`] checks the topology, assembles and factors once; the methods
//! ([`harmonic_arc_length`], [`cem`], [`ccem`]) then reuse that factorization.
//! [`compute_disk_map`] does both for a [`DiskMethod`]; the default, CCEM with BFGS
//! ([`DiskMethod::CcemQn`]), gives the most conformal map (lowest `E_C`) of the four.
//! [`koebe`] maps a genus-0 mesh with several boundary loops onto the unit disk with
//! circular holes (CEM §3.3, Algorithm 2: Koebe's iteration, then the circle-domain map of
//! least conformal energy). [`flatten`] is boundary first flattening (Sawhney & Crane 2017):
//! a free boundary that keeps the boundary's lengths, or a target boundary (given scale
//! factors or angles, a circle, a rectangle, a polygon), on the same factorizations.
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
mod cem;
mod error;
mod flatten;
mod harmonic;
pub mod initial;
mod koebe;
mod laplacian_choice;
mod memory;
mod method;
mod options;
mod problem;
mod report;
mod summary;
mod unfold;

#[doc(hidden)]
pub mod doc_support;

pub use ccem::{ccem, CcemOptions, CcemStart, CcemVariant, SchurMode};
pub use cem::{cem, interior_residual, CemOptions};
pub use error::DiskError;
pub use flatten::{
    flatten, flatten_peak_bytes, parse_boundary_values, BoundarySpec, FlattenBoundary,
    FlattenInterior, FlattenOptions, FlattenReport, FlattenTimings, Flattening, AXIS_SNAP_RAD,
    CLEAR_CORNER_RAD, CORNER_SEPARATION, TURNING_SUM_TOL,
};
pub use harmonic::harmonic_arc_length;
pub use koebe::{
    koebe, CircleDomainMap, KoebeOptions, KoebeReport, KoebeStepRecord, KoebeTimings, PolishReport,
};
pub use laplacian_choice::{GuardedExtension, InteriorOperator, LaplacianKind, ProblemOptions};
pub use memory::{koebe_peak_bytes, CEM_EXTRA_BYTES_PER_VERTEX};
pub use method::{compute_disk_map, run_disk_method, DiskMethod, DiskOptions};
pub use problem::{polygon_area_of, DiskProblem};
pub use report::{
    BoundaryReport, CcemReport, CcemStages, DiskMap, LineSearchReport, SchurReport, SolverReport,
    StepRecord, Timings,
};
pub use summary::FLATTEN_CLOSURE_TOL;
pub use unfold::{unfold_disk_map, Unfolded};
