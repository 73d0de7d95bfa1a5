//! Seamed maps: texture coordinates per face corner (`f v/vt` with a vertex carrying
//! several `vt`), as `global` writes them and as other tools' atlases come.

use rustc_hash::FxHashMap as HashMap;

use crate::error::WriteProblem;

/// Texture coordinates per face corner: corner `k` of face `f` has
/// `texcoords[faces[f][k]]`. A vertex may have different coordinates in different faces
/// (a seam); a per-vertex map is the case `faces == mesh.faces()`.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CornerUv {
    /// The distinct texture coordinates (OBJ `vt` lines, in the OBJ convention: origin
    /// bottom-left).
    pub texcoords: Vec<[f64; 2]>,
    /// For each face of the mesh, the texture coordinate of each of its corners.
    pub faces: Vec<[u32; 3]>,
}

impl CornerUv {
    /// The per-corner form of a per-vertex map: `texcoords = uv`, `faces = faces`.
    pub fn per_vertex(uv: &[[f64; 2]], faces: &[[u32; 3]]) -> Self {
        Self {
            texcoords: uv.to_vec(),
            faces: faces.to_vec(),
        }
    }

    /// The texture coordinate of corner `k` of face `f`.
    ///
    /// # Panics
    /// If `f` or the index it holds is out of range (see [`Self::check`]).
    pub fn corner(&self, f: usize, k: usize) -> [f64; 2] {
        self.texcoords[self.faces[f][k] as usize]
    }

    /// Whether this is a map of a mesh with `faces` faces: one triple per face, every index
    /// in range, every value finite.
    ///
    /// # Errors
    /// The first [`WriteProblem`] found.
    pub fn check(&self, faces: usize) -> Result<(), WriteProblem> {
        if self.faces.len() != faces {
            return Err(WriteProblem::CornerFaceCount {
                expected: faces,
                found: self.faces.len(),
            });
        }
        let count = self.texcoords.len();
        for (face, t) in self.faces.iter().enumerate() {
            if let Some(&index) = t.iter().find(|&&i| i as usize >= count) {
                return Err(WriteProblem::TexcoordIndex { face, index, count });
            }
        }
        for (vertex, t) in self.texcoords.iter().enumerate() {
            if let Some(&value) = t.iter().find(|x| !x.is_finite()) {
                return Err(WriteProblem::NonFinite { vertex, value });
            }
        }
        Ok(())
    }

    /// The mesh split along the seams: one vertex per distinct (mesh vertex, texture
    /// coordinate) pair, numbered by first use in face order. Returns, per split vertex, its
    /// mesh vertex and its texture coordinate index, and the faces in split numbering.
    pub fn split(&self, mesh_faces: &[[u32; 3]]) -> (Vec<(u32, u32)>, Vec<[u32; 3]>) {
        let mut index: HashMap<(u32, u32), u32> =
            HashMap::with_capacity_and_hasher(self.texcoords.len(), Default::default());
        let mut pairs = Vec::with_capacity(self.texcoords.len());
        let faces = mesh_faces
            .iter()
            .zip(&self.faces)
            .map(|(f, t)| {
                std::array::from_fn(|k| {
                    *index.entry((f[k], t[k])).or_insert_with(|| {
                        pairs.push((f[k], t[k]));
                        (pairs.len() - 1) as u32
                    })
                })
            })
            .collect();
        (pairs, faces)
    }
}
