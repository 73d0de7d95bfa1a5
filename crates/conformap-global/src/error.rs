//! The one error type of conformap-global.

use conformap_mesh::{MeshError, Topology};
use conformap_operators::OperatorError;

/// Why a global conformal map by holomorphic 1-forms or a topological optimization could
/// not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GlobalError {
    /// The mesh has the wrong topology for the operation. Fix: a global map needs one
    /// connected surface of genus ≥ 1 or with ≥ 2 boundary loops (`conformap info MESH` shows
    /// the topology); genus-0 closed surfaces and disks are `conformap-sphere`'s and
    /// `conformap-disk`'s.
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
    /// The starting disk map of the topological optimization of a disk failed (see the
    /// inner error; `conformap disk` on the same mesh reports the same).
    #[error("the starting disk map failed: {0}")]
    Disk(#[from] conformap_disk::DiskError),
    /// A mesh built by surgery (the cut along the homology basis, a slit) failed validation.
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
    /// An option is out of range. Fix: see the option's documentation for its range.
    #[error("invalid option {name}: {reason}")]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What is required.
        reason: &'static str,
    },
    /// The holomorphic 1-form basis is numerically degenerate (the wedge matrix of the
    /// harmonic basis or the Gram matrix is singular, or a form integrates to zero). Fix: the
    /// mesh is too coarse or its cotangent weights too badly conditioned; refine or remesh
    /// the extremely thin triangles.
    #[error("the 1-form basis is degenerate: {reason}")]
    DegenerateFormBasis {
        /// What was singular.
        reason: &'static str,
    },
    /// A zero-allocation target vertex does not exist. Fix: targets are 0-based indices of
    /// the input's vertices, below its vertex count.
    #[error("zero target vertex {vertex} is out of range: the mesh has {vertices} vertices (0-based indices)")]
    ZeroTargetOutOfRange {
        /// The offending vertex index.
        vertex: usize,
        /// Vertices of the input.
        vertices: usize,
    },
    /// A genus-0 step failed: the sphere map, the double covering or a Möbius optimization
    /// (see the inner error: its message, cause and fix are unchanged). An emphasized region
    /// out of range is reported here too ([`conformap_sphere::SphereError::RegionFaceOutOfRange`]).
    #[error(transparent)]
    Sphere(#[from] conformap_sphere::SphereError),
}

#[cfg(test)]
mod tests {
    use super::GlobalError;
    use conformap_sphere::SphereError;

    #[test]
    fn a_genus_0_error_keeps_its_message_and_its_fields_inside_global_error() {
        let inner = match conformap_sphere::region_mask(4, &[7]) {
            Err(e) => e,
            Ok(mask) => panic!("face 7 of 4 accepted: {mask:?}"),
        };
        let outer = GlobalError::from(inner.clone());
        assert_eq!(outer.to_string(), inner.to_string());
        assert_eq!(
            outer,
            GlobalError::Sphere(SphereError::RegionFaceOutOfRange { face: 7, faces: 4 })
        );
    }
}
