//! Disk conformal maps for conformap: Angenent initial map, harmonic extension, CEM and
//! CCEM.
//!
//! Depends on `conformap-mesh` (validated meshes) and `conformap-operators` (Laplacian,
//! factorizations); never touches files, spheres or 1-forms. Entry point:
//! [`DiskProblem::new`] checks the topology, assembles and factors once; the methods
//! ([`harmonic_arc_length`], [`cem`]) then reuse that factorization.
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

mod cem;
mod error;
mod harmonic;
mod initial;
mod problem;
mod report;

#[doc(hidden)]
pub mod doc_support;

pub use cem::{cem, interior_residual, CemOptions, CEM_MAX_ITER, CEM_TOL};
pub use error::DiskError;
pub use harmonic::harmonic_arc_length;
pub use initial::{
    angenent_boundary, angenent_rhs, arc_length_boundary, centralize_normalize, centre_face,
    InitialBoundary,
};
pub use problem::{polygon_area, polygon_area_of, DiskProblem};
pub use report::{DiskMap, SolverReport, Timings};
