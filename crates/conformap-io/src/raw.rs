//! Reading without validating: the triangles a file holds, for callers that repair a mesh
//! before validation (the CLI's `--repair`). [`read_mesh`](crate::read_mesh) is this
//! followed by [`RawMesh::validate`].

use std::path::Path;

use conformap_mesh::{MeshError, TriMesh};

use crate::corner_uv::CornerUv;
use crate::error::{mesh_error_element, Element, IoError, Origin, UvProblem};
use crate::gltffile::{face_origin, read_gltf_raw, vertex_origin, PrimRange};
use crate::loaded::{Format, LoadedMesh, SourceInfo, VertexText};
use crate::objfile::read_obj_raw;

/// The name errors use for data that did not come from a file.
const MEMORY: &str = "<memory>";

/// A mesh as the file gives it, parsed but not validated: positions and triangles may have
/// any defect [`TriMesh::try_new`] rejects except an empty file (an error already).
///
/// Numbering is that of [`LoadedMesh`]: for OBJ, vertex `k` is the file's `k`-th `v` line
/// and face `k` the `k`-th triangle; for glTF, vertices are welded (bit-identical positions
/// merged, vertices no triangle uses left out; see [`SourceInfo::weld_map`]).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RawMesh {
    /// Vertex positions (possibly non-finite).
    pub positions: Vec<[f64; 3]>,
    /// Triangles (indices are in range; faces may be degenerate, duplicated, non-manifold or
    /// inconsistently oriented).
    pub faces: Vec<[u32; 3]>,
    /// The texture coordinate of each vertex (`None` for a vertex no face uses), when the
    /// file gives one per vertex; `None` otherwise (see [`Self::uv_problem`]).
    pub uv: Option<Vec<Option<[f64; 2]>>>,
    /// Why [`Self::uv`] is `None`; `None` when it is `Some`.
    pub uv_problem: Option<UvProblem>,
    /// The texture coordinate of every face corner, when every corner has one (seamed maps
    /// included); `None` when some corner has none.
    pub corner_uv: Option<CornerUv>,
    /// Where the mesh came from and how its elements map to the file.
    pub source: SourceInfo,
    /// glTF: the primitive ranges and the file vertex of each welded vertex, to name an
    /// element's origin. Empty for OBJ (lines are in `source`).
    origins: GltfOrigins,
    /// PLY, STL, OFF, GIfTI, FreeSurfer: the file element of each vertex and face.
    elements: Option<ElementOrigins>,
}

/// What a PLY, STL, OFF, GIfTI or FreeSurfer read keeps to name an element's origin.
#[derive(Debug, Clone, Default)]
pub(crate) struct ElementOrigins {
    /// What the file calls a vertex (`vertex`).
    pub(crate) vertex: &'static str,
    /// What the file calls a face (`face`, `facet`, `triangle`).
    pub(crate) face: &'static str,
    /// The file element of each mesh vertex; empty: the same index.
    pub(crate) vertex_of: Vec<usize>,
    /// The file element of each mesh face (a polygon gives several); empty: the same index.
    pub(crate) face_of: Vec<usize>,
}

impl ElementOrigins {
    /// Vertex `k` and face `k` are the file's `k`-th ones.
    pub(crate) fn identity(vertex: &'static str, face: &'static str) -> Self {
        Self {
            vertex,
            face,
            ..Self::default()
        }
    }

    fn origin(&self, element: Element) -> Option<Origin> {
        let pick = |of: &[usize], k: usize| {
            if of.is_empty() {
                Some(k)
            } else {
                of.get(k).copied()
            }
        };
        Some(match element {
            Element::Vertex(v) => Origin::Element {
                element: self.vertex,
                index: pick(&self.vertex_of, v)?,
            },
            Element::Face(f) => Origin::Element {
                element: self.face,
                index: pick(&self.face_of, f)?,
            },
        })
    }
}

/// What a glTF read keeps to name the origin of a welded vertex or a face.
#[derive(Debug, Clone, Default)]
pub(crate) struct GltfOrigins {
    pub(crate) prims: Vec<PrimRange>,
    /// For each welded vertex, its first file vertex.
    pub(crate) first_file: Vec<usize>,
}

impl RawMesh {
    pub(crate) fn new(
        positions: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        uv: Result<Vec<Option<[f64; 2]>>, UvProblem>,
        source: SourceInfo,
        origins: Option<GltfOrigins>,
    ) -> Self {
        let (uv, uv_problem) = match uv {
            Ok(uv) => (Some(uv), None),
            Err(p) => (None, Some(p)),
        };
        Self {
            positions,
            faces,
            uv,
            uv_problem,
            corner_uv: None,
            source,
            origins: origins.unwrap_or_default(),
            elements: None,
        }
    }

    /// Sets the file elements that vertices and faces come from (formats other than OBJ
    /// and glTF).
    pub(crate) fn with_elements(mut self, elements: ElementOrigins) -> Self {
        self.elements = Some(elements);
        self
    }

