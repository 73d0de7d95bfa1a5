//! The one error type of the disk solvers (the disk map and the disk with circular holes).

use conformap_mesh::{MeshError, Topology};
use conformap_operators::OperatorError;

/// Why a disk map (or a disk with circular holes) could not be computed.
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
    /// An option is out of range. Fix: see the option's documentation for its range.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What is required.
        reason: &'static str,
    },
    /// CCEM's starting boundary (the CEM map's, by default) does not wind once
    /// counter-clockwise around the circle, even after its out-of-order gaps are repaired,
    /// so there is no bijective boundary to start from. Fix: start from the arc-length
    /// boundary (`CcemStart::ArcLength`), which is always in order.
    #[error("the starting boundary of CCEM does not wind once around the circle")]
    InvalidStart,
    /// CCEM's map would fold: faces of the harmonic extension of its boundary have
    /// non-positive area. With gaps at the floor, the conformal map of this mesh crowds
    /// boundary vertices (thin limbs, long corridors) closer than f64 resolves even at
    /// the highest floor tried; with none, the mesh's negative cotangent weights fold the
    /// harmonic interior map. Fix: cut the long thin parts off (or map them separately), or
    /// remesh to a Delaunay triangulation; `--method cem` returns CEM's map, folds included.
    #[error(
        "the disk map would fold {flipped_faces} faces (first: face {face}) with {held_gaps} \
         boundary gaps at the floor {floor:.0e} rad: the conformal map of this mesh crowds \
         boundary vertices closer than f64 resolves, or its negative cotangent weights fold \
         the interior"
    )]
    Folded {
        /// Faces with non-positive image area.
        flipped_faces: usize,
        /// The first such face (0-based).
        face: usize,
        /// Boundary gaps held at the floor.
        held_gaps: usize,
        /// The last floor tried, radians.
        floor: f64,
    },
    /// The mesh is not a connected genus-0 surface with boundary, so no disk with circular
    /// holes is conformally equivalent to it. Fix: closed genus-0 meshes map to the sphere;
    /// higher-genus ones need cutting (or the global 1-form map); split several components.
    #[error(
        "a disk with circular holes needs a connected genus-0 surface with at least one \
         boundary loop, but the mesh is {found}"
    )]
    NotGenusZero {
        /// What the mesh is.
        found: Topology,
    },
    /// The requested outer loop does not exist. Fix: loops are numbered from 0 in the order
    /// of `conformap info` (by smallest vertex).
    #[error("outer loop {index} does not exist: the mesh has {loops} boundary loops")]
    OuterLoopOutOfRange {
        /// The requested loop.
        index: usize,
        /// Number of loops.
        loops: usize,
    },
    /// Filling the holes of the input surface with centroid fans (the first step of the
    /// disk with circular holes) gave an invalid mesh (a fan triangle is degenerate: a flat
    /// loop whose centroid lies on one of its edges).
    #[error("filling the holes failed: {0}")]
    Fill(#[from] MeshError),
    /// No point inside a hole's current image was found to invert about (Koebe iteration):
    /// the loop's image is not a simple polygon (the previous map folded it).
    #[error(
        "the image of boundary loop {loop_index} is not a simple closed curve (sweep {sweep}); \
         the previous map folded it"
    )]
    LoopNotSimple {
        /// The loop.
        loop_index: usize,
        /// The sweep (0 = the first disk map).
        sweep: usize,
    },
    /// A boundary target names a vertex that does not exist.
    #[error(
        "vertex {vertex} does not exist (the mesh has {vertices} vertices); hint: vertices \
         are 0-based"
    )]
    VertexOutOfRange {
        /// The vertex as given.
        vertex: u32,
        /// Number of vertices of the mesh.
        vertices: usize,
    },
    /// A boundary target names an interior vertex (or, with several loops, a vertex off the
    /// outer loop).
    #[error(
        "vertex {vertex} is not on the boundary loop being flattened; hint: list vertices \
         of the (longest) boundary loop, 0-based (`conformap info` lists the loops)"
    )]
    NotOnBoundary {
        /// The vertex (0-based).
        vertex: u32,
    },
    /// A `scale` or `angles` target leaves out a boundary vertex.
    #[error(
        "boundary vertex {vertex} has no value; hint: `scale` and `angles` need one line \
         per vertex of the boundary loop"
    )]
    MissingBoundaryValue {
        /// The first boundary vertex without a value (0-based).
        vertex: u32,
    },
    /// A boundary value is NaN or infinite.
    #[error("the value of boundary vertex {vertex} is not finite; hint: give a finite number")]
    NonFiniteBoundaryValue {
        /// The vertex (0-based).
        vertex: u32,
    },
    /// The corners of a rectangle or polygon are unusable.
    #[error(
        "bad corners: {reason}; hint: give distinct boundary vertices in the order of the \
         boundary loop (the surface on the left)"
    )]
    BadCorners {
        /// What is wrong.
        reason: String,
    },
    /// The exterior angles of an `angles` or `polygon` target do not sum to 360°.
    #[error(
        "the exterior angles sum to {sum_deg:.6}°, but a closed boundary loop turns by \
         360°; hint: convex corners count positive, reflex ones negative (a rectangle: \
         four times 90)"
    )]
    TurningSum {
        /// The sum as given, degrees.
        sum_deg: f64,
    },
    /// A boundary file has a malformed line.
    #[error(
        "{file}:{line}: {reason}; hint: each line is `<0-based vertex> <value>` (angles in \
         degrees); `#` starts a comment line"
    )]
    BoundaryFile {
        /// The file as named by the caller.
        file: String,
        /// The 1-based line.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// An unknown `--boundary` spelling.
    #[error(
        "unknown boundary {spelling:?}; hint: free, circle, rectangle, scale:FILE, \
         angles:FILE or polygon:FILE"
    )]
    UnknownBoundary {
        /// The spelling as given.
        spelling: String,
    },
}
