//! Validated triangle meshes for conformap: connectivity, boundary loops, topology and
//! mesh surgery.
//!
//! Depends on nothing but `thiserror` and `rayon` (validation runs its independent passes on
//! both cores); never touches files or matrices.
//! [`TriMesh::try_new`] is the single gate every mesh passes: once it returns `Ok`, the
//! mesh has finite coordinates, in-range indices, no degenerate, duplicate or unreferenced
//! elements, manifold edges and vertices and a consistent orientation, so downstream crates
//! need not check again. [`repair`] fixes the defects with a safe, standard fix (duplicate
//! faces, several components, inconsistent orientation, unreferenced vertices) on request,
//! before validation, and logs what it changed.
//!
//! # Example
//! ```
//! use conformap_mesh::{Topology, TriMesh};
//! // a square made of two triangles
//! let mesh = TriMesh::try_new(
//!     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
//!     vec![[0, 1, 2], [0, 2, 3]],
//! )?;
//! assert_eq!(mesh.topology(), Topology::Disk);
//! assert_eq!(mesh.boundary_loops()[0], vec![0, 1, 2, 3]); // counter-clockwise
//! # Ok::<(), conformap_mesh::MeshError>(())
//! ```

mod error;
mod holes;
mod repair;
mod slit;
mod surgery;
mod topology;
mod trimesh;

pub use error::MeshError;
pub use holes::{centroid_fan_faces, fill_all_holes_except};
pub use repair::{repair, RepairLog, RepairOptions, Repaired, DROPPED};
pub use slit::{cut_slits, SlitMesh, SlitPlanner};
pub use surgery::{fill_holes, FilledMesh};
#[doc(hidden)]
pub use topology::doc_torus;
pub use topology::{
    cut_graph, cut_mesh, cut_mesh_along, homology_basis, CutMesh, EdgeIndex, Generator,
    HomologyBasis,
};
pub use trimesh::{
    bbox_diagonal, bounding_box, triangle_area, Adjacency, Topology, TriMesh, ValidationOptions,
    WellConditioned, DEGENERATE_AREA_REL, NO_HALFEDGE,
};
