//! The one error type of this crate.

/// Why a list of positions and triangles is not a valid [`crate::TriMesh`].
///
/// Every variant names the offending element (0-based vertex or face index) so a reader
/// can map it back to a file line, and says what the user can do about it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no vertices at all. Fix: check that the file is the mesh you meant.
    #[error("the mesh has no vertices")]
    NoVertices,
    /// The mesh has vertices but no triangles. Fix: export faces, not a point cloud.
    #[error("the mesh has {vertices} vertices but no faces")]
    NoFaces {
        /// Number of vertices that were given.
        vertices: usize,
    },
    /// More vertices than `u32` triangle indices can address.
    #[error("the mesh has {vertices} vertices, more than u32 indices can address")]
    TooManyVertices {
        /// Number of vertices that were given.
        vertices: usize,
    },
    /// A coordinate is NaN or infinite. Fix: repair or remove that vertex in the source.
    #[error("vertex {vertex} has a non-finite coordinate ({axis} = {value})")]
    NonFiniteCoordinate {
        /// 0-based vertex index.
        vertex: usize,
        /// `x`, `y` or `z`.
        axis: char,
        /// The offending value.
        value: f64,
    },
    /// A face refers to a vertex that does not exist.
    #[error("face {face} refers to vertex {index}, but there are only {vertex_count} vertices")]
    IndexOutOfRange {
        /// 0-based face index.
        face: usize,
        /// The index found in the face.
        index: u32,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A face uses the same vertex twice (a collapsed triangle).
    #[error("face {face} uses vertex {vertex} more than once (degenerate triangle)")]
    RepeatedVertexInFace {
        /// 0-based face index.
        face: usize,
        /// The repeated vertex.
        vertex: u32,
    },
    /// A face has (numerically) zero area: its three vertices are collinear or coincide.
    #[error(
        "face {face} is degenerate: area {area:.3e} is below {threshold:.3e} \
         (collinear or coincident vertices); remove it or remesh"
    )]
    ZeroAreaFace {
        /// 0-based face index.
        face: usize,
        /// The face's area.
        area: f64,
        /// The area threshold in force (relative to the squared bounding-box diagonal).
        threshold: f64,
    },
    /// Two faces use the same three vertices.
    #[error("face {face} duplicates face {first} (same three vertices); drop one of them")]
    DuplicateFace {
        /// 0-based index of the later face.
        face: usize,
        /// 0-based index of the first face with these vertices.
        first: usize,
    },
    /// A vertex is not used by any face; it would get no map value.
    #[error(
        "vertex {vertex} is not used by any face ({count} such vertices in all); \
         remove unreferenced vertices"
    )]
    UnreferencedVertex {
        /// The first unreferenced vertex.
        vertex: usize,
        /// How many vertices are unreferenced.
        count: usize,
    },
    /// An edge is shared by more than two faces.
    #[error(
        "edge ({a}, {b}) is non-manifold: it is shared by {count} faces (e.g. faces {faces:?})"
    )]
    NonManifoldEdge {
        /// One end of the edge.
        a: u32,
        /// The other end.
        b: u32,
        /// Number of faces sharing it.
        count: usize,
        /// Up to four of those faces.
        faces: Vec<usize>,
    },
    /// Two neighbouring faces traverse their common edge in the same direction.
    #[error(
        "faces {face} and {other} are inconsistently oriented across edge ({a}, {b}); \
         flip one so that neighbours agree"
    )]
    InconsistentOrientation {
        /// 0-based face index.
        face: usize,
        /// The neighbouring face with the same directed edge.
        other: usize,
        /// Edge start.
        a: u32,
        /// Edge end.
        b: u32,
    },
    /// The surface is not orientable (a Möbius strip, a Klein bottle): walking from face
    /// `other` and flipping faces to agree with their neighbours comes back to face `face`
    /// with the opposite orientation across edge `(a, b)`, so no flip of faces can fix it
    /// (found by [`crate::repair`]). Fix: cut the surface open along a seam through that
    /// edge, or remove the twisted band.
    #[error(
        "the surface is not orientable: face {face} cannot agree with face {other} across \
         edge ({a}, {b}) whichever faces are flipped (a Möbius-like twist); cut the surface \
         open along a seam through that edge"
    )]
    NonOrientable {
        /// 0-based input face where the walk found the conflict.
        face: usize,
        /// The neighbouring 0-based input face it conflicts with.
        other: usize,
        /// One end of the shared edge (input vertex).
        a: u32,
        /// The other end.
        b: u32,
    },
    /// The faces around a vertex form several fans (a "bowtie" vertex).
    #[error(
        "vertex {vertex} is non-manifold: its {faces} faces form more than one fan (bowtie); \
         split the vertex or remove one fan"
    )]
    NonManifoldVertex {
        /// 0-based vertex index.
        vertex: usize,
        /// Number of faces around the vertex.
        faces: usize,
    },
    /// A topology computation (homology generators, cut graph) needs one connected closed
    /// surface. Fix: close the boundary loops (or take the double covering of a surface with
    /// boundary) and keep a single component.
    #[error(
        "a homology basis needs one connected closed surface, but the mesh has {components} \
         component(s) and {boundaries} boundary loop(s)"
    )]
    NotClosedSurface {
        /// Connected components.
        components: usize,
        /// Boundary loops.
        boundaries: usize,
    },
    /// A slit (a path of vertices to cut along) is not usable: fewer than two edges,
    /// consecutive vertices not joined by an edge, a repeated vertex, a vertex on or next to
    /// the boundary or another slit, or an edge between two non-consecutive slit vertices (a
    /// chord: both its ends would become boundary vertices). Fix: choose another centre or
    /// a shorter slit ([`crate::SlitPlanner::propose`] builds valid ones).
    #[error("slit {slit} is not usable at vertex {vertex}: {reason}")]
    InvalidSlit {
        /// Index of the slit in the list given.
        slit: usize,
        /// The offending vertex.
        vertex: u32,
        /// What is wrong.
        reason: &'static str,
    },
}
