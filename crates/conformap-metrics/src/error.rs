//! The one error type of this crate.

use num_complex::Complex64;

/// Largest `|f|` a map value may have: `1e100`. Far beyond any sensible planar map, and small
/// enough that squared differences, areas and energies summed over millions of faces stay
/// finite, so no report ever holds an infinity.
pub const MAP_ABS_LIMIT: f64 = 1e100;

/// Why a map cannot be judged. Every variant names what to fix.
///
/// ```
/// use conformap_metrics::{dirichlet_energy, MetricsError};
/// use num_complex::Complex64;
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2]],
/// )?;
/// let map = [Complex64::new(0.0, 0.0), Complex64::new(f64::NAN, 0.0), Complex64::new(0.0, 1.0)];
/// let err = dirichlet_energy(&mesh, &map).unwrap_err();
/// assert!(matches!(err, MetricsError::NonFiniteValue { vertex: 1, .. }));
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MetricsError {
    /// The map does not have one value per mesh vertex. Fix: pass the map of this mesh, in
    /// its vertex order (texture coordinates of a file whose vertices were split at seams
    /// must be welded back first).
    #[error(
        "the map has {map_len} values but the mesh has {vertices} vertices; \
         give one value per vertex, in the mesh's vertex order"
    )]
    LengthMismatch {
        /// Number of map values given.
        map_len: usize,
        /// Number of mesh vertices.
        vertices: usize,
    },
    /// A map value is NaN or infinite (typically a solver that diverged, or a missing texture
    /// coordinate). Fix: recompute or repair the map at that vertex.
    #[error("the map value at vertex {vertex} is not finite ({value})")]
    NonFiniteValue {
        /// 0-based vertex index (the first bad one).
        vertex: usize,
        /// The offending value.
        value: Complex64,
    },
    /// A map value exceeds [`MAP_ABS_LIMIT`] in modulus. Fix: rescale the map.
    #[error("the map value at vertex {vertex} is too large (|f| = {abs:e} > {limit:e})")]
    ValueTooLarge {
        /// 0-based vertex index (the first bad one).
        vertex: usize,
        /// `|f|` there.
        abs: f64,
        /// The limit, [`MAP_ABS_LIMIT`].
        limit: f64,
    },
    /// [`crate::MetricsOptions::outer_loop`] names a boundary loop the mesh does not have.
    /// Fix: use an index below the number of loops (`conformap info` lists them).
    #[error("outer loop {index} was requested, but the mesh has {loops} boundary loop(s)")]
    OuterLoopOutOfRange {
        /// The requested loop index.
        index: usize,
        /// Number of boundary loops of the mesh.
        loops: usize,
    },
}

/// Checks that `map` has one finite value of modulus at most [`MAP_ABS_LIMIT`] per vertex.
pub(crate) fn check_map(vertices: usize, map: &[Complex64]) -> Result<(), MetricsError> {
    if map.len() != vertices {
        return Err(MetricsError::LengthMismatch {
            map_len: map.len(),
            vertices,
        });
    }
    for (vertex, &value) in map.iter().enumerate() {
        if !value.is_finite() {
            return Err(MetricsError::NonFiniteValue { vertex, value });
        }
        let abs = value.norm();
        if abs > MAP_ABS_LIMIT {
            return Err(MetricsError::ValueTooLarge {
                vertex,
                abs,
                limit: MAP_ABS_LIMIT,
            });
        }
    }
    Ok(())
}
