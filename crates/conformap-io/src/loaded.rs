//! What a reader returns: the validated mesh, optional texture coordinates, and where the
//! mesh's elements came from in the file.

use std::path::{Path, PathBuf};

use conformap_mesh::TriMesh;

use crate::corner_uv::CornerUv;
use crate::error::{IoError, UvProblem};

/// Peak memory of reading a mesh file, per byte of the file (the bytes, the text the OBJ
/// parser holds, its and our index arrays). Measured: 590 MiB for the 84 MB OBJ of a
/// 2M-face grid (7.4×). Callers use it to refuse, before reading, a file that would not fit.
/// It bounds every format but gzip-compressed GIfTI, whose own factor is
/// [`Format::read_peak_bytes_per_file_byte`]; every reader also checks the counts its
/// header declares against the bytes present before allocating for them.
pub const READ_PEAK_BYTES_PER_FILE_BYTE: u64 = 8;

/// Marks a file vertex that no triangle uses in [`SourceInfo::weld_map`].
pub const NO_VERTEX: u32 = u32::MAX;

/// A mesh file format, chosen by the file's extension (or, for FreeSurfer surfaces, which
/// have none, by the file's first bytes: see [`Format::sniff`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Format {
    /// Wavefront OBJ text (`.obj`).
    Obj,
    /// glTF 2.0 JSON (`.gltf`); buffers external or embedded as data URIs.
    Gltf,
    /// Binary glTF 2.0 (`.glb`).
    Glb,
    /// Stanford PLY (`.ply`): ASCII or binary, either byte order.
    Ply,
    /// STL (`.stl`): ASCII or binary; read only.
    Stl,
    /// Object File Format (`.off`, with `COFF`, `NOFF`, `STOFF`... headers); read only.
    Off,
    /// GIfTI (`.gii`: `.surf.gii` surfaces; `.shape.gii`/`.func.gii` data arrays are
    /// written by [`write_vertex_data`](crate::write_vertex_data)).
    Gifti,
    /// FreeSurfer binary triangle surface (`lh.white`, `rh.pial`, `lh.sphere`...): named by
    /// a surface extension (`.white`, `.pial`, `.sphere`, `.inflated`, `.orig`,
    /// `.smoothwm`, `.midthickness`, `.reg`, or `.fsurf`) or, when reading, found by its
    /// magic number.
    FreeSurfer,
}

/// The extensions of FreeSurfer surfaces (`lh.white` has the extension `white`).
const FREESURFER_EXTENSIONS: &[&str] = &[
    "white",
    "pial",
    "sphere",
    "inflated",
    "orig",
    "smoothwm",
    "midthickness",
    "reg",
    "fsurf",
];

/// The first three bytes of a FreeSurfer triangle file (the magic number 0xFFFFFE).
pub(crate) const FREESURFER_MAGIC: [u8; 3] = [0xff, 0xff, 0xfe];

impl Format {
    /// The format named by the extension of `path` (any case): `.obj`, `.gltf`, `.glb`,
    /// `.ply`, `.stl`, `.off`, `.gii`, and FreeSurfer's surface names (see
    /// [`Format::FreeSurfer`]).
    ///
    /// # Errors
    /// [`IoError::UnknownFormat`] for any other extension or none.
    ///
    /// # Examples
    /// ```
    /// use conformap_io::Format;
    /// assert_eq!(Format::from_path("out/Head.GLB".as_ref())?, Format::Glb);
    /// assert_eq!(Format::from_path("sub-01/lh.white".as_ref())?, Format::FreeSurfer);
    /// assert_eq!(Format::from_path("lh.sphere.surf.gii".as_ref())?, Format::Gifti);
    /// assert!(Format::from_path("head.3ds".as_ref()).is_err());
    /// # Ok::<(), conformap_io::IoError>(())
    /// ```
    pub fn from_path(path: &Path) -> Result<Self, IoError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("obj") => Ok(Self::Obj),
            Some("gltf") => Ok(Self::Gltf),
            Some("glb") => Ok(Self::Glb),
            Some("ply") => Ok(Self::Ply),
            Some("stl") => Ok(Self::Stl),
            Some("off") => Ok(Self::Off),
            Some("gii") => Ok(Self::Gifti),
            Some(e) if FREESURFER_EXTENSIONS.contains(&e) => Ok(Self::FreeSurfer),
            _ => Err(IoError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
    }