    /// Sets [`Self::corner_uv`].
    pub(crate) fn with_corner_uv(mut self, corner_uv: Option<CornerUv>) -> Self {
        self.corner_uv = corner_uv;
        self
    }

    /// The file place of vertex `v` (this mesh's numbering).
    pub(crate) fn vertex_place(&self, v: usize) -> Option<Origin> {
        let at = MeshError::UnreferencedVertex {
            vertex: v,
            count: 1,
        };
        self.origin_of(&at)
    }

    /// After welding: welded vertex `c` is the former vertex `first[c]`.
    pub(crate) fn reset_origins(&mut self, first: &[usize]) {
        if !self.origins.first_file.is_empty() {
            let old = std::mem::take(&mut self.origins.first_file);
            self.origins.first_file = first.iter().map(|&i| old[i]).collect();
        }
        if let Some(e) = &mut self.elements {
            let old = std::mem::take(&mut e.vertex_of);
            e.vertex_of = first
                .iter()
                .map(|&i| if old.is_empty() { i } else { old[i] })
                .collect();
        }
    }

    /// The file place of the vertex or face `error` names (its numbering must be this
    /// mesh's): an OBJ line, a glTF primitive vertex or triangle; `None` for whole-mesh
    /// errors or an index past the mesh.
    pub fn origin_of(&self, error: &MeshError) -> Option<Origin> {
        origin_in(&self.source, &self.origins, self.elements.as_ref(), error)
    }

    /// The [`IoError::InvalidMesh`] for a validation error about this mesh (this mesh's
    /// numbering), with the file place of the element it names.
    pub fn invalid_mesh(&self, error: MeshError) -> IoError {
        IoError::InvalidMesh {
            path: self.source.path.clone(),
            origin: self.origin_of(&error),
            source: error,
        }
    }

    /// Validates the mesh ([`TriMesh::try_new`]), as [`read_mesh`](crate::read_mesh) does.
    ///
    /// # Errors
    /// [`IoError::InvalidMesh`] naming the file place of the offending element.
    ///
    /// # Examples
    /// ```
    /// use conformap_io::{read_raw_mesh_from_bytes, Format, IoError, Origin};
    /// // the second face repeats the first: the raw read succeeds, validation does not
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 3 1\n";
    /// let raw = read_raw_mesh_from_bytes(obj, Format::Obj)?;
    /// assert_eq!(raw.faces.len(), 2);
    /// let err = raw.validate().unwrap_err();
    /// assert!(matches!(err, IoError::InvalidMesh { origin: Some(Origin::Line(5)), .. }));
    /// # Ok::<(), IoError>(())
    /// ```
    pub fn validate(self) -> Result<LoadedMesh, IoError> {
        let Self {
            positions,
            faces,
            uv,
            uv_problem,
            corner_uv,
            source,
            origins,
            elements,
        } = self;
        let mesh = TriMesh::try_new(positions, faces).map_err(|e| IoError::InvalidMesh {
            path: source.path.clone(),
            origin: origin_in(&source, &origins, elements.as_ref(), &e),
            source: e,
        })?;
        // a valid mesh references every vertex, so a per-vertex uv has every slot filled
        let uv = uv.map(|uv| uv.into_iter().collect::<Option<Vec<_>>>());
        let (uv, uv_problem) = match (uv, uv_problem) {
            (Some(Some(uv)), _) => (Some(uv), None),
            (Some(None), _) => (None, Some(UvProblem::Absent)),
            (None, problem) => (None, problem),
        };
        Ok(LoadedMesh {
            mesh,
            uv,
            uv_problem,
            corner_uv,
            source,
        })
    }
}

/// See [`RawMesh::origin_of`].
fn origin_in(
    src: &SourceInfo,
    origins: &GltfOrigins,
    elements: Option<&ElementOrigins>,
    error: &MeshError,
) -> Option<Origin> {
    let element = mesh_error_element(error)?;
    if let Some(e) = elements {
        return e.origin(element);
    }
    match (element, &src.vertex_lines, &src.face_lines) {
        (Element::Vertex(v), Some(lines), _) => lines.get(v).map(|&l| Origin::Line(l)),
        (Element::Face(f), _, Some(lines)) => lines.get(f).map(|&l| Origin::Line(l)),
        (Element::Vertex(v), None, _) => {
            let file = *origins.first_file.get(v)?;
            vertex_origin(&origins.prims, file)
        }
        (Element::Face(f), _, None) => face_origin(&origins.prims, f),
    }
}

