//! Seamed maps: texture coordinates per face corner (`f v/vt` with a vertex carrying
//! several `vt`), as `global` writes them and as other tools' atlases come.

use std::collections::HashMap;
use std::path::Path;

use conformap_mesh::TriMesh;

use crate::api::write_target;
use crate::atomic::{write_atomically, write_encoded_atomically};
use crate::error::{IoError, WriteProblem};
use crate::gltffile::encode_gltf;
use crate::loaded::Format;
use crate::objfile::encode_obj_with_corner_uv;
use crate::plyfile::{encode_ply, PlyUv};

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
        let mut index: HashMap<(u32, u32), u32> = HashMap::with_capacity(self.texcoords.len());
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

/// Writes `mesh` with a seamed map: OBJ keeps the `v` lines in the mesh's order and count
/// and writes `f v/vt` with one `vt` per entry of `uv.texcoords` (exact round trip);
/// glTF/GLB split the vertices along the seams (one vertex per distinct position and
/// texture coordinate, `TEXCOORD_0`), as glTF requires.
///
/// The file appears complete or not at all.
///
/// # Errors
/// [`IoError::BadWriteInput`] if `uv` is not a map of `mesh` ([`CornerUv::check`]) or a
/// value is not finite; [`IoError::Write`] if the file cannot be written;
/// [`IoError::UnknownFormat`] for another extension.
///
/// # Examples
/// ```
/// use conformap_io::{read_mesh, write_mesh_with_corner_uv, CornerUv};
/// # let dir = std::env::temp_dir().join(format!("conformap-io-corner-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir).unwrap();
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// ).unwrap();
/// // the second face's copy of vertex 0 sits elsewhere: a seam along edge 0–2
/// let uv = CornerUv {
///     texcoords: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]],
///     faces: vec![[0, 1, 2], [4, 2, 3]],
/// };
/// let out = dir.join("seamed.obj");
/// write_mesh_with_corner_uv(&out, &mesh, &uv)?;
/// let back = read_mesh(&out)?;
/// assert_eq!(back.corner_uv.as_ref(), Some(&uv));
/// assert!(back.uv.is_none()); // not one texture coordinate per vertex
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn write_mesh_with_corner_uv(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    uv: &CornerUv,
) -> Result<(), IoError> {
    let path = path.as_ref();
    let (format, bad) = write_target(path)?;
    uv.check(mesh.num_faces()).map_err(bad)?;
    match format {
        Format::Obj => {
            let encoded =
                encode_obj_with_corner_uv(mesh.positions(), &uv.texcoords, mesh.faces(), &uv.faces);
            write_encoded_atomically(path, &encoded)
        }
        Format::Gltf | Format::Glb => {
            let (pairs, faces) = uv.split(mesh.faces());
            let positions: Vec<[f64; 3]> = pairs
                .iter()
                .map(|&(v, _)| mesh.positions()[v as usize])
                .collect();
            let texcoords: Vec<[f64; 2]> = pairs
                .iter()
                .map(|&(_, t)| uv.texcoords[t as usize])
                .collect();
            let bytes = encode_gltf(format == Format::Glb, &positions, Some(&texcoords), &faces)
                .map_err(bad)?;
            write_atomically(path, &bytes)
        }
        Format::Ply => {
            crate::api::check_ply_size(mesh.num_vertices()).map_err(bad)?;
            let bytes = encode_ply(mesh.positions(), mesh.faces(), PlyUv::PerCorner(uv));
            write_atomically(path, &bytes)
        }
        other => Err(bad(crate::api::no_texture_coordinates(other))),
    }
}
