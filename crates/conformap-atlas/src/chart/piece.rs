//! A flat piece of a component and the pieces cut from it (what the overlap splits, the
//! fold repair, the last-resort regions and the neck cuts share).

use rustc_hash::FxHashMap as HashMap;

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

/// The layout of the new vertices: the parent's.
fn local_uv(local: &HashMap<u32, u32>, parent: &[Complex64], n: usize) -> Vec<Complex64> {
    let mut uv = vec![Complex64::new(0.0, 0.0); n];
    for (&v, &l) in local {
        uv[l as usize] = parent[v as usize];
    }
    uv
}

/// The piece of `piece` made of its faces `faces`, in the parent's layout.
pub(crate) fn sub_piece(piece: &Piece, faces: &[u32]) -> Result<Piece, AtlasError> {
    let mut local = HashMap::default();
    let mut original = Vec::new();
    let mut positions = Vec::new();
    let mut tris = Vec::with_capacity(faces.len());
    for &f in faces {
        let t = piece.mesh.faces()[f as usize];
        tris.push(t.map(|v| {
            *local.entry(v).or_insert_with(|| {
                original.push(piece.original[v as usize]);
                positions.push(piece.mesh.positions()[v as usize]);
                (original.len() - 1) as u32
            })
        }));
    }
    let mesh = TriMesh::try_new(positions, tris).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let uv = local_uv(&local, &piece.uv, original.len());
    Ok(Piece {
        faces: faces.iter().map(|&f| piece.faces[f as usize]).collect(),
        mesh,
        original,
        uv,
    })
}
