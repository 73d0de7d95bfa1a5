//! The one error type of the disk solvers.

use conformap_mesh::Topology;
use conformap_operators::OperatorError;

/// Why a disk map could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiskError {
    /// The mesh is not a topological disk. Fix: a disk map needs one connected, genus-0
    /// surface with exactly one boundary loop; use the sphere map for closed genus-0 meshes,
    /// cut higher-genus surfaces open, or (several loops) the disk-with-holes map.
    #[error("a disk map needs a disk (genus 0, one boundary loop), but the mesh is {found}")]
    WrongTopology {
        /// What the mesh is.
        found: Topology,
    },
    /// The mesh has no interior vertex, so there is nothing to solve for.
    #[error("the mesh has no interior vertex (every vertex lies on the boundary)")]
    NoInteriorVertex,
    /// A sparse factorization failed (see the inner error).
    #[error("linear algebra failed: {0}")]
    Operator(#[from] OperatorError),
    /// The computation produced a non-finite value at this vertex: the cotangent weights are
    /// too badly conditioned for f64 (extremely thin triangles).
    #[error("the map became non-finite at vertex {vertex} ({stage})")]
    NonFinite {
        /// 0-based vertex index.
        vertex: usize,
        /// Which step produced it.
        stage: &'static str,
    },
    /// The boundary collapsed: after normalization some boundary vertex sits at the centre
    /// (the iteration cannot place it on the circle).
    #[error("boundary vertex {vertex} collapsed to the centre of the disk ({stage})")]
    BoundaryCollapsed {
        /// 0-based vertex index.
        vertex: usize,
        /// Which step produced it.
        stage: &'static str,
    },
}
