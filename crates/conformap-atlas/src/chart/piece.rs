//! A flat piece of a component and the pieces cut from it (what the overlap splits, the
//! fold repair, the last-resort regions and the neck cuts share).

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use crate::error::AtlasError;

/// A flat piece of a component: its faces (component-local ids), its own mesh (a disk),
/// the component vertex of each of its vertices, and its layout.
#[derive(Debug, Clone)]
pub struct Piece {
    /// Component face of each face.
    pub faces: Vec<u32>,
    /// The piece as a mesh.
    pub mesh: TriMesh,
    /// Component vertex of each vertex.
    pub original: Vec<u32>,
    /// Layout, one point per vertex.
    pub uv: Vec<Complex64>,
}

/// The piece of `piece` made of its faces `faces`, in the parent's layout.
pub(crate) fn sub_piece(piece: &Piece, faces: &[u32]) -> Result<Piece, AtlasError> {
    // the parent's checks and half-edge matching carried over (`TriMesh::sub_mesh`): the
    // same mesh as validating the faces afresh, for a third of the time
    let (mesh, vertices) = piece
        .mesh
        .sub_mesh(faces)
        .map_err(|e| AtlasError::Mesh(e.to_string()))?;
    Ok(Piece {
        faces: faces.iter().map(|&f| piece.faces[f as usize]).collect(),
        original: vertices
            .iter()
            .map(|&v| piece.original[v as usize])
            .collect(),
        uv: vertices.iter().map(|&v| piece.uv[v as usize]).collect(),
        mesh,
    })
}
