//! The one error type of conformap-morph.

use conformap_disk::DiskError;
use conformap_operators::OperatorError;
use conformap_sphere::SphereError;

/// Why a morph could not be computed. Surfaces are numbered from 0 in the order given
/// (surface 0 is S1, the one whose connectivity every frame has).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MorphError {
    /// Fewer than two surfaces. Fix: give at least two surfaces, each with its landmarks.
    #[error("a morph needs at least two surfaces, got {found}")]
    TooFewSurfaces {
        /// Surfaces given.
        found: usize,
    },
    /// A line of a landmark file is not `<0-based vertex index> <name>`. Fix: correct that
    /// line (blank lines and lines starting with `#` are skipped).
    #[error("landmarks line {line}: {reason}")]
    LandmarkSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// A landmark file has fewer than the two landmarks the normalization needs (the first
    /// is sent to the centre, the second fixes the rotation). Fix: add landmarks.
    #[error("{found} landmark(s) given, at least 2 are needed (centre and rotation)")]
    TooFewLandmarks {
        /// Landmarks given.
        found: usize,
    },
    /// A landmark names a vertex the surface does not have. Fix: the indices are 0-based
    /// vertex numbers of that surface's mesh.
    #[error("surface {surface}: landmark {name:?} is vertex {vertex}, but the mesh has {vertices} vertices (indices are 0-based)")]
    LandmarkOutOfRange {
        /// 0-based surface.
        surface: usize,
        /// The landmark's name.
        name: String,
        /// The index given.
        vertex: u64,
        /// Vertices of the mesh.
        vertices: usize,
    },
    /// Two landmarks of one surface are the same vertex, or share a name. Fix: every
    /// landmark needs its own vertex and its own name.
    #[error("surface {surface}: landmarks {first} and {second} ({what}) repeat each other")]
    RepeatedLandmark {
        /// 0-based surface.
        surface: usize,
        /// 0-based position of the first of the two.
        first: usize,
        /// 0-based position of the second.
        second: usize,
        /// `"same vertex"` or `"same name"`.
        what: &'static str,
    },
    /// The landmark lists of two surfaces differ in length or in a name. Fix: every surface
    /// needs the same landmark names in the same order.
    #[error("surface {surface}: landmark {index} is {found:?}, but surface 0 has {expected:?} there (same names in the same order needed)")]
    LandmarkMismatch {
        /// 0-based surface.
        surface: usize,
        /// 0-based landmark position.
        index: usize,
        /// Surface 0's name there (`<none>` past its end).
        expected: String,
        /// This surface's name there (`<none>` past its end).
        found: String,
    },
    /// The first or second landmark lies on the boundary: the normalization sends the first
    /// to the centre of the disk and turns the second onto the positive real axis, which
    /// needs both inside. Fix: put an interior vertex (e.g. the nose tip) first.
    #[error("surface {surface}: landmark {index} (vertex {vertex}) maps to |z| = {radius}, it must be an interior vertex for the normalization")]
    LandmarkOnBoundary {
        /// 0-based surface.
        surface: usize,
        /// 0-based landmark position (0 or 1).
        index: usize,
        /// The vertex.
        vertex: u32,
        /// `|z|` of its disk map value.
        radius: f64,
    },
    /// The first or second landmark is an interior vertex of the mesh, but the surface's
    /// disk map puts it within [`crate::NORMALIZE_BOUNDARY_TOL`] of the circle (a long or
    /// narrow part of the boundary crowds vertices against it, as the maze's corridors do),
    /// where the normalization cannot send it to the centre in f64. Fix: choose landmarks
    /// nearer the middle of the surface.
    #[error("surface {surface}: landmark {index} (vertex {vertex}) is an interior vertex, but the disk map puts it at |z| = {radius}, too close to the circle for the normalization to send it to the centre (the surface's boundary crowds it there)")]
    LandmarkNearCircle {
        /// 0-based surface.
        surface: usize,
        /// 0-based landmark position (0 or 1).
        index: usize,
        /// The vertex.
        vertex: u32,
        /// `|z|` of its disk map value.
        radius: f64,
    },
    /// The disk map of a surface failed (e.g. it is not a disk): see the inner error.
    #[error("surface {surface}: disk map failed: {source}")]
    Disk {
        /// 0-based surface.
        surface: usize,
        /// The disk map's error.
        source: DiskError,
    },
    /// A Möbius transform failed (see the inner error).
    #[error("surface {surface}: Möbius normalization failed: {source}")]
    Mobius {
        /// 0-based surface.
        surface: usize,
        /// The Möbius code's error.
        source: SphereError,
    },
    /// A factorization or solve of the registration failed (see the inner error).
    #[error("surface {surface}: registration solve failed: {source}")]
    Operator {
        /// 0-based surface.
        surface: usize,
        /// The operator's error.
        source: OperatorError,
    },
    /// The registration produced a non-finite value: the landmark system is singular (two
    /// landmarks at the same place) or the weights are badly conditioned.
    #[error("surface {surface}: the registration became non-finite at vertex {vertex}")]
    NonFinite {
        /// 0-based surface.
        surface: usize,
        /// 0-based vertex of that surface.
        vertex: usize,
    },
    /// An option is out of range. Fix: see the option's documentation.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What is required.
        reason: String,
    },
}
