//! The one error type of conformap-sphere.

use conformap_mesh::{MeshError, Topology};
use conformap_operators::OperatorError;

/// Why a sphere map, double covering or Möbius optimization could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SphereError {
    /// The mesh has the wrong topology for the operation. Fix: a sphere map needs one
    /// connected closed genus-0 surface (`conformap info MESH` shows the topology); a double
    /// covering needs a disk (genus 0, one boundary loop).
    #[error("{operation} needs {expected}, but the mesh is {found}")]
    WrongTopology {
        /// What was attempted.
        operation: &'static str,
        /// What it needs.
        expected: &'static str,
        /// What the mesh is.
        found: Topology,
    },
    /// A sparse factorization failed (see the inner error): the cotangent Laplacian is too
    /// badly conditioned (extremely thin or strongly non-Delaunay triangles).
    #[error("linear algebra failed: {0}")]
    Operator(#[from] OperatorError),
    /// A mesh built by surgery (the double covering) failed validation.
    #[error("mesh surgery failed: {0}")]
    Mesh(#[from] MeshError),
    /// The computation produced a non-finite value at this vertex. Fix: the cotangent
    /// weights are too badly conditioned for f64; remesh the extremely thin triangles.
    #[error("the map became non-finite at vertex {vertex} ({stage})")]
    NonFinite {
        /// 0-based vertex index.
        vertex: usize,
        /// Which step produced it.
        stage: &'static str,
    },
    /// A map given to a metric or an optimizer has the wrong number of values.
    #[error("the map has {found} values but the mesh has {expected} vertices")]
    MapLength {
        /// Vertices of the mesh.
        expected: usize,
        /// Values given.
        found: usize,
    },
    /// A value of a given map is not finite.
    #[error("the map value of vertex {vertex} is not finite")]
    NonFiniteMap {
        /// 0-based vertex index.
        vertex: usize,
    },
    /// A given sphere map has a point off the unit sphere (by more than the tolerance). Fix:
    /// pass unit vectors (a sphere map as written by `conformap sphere --flat`).
    #[error("vertex {vertex} of the sphere map is at radius {radius}, not on the unit sphere")]
    NotOnSphere {
        /// 0-based vertex index.
        vertex: usize,
        /// Its distance from the origin.
        radius: f64,
    },
    /// A given disk map has a point outside the closed unit disk (by more than the
    /// tolerance). Fix: pass a disk map (e.g. written by `conformap disk`).
    #[error("vertex {vertex} of the disk map is at radius {radius}, outside the unit disk")]
    NotInDisk {
        /// 0-based vertex index.
        vertex: usize,
        /// Its distance from the origin.
        radius: f64,
    },
    /// The emphasized region names a face that does not exist.
    #[error("region face {face} is out of range: the mesh has {faces} faces")]
    RegionFaceOutOfRange {
        /// The index given.
        face: usize,
        /// Faces of the mesh.
        faces: usize,
    },
    /// The emphasized region is empty or covers every face, so there is nothing to trade.
    #[error("the emphasized region has {region} of {faces} faces: it must be a proper, non-empty subset")]
    DegenerateRegion {
        /// Distinct faces in the region.
        region: usize,
        /// Faces of the mesh.
        faces: usize,
    },
    /// A Möbius matrix is singular or not finite.
    #[error("the Möbius coefficients are singular or not finite (|det| = {det:e})")]
    SingularMobius {
        /// `|ad − bc|` (sphere) or `|a|² − |b|²` (disk) before normalization.
        det: f64,
    },
    /// An option is out of range. Fix: see the option's documentation for its range.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What is required.
        reason: &'static str,
    },
}