    /// The format a file's first bytes show, for files whose name says none: FreeSurfer's
    /// triangle magic `FF FF FE`, `ply`, `solid`, `OFF`, `glTF`, `<?xml` (GIfTI). `None`
    /// when the bytes show none of them.
    ///
    /// # Examples
    /// ```
    /// use conformap_io::Format;
    /// assert_eq!(Format::sniff(b"\xff\xff\xfecreated by me\n\n"), Some(Format::FreeSurfer));
    /// assert_eq!(Format::sniff(b"ply\nformat ascii 1.0\n"), Some(Format::Ply));
    /// assert_eq!(Format::sniff(b"v 0 0 0\n"), None);
    /// ```
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        if bytes.starts_with(&FREESURFER_MAGIC) {
            Some(Self::FreeSurfer)
        } else if text.starts_with(b"ply") {
            Some(Self::Ply)
        } else if bytes.starts_with(b"glTF") {
            Some(Self::Glb)
        } else if text.starts_with(b"<?xml") || text.starts_with(b"<GIFTI") {
            Some(Self::Gifti)
        } else if crate::off_keyword::is_off_header(text) {
            Some(Self::Off)
        } else if text.starts_with(b"solid") {
            Some(Self::Stl)
        } else {
            None
        }
    }

    /// The usual file extension, without the dot (`surf.gii` for GIfTI surfaces, `white`
    /// for FreeSurfer).
    pub fn extension(self) -> &'static str {
        match self {
            Self::Obj => "obj",
            Self::Gltf => "gltf",
            Self::Glb => "glb",
            Self::Ply => "ply",
            Self::Stl => "stl",
            Self::Off => "off",
            Self::Gifti => "surf.gii",
            Self::FreeSurfer => "white",
        }
    }

    /// Peak memory of reading a file of this format, per byte of the file: what a caller
    /// holds against the memory available before reading (see
    /// [`READ_PEAK_BYTES_PER_FILE_BYTE`], the bound
    /// over every format but gzip-compressed GIfTI).
    ///
    /// Binary formats hold the bytes (1×) and f64 positions from f32 (2×) plus triangles
    /// and their checks: ≤ 6×. GIfTI decodes base64 (0.75×) and may inflate gzip: its
    /// estimate assumes the 4:1 of typical compressed surfaces and the reader stops
    /// inflating at the size the header declares.
    pub fn read_peak_bytes_per_file_byte(self) -> u64 {
        match self {
            Self::Gifti => 24,
            _ => READ_PEAK_BYTES_PER_FILE_BYTE,
        }
    }
}

/// A mesh read from a file.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct LoadedMesh {
    /// The validated mesh. For OBJ, vertex `k` is the file's `k`-th `v` line and face `k` the
    /// `k`-th triangle (polygons fan-triangulated in place). For glTF, vertices are welded:
    /// see [`SourceInfo::weld_map`].
    pub mesh: TriMesh,
    /// One texture coordinate per mesh vertex, in the OBJ convention (origin bottom-left;
    /// glTF's `TEXCOORD_0` `(s, t)` becomes `(s, 1 − t)`), or `None` when the file has none
    /// or not exactly one per vertex (see [`Self::uv_problem`]).
    pub uv: Option<Vec<[f64; 2]>>,
    /// Why [`Self::uv`] is `None`; `None` when it is `Some`.
    pub uv_problem: Option<UvProblem>,
    /// The texture coordinate of every face corner, when every corner has one: a seamed
    /// map (OBJ `f v/vt` with a vertex under several `vt`, or glTF vertices split along
    /// seams) as well as a per-vertex one. `None` when the file has none or some corner
    /// lacks one (then [`Self::uv_problem`] says which).
    pub corner_uv: Option<CornerUv>,
    /// Where the mesh came from and how its elements map to the file.
    pub source: SourceInfo,
}

impl LoadedMesh {
    /// The per-vertex texture coordinates, for inputs that carry a map (`PARAM`).
    ///
    /// # Errors
    /// [`IoError::NotPerVertexUv`] when the file has none, some corners lack one, or a vertex
    /// has two different ones (a seam); the error names the line or glTF primitive vertex.
    pub fn per_vertex_uv(&self) -> Result<&[[f64; 2]], IoError> {
        match (&self.uv, &self.uv_problem) {
            (Some(uv), _) => Ok(uv),
            (None, problem) => Err(IoError::NotPerVertexUv {
                path: self.source.path.clone(),
                problem: problem.clone().unwrap_or(UvProblem::Absent),
            }),
        }
    }
}