/// Reads the triangles of an `.obj`, `.gltf` or `.glb` file (by extension) without
/// validating them: the same parsing, triangulation, node transforms and welding as
/// [`read_mesh`](crate::read_mesh), which is this followed by [`RawMesh::validate`].
///
/// # Errors
/// As [`read_mesh`](crate::read_mesh), except that [`IoError::InvalidMesh`] only comes for
/// a file with no vertex at all (`NoVertices`).
///
/// # Examples
/// ```no_run
/// let raw = conformap_io::read_raw_mesh("fixtures/bad/duplicate_face.obj")?;
/// assert_eq!(raw.source.face_lines.as_deref(), Some(&[5, 6][..]));
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn read_raw_mesh(path: impl AsRef<Path>) -> Result<RawMesh, IoError> {
    let path = path.as_ref();
    let named = Format::from_path(path);
    let bytes = read_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    // a FreeSurfer surface (`lh.white`) or a file named otherwise is known by its magic
    let format = match named {
        Ok(format) => format,
        Err(e) => Format::sniff(&bytes)
            .or_else(|| freesurfer_name(path))
            .ok_or(e)?,
    };
    match format {
        Format::Obj => {
            let (mut raw, spans) = read_obj_raw(&bytes, path)?;
            // the bytes move into the source (no copy) for the writer to reuse
            raw.source.vertex_text = Some(std::sync::Arc::new(VertexText::new(bytes, spans)));
            Ok(raw)
        }
        Format::Gltf | Format::Glb => {
            let base = path.parent().unwrap_or(Path::new(""));
            read_gltf_raw(&bytes, path, Some(base), format)
        }
        other => read_other_raw(&bytes, path, other),
    }
}

/// FreeSurfer for a name like `lh.mysurf` or `rh.x` (whose extension names no format): its
/// reader then says what is wrong with the magic.
fn freesurfer_name(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_str()?;
    (name.starts_with("lh.") || name.starts_with("rh.")).then_some(Format::FreeSurfer)
}

/// The readers of PLY, STL, OFF, GIfTI and FreeSurfer surfaces.
fn read_other_raw(bytes: &[u8], path: &Path, format: Format) -> Result<RawMesh, IoError> {
    match format {
        Format::Ply => crate::plyfile::read_ply_raw(bytes, path),
        Format::Stl => crate::stlfile::read_stl_raw(bytes, path),
        Format::Off => crate::offfile::read_off_raw(bytes, path),
        Format::Gifti => crate::gifti::read_gifti_raw(bytes, path),
        Format::FreeSurfer => crate::freesurfer::read_freesurfer_raw(bytes, path),
        Format::Obj | Format::Gltf | Format::Glb => Ok(read_obj_raw(bytes, path)?.0),
    }
}

/// Files at least this large are read by all threads at once, each its own part.
const PARALLEL_READ_MIN_BYTES: u64 = 1 << 20;

/// The bytes of a file, as [`std::fs::read`] gives them. A large file is read in parts on
/// all threads at once: the copy from the page cache into fresh memory costs a page fault
/// per 4 KiB, which both cores then share (a 3.7 MB mesh: 4–7 ms read alone).
#[cfg(unix)]
fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    use rayon::prelude::*;
    use std::io::{Read, Seek, SeekFrom};
    use std::os::unix::fs::FileExt;

    let mut file = std::fs::File::open(path)?;
    let len = file.metadata()?.len();
    if len < PARALLEL_READ_MIN_BYTES {
        let mut bytes = Vec::new();
        file.read_to_end(&mut bytes)?;
        return Ok(bytes);
    }
    let mut bytes = vec![0u8; usize::try_from(len).map_err(std::io::Error::other)?];
    let part = bytes.len().div_ceil(rayon::current_num_threads().max(1));
    bytes
        .par_chunks_mut(part)
        .enumerate()
        .try_for_each(|(k, chunk)| file.read_exact_at(chunk, (k * part) as u64))?;
    // what a file that grew meanwhile has beyond, as a plain read would have it
    file.seek(SeekFrom::Start(len))?;
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The bytes of a file ([`std::fs::read`]).
#[cfg(not(unix))]
fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    std::fs::read(path)
}

/// [`read_raw_mesh`] from bytes already in memory (tests, fuzzing); errors name the file
/// `<memory>` and a glTF that refers to external files is an error.
///
/// # Errors
/// As [`read_raw_mesh`].
pub fn read_raw_mesh_from_bytes(bytes: &[u8], format: Format) -> Result<RawMesh, IoError> {
    let path = Path::new(MEMORY);
    match format {
        Format::Obj => Ok(read_obj_raw(bytes, path)?.0),
        Format::Gltf | Format::Glb => read_gltf_raw(bytes, path, None, format),
        other => read_other_raw(bytes, path, other),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    /// A file large enough to be read in parts comes back byte for byte, parts of an odd
    /// size included; so does a small one.
    #[test]
    fn files_read_in_parts_are_whole() {
        let dir = std::env::temp_dir().join(format!("conformap-io-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for len in [0usize, 10, (3 << 20) + 7] {
            let bytes: Vec<u8> = (0..len).map(|i| (i * 7 + i / 4099) as u8).collect();
            let path = dir.join(format!("f{len}.bin"));
            std::fs::write(&path, &bytes).unwrap();
            assert!(read_file(&path).unwrap() == bytes, "{len} bytes");
        }
        assert!(read_file(&dir.join("absent.obj")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
