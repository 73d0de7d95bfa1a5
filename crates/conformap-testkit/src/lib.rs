//! Test support for the conformap workspace: assert_near!, fixture loaders and analytic meshes
//! (never published).
//!
//! Depends only on `conformap-mesh` (every builder returns a validated
//! [`conformap_mesh::TriMesh`]); never touches the operators, solvers or file formats, so any
//! crate can take it as a dev-dependency without a cycle.
//!
//! # Contents
//! - Float assertions: [`assert_near!`] (absolute) and [`assert_rel_near!`] (relative), with
//!   the expressions, values and difference in the failure message.
//! - Fixtures: [`fixture_path`] (`<workspace>/fixtures/…`), [`shared_mesh_path`] and
//!   [`shared_mesh_or_skip`] (`../shared/meshes/…`, absent on a fresh clone),
//!   [`real_mesh_or_skip`] (either), [`read_plain_obj`] for plain `v`/`f` OBJ files (read
//!   already: [`fixture_mesh`], [`read_shared_mesh_or_skip`], [`read_real_mesh_or_skip`]), and the
//!   shared meshes' classes [`CLASS_A`] (disks) and [`CLASS_C`] (genus-0 closed).
//! - Analytic meshes built in code: [`flat_disk`], [`square_grid`], [`annulus`],
//!   [`disk_with_holes`] (flat, counter-clockwise); [`cylinder`], [`torus`], [`jittered_torus`],
//!   [`icosphere`] (outward normals); [`grid_faces`] for a grid with positions of one's own.
//! - [`XorShift64Star`], a seeded random stream for reproducible random cases.
//!
//! # Example
//! ```
//! use conformap_testkit::{assert_near, flat_disk};
//! let disk = flat_disk(10, 6);
//! assert_eq!(disk.boundary_loops().len(), 1);
//! assert_eq!(disk.euler_characteristic(), 1);
//! // the boundary lies on the unit circle
//! for &v in &disk.boundary_loops()[0] {
//!     let p = disk.positions()[v as usize];
//!     assert_near!(p[0].hypot(p[1]), 1.0, 1e-15);
//! }
//! ```

mod assert;
mod fixtures;
mod grid;
mod holes;
mod jittered;
mod planar;
mod random;
mod surfaces;

pub use assert::{check_near, check_rel_near};
pub use fixtures::{
    fixture_mesh, fixture_path, read_plain_obj, read_real_mesh_or_skip, read_shared_mesh_or_skip,
    real_mesh_or_skip, shared_mesh_or_skip, shared_mesh_path, workspace_root, FixtureError,
    CLASS_A, CLASS_C,
};
pub use grid::grid_faces;
pub use holes::{disk_with_holes, Circle};
pub use jittered::jittered_torus;
pub use planar::{annulus, flat_disk, square_grid};
pub use random::XorShift64Star;
pub use surfaces::{cylinder, icosphere, torus};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