/// Where a mesh came from and how its vertices and faces map back to the file.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct SourceInfo {
    /// The file read (`<memory>` for the `_from_bytes` readers).
    pub path: PathBuf,
    /// Its format.
    pub format: Format,
    /// Vertices as the file stores them: OBJ `v` lines, or glTF `POSITION` elements of all
    /// triangle primitives (per node instance, concatenated in traversal order).
    pub file_vertex_count: usize,
    /// OBJ: the 1-based line of each vertex. `None` for glTF.
    pub vertex_lines: Option<Vec<usize>>,
    /// OBJ: the 1-based line of each face (a polygon line gives several faces). `None` for
    /// glTF.
    pub face_lines: Option<Vec<usize>>,
    /// glTF: for each file vertex, the mesh vertex it was welded into ([`NO_VERTEX`] if no
    /// triangle uses it). Bit-identical positions weld; the first occurrence fixes the mesh
    /// vertex's number, so mesh vertices are in order of first occurrence. `None` for OBJ.
    pub weld_map: Option<Vec<u32>>,
    /// glTF: the faces in file-vertex numbering (same order as the mesh's faces), so a
    /// writer can reproduce the file's vertex layout. `None` for OBJ.
    pub file_faces: Option<Vec<[u32; 3]>>,
    /// Things that were ignored or adjusted while reading (non-triangle glTF primitives,
    /// OBJ lines or points, ...), for the caller to show. Empty when nothing was.
    pub notes: Vec<String>,
    /// OBJ read from a file: every vertex's coordinates as the file wrote them, which the
    /// OBJ writer copies instead of formatting the same numbers again. `None` for glTF and
    /// for bytes read from memory.
    pub vertex_text: Option<std::sync::Arc<VertexText>>,
    /// GIfTI and FreeSurfer surfaces: what the file says about the surface beyond its
    /// mesh (created-by line, volume geometry, coordinate transforms), kept for the report
    /// and for writing the same kind of file back. `None` for other formats.
    pub surface: Option<SurfaceMetadata>,
}

/// What a neuroimaging surface file says beyond its mesh.
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct SurfaceMetadata {
    /// FreeSurfer: the `created by …` line.
    pub created_by: Option<String>,
    /// FreeSurfer: the volume-geometry footer after the triangles (tag and `key = value`
    /// lines: `valid`, `filename`, `volume`, `voxelsize`, `xras`, `yras`, `zras`, `cras`),
    /// byte for byte; written back by the FreeSurfer writer.
    pub volume_info: Option<Vec<u8>>,
    /// GIfTI: the coordinate-system transforms of the point set.
    pub transforms: Vec<CoordinateTransform>,
}

/// A GIfTI `CoordinateSystemTransformMatrix`: the affine from the points' space to another.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordinateTransform {
    /// The space the points are in (e.g. `NIFTI_XFORM_UNKNOWN`).
    pub data_space: String,
    /// The space the matrix maps them to (e.g. `NIFTI_XFORM_TALAIRACH`).
    pub transformed_space: String,
    /// The 4×4 matrix, row-major.
    pub matrix: [[f64; 4]; 4],
}

/// The text of each vertex's `x y z` in an OBJ file, kept from reading for writing: copying
/// the numbers as written gives back exactly the bits they were parsed to (the same parser
/// reads the output), at the cost of keeping the file's bytes (its size) until then.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexText {
    bytes: Vec<u8>,
    /// `(start, len)` in `bytes` per vertex; `start == usize::MAX` where the numbers cannot
    /// be copied (a homogeneous `w`, colours after the position, a continued line).
    spans: Vec<(usize, usize)>,
}

impl VertexText {
    /// The file's bytes and the span of each vertex's numbers in them.
    pub(crate) fn new(bytes: Vec<u8>, spans: Vec<(usize, usize)>) -> Self {
        Self { bytes, spans }
    }

    /// Vertices described.
    pub fn len(&self) -> usize {
        self.spans.len()
    }

    /// Whether no vertex is described.
    pub fn is_empty(&self) -> bool {
        self.spans.is_empty()
    }

    /// Vertex `v`'s `x y z` as written, `None` where it cannot be copied.
    pub fn vertex(&self, v: usize) -> Option<&[u8]> {
        let &(start, len) = self.spans.get(v)?;
        self.bytes.get(start..start.checked_add(len)?)
    }

    /// Whether the text of vertex `v` (where there is one) parses to exactly `p`: the
    /// writer's check that the mesh it writes is the one read.
    pub fn matches(&self, v: usize, p: [f64; 3]) -> bool {
        let Some(text) = self.vertex(v) else {
            return true;
        };
        let mut words = text
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        p.iter().all(|&x| {
            words
                .next()
                .and_then(|w| match crate::objfile::decimal(w) {
                    Some((y, len)) if len == w.len() => Some(y),
                    _ => fast_float2::parse::<f64, _>(w).ok(),
                })
                .is_some_and(|y| y.to_bits() == x.to_bits())
        }) && words.next().is_none()
    }
}

impl SourceInfo {
    /// The source of a mesh with no file layout to keep (no lines, no weld): what the
    /// readers start from, and what a mesh built from arrays (the Python package) has.
    pub fn new(path: PathBuf, format: Format) -> Self {
        Self {
            path,
            format,
            file_vertex_count: 0,
            vertex_lines: None,
            face_lines: None,
            weld_map: None,
            file_faces: None,
            notes: Vec::new(),
            vertex_text: None,
            surface: None,
        }
    }
}
