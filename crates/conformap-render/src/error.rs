//! The one error type of this crate.

/// Why a picture cannot be made. Every variant names what to fix.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The map does not have one value per vertex (or per face, for per-corner maps). Fix:
    /// pass the map of this mesh, in its vertex (face) order.
    #[error(
        "the map has {found} {what} but the mesh has {expected}; give one per {per}, \
         in the mesh's order"
    )]
    LengthMismatch {
        /// What was counted ("values", "corner triples").
        what: &'static str,
        /// What one value belongs to ("vertex", "face").
        per: &'static str,
        /// How many the mesh needs.
        expected: usize,
        /// How many were given.
        found: usize,
    },
    /// A map value is NaN or infinite. Fix: recompute or repair the map there.
    #[error("the map value at {what} {index} is not finite")]
    NonFiniteValue {
        /// "vertex" or "face".
        what: &'static str,
        /// 0-based index of the first bad vertex or face.
        index: usize,
    },
    /// A sphere map point is far from the unit sphere (or zero). Fix: pass unit vectors
    /// (a sphere map's points), or use a planar map type for planar maps.
    #[error(
        "the sphere map point of vertex {vertex} has length {length}; \
         sphere maps must be unit vectors"
    )]
    NotOnSphere {
        /// 0-based vertex (or corner index `3·face + k` for per-corner input).
        vertex: usize,
        /// Its Euclidean length.
        length: f64,
    },
    /// An option is out of range. Fix: as the reason says.
    #[error("invalid render option `{name}`: {reason}")]
    InvalidOption {
        /// The options field.
        name: &'static str,
        /// What is wrong and what is allowed.
        reason: &'static str,
    },
    /// The map has no extent to fit into a picture (every vertex at one point). Fix: check
    /// the map; a collapsed map cannot be drawn.
    #[error("the map is collapsed to a point; nothing to draw")]
    Collapsed,
    /// Encoding or writing the PNG failed.
    #[error("writing the PNG failed: {0}")]
    Png(#[from] png::EncodingError),
    /// Writing a file failed.
    #[error("writing {path} failed: {source}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}
