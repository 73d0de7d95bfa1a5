//! The one error type of this crate, and the places in a file it points at.

use std::fmt;
use std::path::PathBuf;

use conformap_mesh::MeshError;

/// Why a mesh file could not be read or written.
///
/// Every variant names the file; those about content also name the place in it (an OBJ line,
/// or a glTF mesh, primitive and accessor), and each says what the user can do about it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum IoError {
    /// The file could not be opened or read. Fix: check the path and its permissions.
    #[error("{}: cannot read the file: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The output (or its temporary sibling) could not be written or renamed into place.
    /// Nothing is left at `path` in that case. Fix: check that the directory exists and is
    /// writable, and that the disk is not full.
    #[error("{}: cannot write the file: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The file name does not end in a mesh extension (`.obj`, `.gltf`, `.glb`, `.ply`,
    /// `.stl`, `.off`, `.gii`, a FreeSurfer surface name; case-insensitive) and, when
    /// reading, its first bytes show no known format either. Fix: rename the file or pick
    /// an output name with one of those extensions.
    #[error(
        "{}: unknown mesh format (expected a .obj, .gltf, .glb, .ply, .stl, .off or .gii file, \
         or a FreeSurfer surface such as lh.white)",
        path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A line of an OBJ file is malformed: see [`ObjProblem`] for what is wrong with it.
    /// Fix: repair that line (the message quotes the offending token).
    #[error("{}:{line}: {problem}", path.display())]
    ObjSyntax {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong with the line.
        problem: ObjProblem,
    },
    /// The file was parsed, but its triangles do not form a valid mesh (non-finite
    /// coordinate, degenerate, duplicate or non-manifold element, ...). `origin` is the file
    /// place of the element the [`MeshError`] names (`None` for whole-mesh problems such as
    /// an empty file). Fix: the message of `source` says what to repair.
    #[error("{}{}: {source}", path.display(), origin_suffix(origin.as_ref()))]
    InvalidMesh {
        /// The file.
        path: PathBuf,
        /// Where the offending vertex or face comes from.
        origin: Option<Origin>,
        /// The validation error, with 0-based mesh vertex/face indices.
        source: MeshError,
    },
    /// Per-vertex texture coordinates were asked for (a `PARAM` input) but the file does not
    /// give exactly one per vertex: see [`UvProblem`]. Fix: export the map with one texture
    /// coordinate per vertex (no seams), or pass it as a flat mesh instead.
    #[error("{}{}: {problem}", path.display(), origin_suffix(problem.origin()))]
    NotPerVertexUv {
        /// The file.
        path: PathBuf,
        /// Why the texture coordinates are not one per vertex.
        problem: UvProblem,
    },
    /// The glTF JSON is invalid, or a buffer could not be loaded for a reason the `gltf`
    /// crate reports (problems this reader recognises itself, such as a wrong GLB header,
    /// glTF 1.0, bad base64 or a short buffer, are [`IoError::GltfData`] with their own
    /// hint). Fix: check the file with the Khronos glTF validator.
    #[error("{}: cannot load the glTF ({source})", path.display())]
    Gltf {
        /// The file.
        path: PathBuf,
        /// What the `gltf` crate said.
        source: gltf::Error,
    },
    /// A glTF accessor, primitive or node cannot be used: wrong type, data outside its
    /// buffer, index out of range, missing `POSITION`, sparse storage, a node cycle...
    /// Fix: re-export the asset; the message names the mesh, primitive and accessor.
    #[error("{}: {}{problem}", path.display(), gltf_place(*mesh, *primitive, *accessor))]
    GltfData {
        /// The file.
        path: PathBuf,
        /// Index of the glTF mesh, if the problem is inside one.
        mesh: Option<usize>,
        /// Index of the primitive within that mesh.
        primitive: Option<usize>,
        /// Index of the accessor, if the problem is in one.
        accessor: Option<usize>,
        /// What is wrong.
        problem: String,
        /// What the user can do about it (see [`IoError::hint`]).
        hint: &'static str,
    },
    /// A PLY, STL, OFF, GIfTI or FreeSurfer file is malformed or truncated: the message
    /// names the format, the place ([`Place`]: a line, a byte offset, an element) and what is
    /// wrong. Fix: the hint says what to do; usually, export the file again.
    #[error("{}: {} {place}: {problem}", path.display(), format_name(*format))]
    Malformed {
        /// The file.
        path: PathBuf,
        /// Its format.
        format: crate::Format,
        /// Where in the file.
        place: Place,
        /// What is wrong.
        problem: String,
        /// What the user can do about it (see [`IoError::hint`]).
        hint: &'static str,
    },
    /// The data handed to a writer is inconsistent: see [`WriteProblem`]. Nothing is written.
    /// Fix: this is a caller bug or a non-finite map value; the message names the element.
    #[error("{}: nothing written: {problem}", path.display())]
    BadWriteInput {
        /// The file that was to be written.
        path: PathBuf,
        /// What is wrong with the data.
        problem: WriteProblem,
    },
}

/// The hint for a glTF problem with no more specific advice.
pub(crate) const GLTF_HINT: &str = "re-export the asset, or check it with the Khronos glTF \
                                    validator; the message names the mesh, primitive and \
                                    accessor";

impl IoError {
    /// What the user can do about this error: one sentence, for a `hint:` line under the
    /// message. Every variant has one; for [`IoError::InvalidMesh`] it is generic (callers
    /// with repair tools, like the CLI, give a more specific one per [`MeshError`]).
    pub fn hint(&self) -> &'static str {
        match self {
            Self::Read { .. } => "check the path and that the file is readable",
            Self::Write { .. } => {
                "check that the output directory exists and is writable, and that the disk \
                 is not full"
            }
            Self::UnknownFormat { .. } => {
                "name the file by its actual format: .obj, .gltf, .glb, .ply, .stl, .off, \
                 .surf.gii, or lh.white-style for FreeSurfer"
            }
            Self::ObjSyntax { problem, .. } => problem.hint(),
            Self::InvalidMesh { .. } => {
                "repair the element the message names in a mesh editor and export again"
            }
            Self::NotPerVertexUv { .. } => {
                "export the map with one texture coordinate per vertex (no seams), or pass \
                 it as a flat mesh"
            }
            Self::Gltf { .. } => GLTF_HINT,
            Self::GltfData { hint, .. } | Self::Malformed { hint, .. } => hint,
            Self::BadWriteInput {
                problem: WriteProblem::NotWritable { .. },
                ..
            } => "pick an output name whose format holds what is written (the message says which)",
            Self::BadWriteInput { .. } => {
                "this is a bug in the caller (or a non-finite map value): please report it \
                 with the input"
            }
        }
    }

    /// The same error with another hint, for [`IoError::GltfData`] (others are unchanged).
    pub(crate) fn with_hint(mut self, new: &'static str) -> Self {
        if let Self::GltfData { hint, .. } = &mut self {
            *hint = new;
        }
        self
    }
}

/// Where in a file a vertex or face comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Origin {
    /// An element of a PLY, STL, OFF, GIfTI or FreeSurfer file: `vertex 12` (the file's
    /// 0-based vertex), `face 7` (PLY/OFF face, before fan triangulation), `facet 9` (STL),
    /// `triangle 3` (GIfTI, FreeSurfer).
    Element {
        /// `vertex`, `face`, `facet` or `triangle`.
        element: &'static str,
        /// 0-based index among the file's elements of that kind.
        index: usize,
    },
    /// A 1-based line of an OBJ file.
    Line(usize),
    /// A vertex of a glTF primitive (0-based index into its `POSITION` accessor).
    GltfVertex {
        /// glTF mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// Vertex index within the primitive.
        vertex: usize,
    },
    /// A triangle of a glTF primitive (0-based, after strips and fans are expanded).
    GltfTriangle {
        /// glTF mesh index.
        mesh: usize,
        /// Primitive index within the mesh.
        primitive: usize,
        /// Triangle index within the primitive.
        triangle: usize,
    },
}

impl fmt::Display for Origin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Line(line) => write!(f, "line {line}"),
            Self::Element { element, index } => write!(f, "{element} {index}"),
            Self::GltfVertex {
                mesh,
                primitive,
                vertex,
            } => write!(f, "mesh {mesh}, primitive {primitive}, vertex {vertex}"),
            Self::GltfTriangle {
                mesh,
                primitive,
                triangle,
            } => write!(f, "mesh {mesh}, primitive {primitive}, triangle {triangle}"),
        }
    }
}

/// A place in a PLY, STL, OFF, GIfTI or FreeSurfer file, for [`IoError::Malformed`].
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Place {
    /// A 1-based line of a text file (PLY header or ASCII body, OFF, ASCII STL, GIfTI XML).
    Line(usize),
    /// A byte offset from the start of the file, and the element there if any
    /// (`vertex 12`, `facet 3`).
    Byte {
        /// 0-based byte offset.
        offset: u64,
        /// The element being read, e.g. `vertex 12`; empty in a header.
        element: String,
    },
    /// A GIfTI data array (0-based, in file order).
    DataArray(usize),
    /// The file as a whole (a missing part, such as a GIfTI file without a triangle array).
    File,
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Line(line) => write!(f, "line {line}"),
            Self::Byte { offset, element } if element.is_empty() => write!(f, "byte {offset}"),
            Self::Byte { offset, element } => write!(f, "byte {offset} ({element})"),
            Self::DataArray(k) => write!(f, "data array {k}"),
            Self::File => write!(f, "file"),
        }
    }
}

/// The name of a format in messages.
fn format_name(format: crate::Format) -> &'static str {
    use crate::Format as F;
    match format {
        F::Obj => "OBJ",
        F::Gltf | F::Glb => "glTF",
        F::Ply => "PLY",
        F::Stl => "STL",
        F::Off => "OFF",
        F::Gifti => "GIfTI",
        F::FreeSurfer => "FreeSurfer surface",
    }
}

/// What is wrong with one line of an OBJ file.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ObjProblem {
    /// The file is not UTF-8 text (the line holds the first invalid byte).
    NotUtf8,
    /// The line starts with a word that is not an OBJ statement.
    UnknownStatement {
        /// The first word of the line.
        keyword: String,
    },
    /// A `v`, `vt` or `vn` line has the wrong number of values (`v`: 3, 4 or 6; `vt`: 2 or 3;
    /// `vn`: 3).
    WrongValueCount {
        /// `v`, `vt` or `vn`.
        keyword: String,
        /// How many values the line has.
        found: usize,
    },
    /// A `v`, `vt` or `vn` line has a value that is not a number.
    BadNumber {
        /// `v`, `vt` or `vn`.
        keyword: String,
        /// The offending text (at most 40 characters).
        text: String,
    },
    /// A `v`, `vt` or `vn` value is a number too large for f64 (`1e400`): it would read as
    /// infinity.
    NumberOverflow {
        /// `v`, `vt` or `vn`.
        keyword: String,
        /// The number as written (at most 40 characters).
        text: String,
    },
    /// A homogeneous `v x y z w` line has `w = 0` (a point at infinity).
    ZeroW,
    /// An `f` line has fewer than three corners.
    TooFewCorners {
        /// How many corners the line has.
        found: usize,
    },
    /// A face corner is not of the form `v`, `v/vt`, `v//vn` or `v/vt/vn` with integers.
    BadCorner {
        /// The offending token.
        token: String,
    },
    /// A face index is 0 (OBJ indices start at 1; negative ones count back from the end).
    IndexZero {
        /// `vertex`, `texture coordinate` or `normal`.
        what: &'static str,
    },
    /// A face index points past the elements defined (for negative indices: before the first).
    IndexOutOfRange {
        /// `vertex`, `texture coordinate` or `normal`.
        what: &'static str,
        /// The index as written.
        index: i64,
        /// How many such elements there are (for negative indices: defined so far).
        count: usize,
    },
    /// The reader's first pass counted fewer elements than its parse met on this line: a
    /// reader bug, never a property of the file (reported instead of writing out of bounds).
    Miscounted,
}

impl ObjProblem {
    /// What the user can do about this line (see [`IoError::hint`]).
    pub fn hint(&self) -> &'static str {
        match self {
            Self::NotUtf8 => "convert the file to UTF-8 text; a binary file is not an OBJ",
            Self::IndexZero { .. } => {
                "OBJ indices start at 1: the exporter wrote 0-based indices; add 1 to every \
                 index of the `f` lines"
            }
            Self::IndexOutOfRange { .. } => {
                "the face refers to an element the file does not define: the file is \
                 truncated or its indices are off; re-export it"
            }
            Self::Miscounted => {
                "this is a conformap bug, not your file's: please report it with the file"
            }
            Self::UnknownStatement { .. }
            | Self::WrongValueCount { .. }
            | Self::BadNumber { .. }
            | Self::NumberOverflow { .. }
            | Self::ZeroW
            | Self::TooFewCorners { .. }
            | Self::BadCorner { .. } => {
                "fix or delete that line of the file (the message quotes what is wrong)"
            }
        }
    }
}

impl fmt::Display for ObjProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotUtf8 => write!(f, "the file is not UTF-8 text"),
            Self::UnknownStatement { keyword } => {
                write!(f, "`{keyword}` is not an OBJ statement (garbage line?)")
            }
            Self::WrongValueCount { keyword, found } => {
                write!(f, "`{keyword}` line has {found} values")
            }
            Self::BadNumber { keyword, text } => {
                write!(f, "`{keyword}` line: `{text}` is not a number")
            }
            Self::NumberOverflow { keyword, text } => write!(
                f,
                "`{keyword}` line: `{text}` overflows (above 1.8e308, the largest f64)"
            ),
            Self::ZeroW => write!(f, "`v` line has w = 0 (a point at infinity)"),
            Self::TooFewCorners { found } => {
                write!(f, "face has {found} corner(s); a face needs at least 3")
            }
            Self::BadCorner { token } => write!(
                f,
                "face corner `{token}` is not v, v/vt, v//vn or v/vt/vn with integer indices"
            ),
            Self::Miscounted => write!(f, "the reader's element count disagrees with its parse"),
            Self::IndexZero { what } => {
                write!(f, "{what} index 0 (OBJ indices start at 1)")
            }
            Self::IndexOutOfRange { what, index, count } => {
                write!(f, "{what} index {index} is out of range ({count} defined)")
            }
        }
    }
}

/// Why a file's texture coordinates are not one per vertex.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum UvProblem {
    /// The file has no texture coordinates (no `vt` in the faces, no `TEXCOORD_0`).
    Absent,
    /// Some face corners (or glTF primitives) have texture coordinates and some do not.
    Missing {
        /// The first corner's face line (OBJ) or primitive vertex (glTF) without one.
        origin: Origin,
    },
    /// A vertex has two different texture coordinates: the map is cut (a seam) there.
    Seam {
        /// 0-based mesh vertex.
        vertex: usize,
        /// Where the second, different texture coordinate is given.
        origin: Origin,
        /// Where the first one is given.
        first: Origin,
    },
}

impl UvProblem {
    /// The file place this problem points at, if any.
    pub fn origin(&self) -> Option<&Origin> {
        match self {
            Self::Absent => None,
            Self::Missing { origin } | Self::Seam { origin, .. } => Some(origin),
        }
    }
}

impl fmt::Display for UvProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Absent => write!(f, "the file has no texture coordinates"),
            Self::Missing { .. } => write!(
                f,
                "a face corner has no texture coordinate while others have one"
            ),
            Self::Seam { vertex, first, .. } => write!(
                f,
                "vertex {vertex} gets a second, different texture coordinate (first at {first}): \
                 the map has a seam, not one texture coordinate per vertex"
            ),
        }
    }
}

/// What is wrong with the data handed to a writer.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum WriteProblem {
    /// The number of texture coordinates differs from the number of vertices.
    UvCount {
        /// Number of vertices.
        expected: usize,
        /// Number of texture coordinates given.
        found: usize,
    },
    /// A face refers to a vertex that does not exist.
    FaceIndex {
        /// 0-based face.
        face: usize,
        /// The index found.
        index: u32,
        /// Number of vertices.
        vertex_count: usize,
    },
    /// A coordinate or texture coordinate is NaN or infinite (or, for glTF, outside the
    /// f32 range).
    NonFinite {
        /// 0-based vertex.
        vertex: usize,
        /// The value.
        value: f64,
    },
    /// A seamed map has not one triple of texture-coordinate indices per face.
    CornerFaceCount {
        /// Number of faces of the mesh.
        expected: usize,
        /// Number of index triples given.
        found: usize,
    },
    /// A face corner refers to a texture coordinate that does not exist.
    TexcoordIndex {
        /// 0-based face.
        face: usize,
        /// The index found.
        index: u32,
        /// Number of texture coordinates.
        count: usize,
    },
    /// More data than the format can index (glTF byte lengths are u32 in GLB).
    TooLarge,
    /// The output format cannot hold this (texture coordinates in a GIfTI or FreeSurfer
    /// surface, anything in STL or OFF, data arrays outside GIfTI).
    NotWritable {
        /// The format's extension.
        format: &'static str,
        /// What it cannot hold, and what to write instead.
        what: &'static str,
    },
    /// No vertex or no triangle: glTF accessors cannot be empty.
    Empty,
}

impl fmt::Display for WriteProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UvCount { expected, found } => write!(
                f,
                "{found} texture coordinates for {expected} vertices (need one per vertex)"
            ),
            Self::FaceIndex {
                face,
                index,
                vertex_count,
            } => write!(
                f,
                "face {face} refers to vertex {index}, but there are only {vertex_count} vertices"
            ),
            Self::NonFinite { vertex, value } => write!(
                f,
                "vertex {vertex} has a value that cannot be written ({value})"
            ),
            Self::CornerFaceCount { expected, found } => write!(
                f,
                "{found} texture-coordinate triples for {expected} faces (need one per face)"
            ),
            Self::TexcoordIndex { face, index, count } => write!(
                f,
                "face {face} refers to texture coordinate {index}, but there are only {count}"
            ),
            Self::TooLarge => write!(f, "the mesh is too large for the format"),
            Self::NotWritable { format, what } => {
                write!(f, "a .{format} file cannot hold {what}")
            }
            Self::Empty => write!(f, "glTF needs at least one vertex and one triangle"),
        }
    }
}

/// The mesh element a [`MeshError`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Element {
    Vertex(usize),
    Face(usize),
}

/// The element a [`MeshError`] names. For a non-manifold edge, the third face on the edge
/// (the first one too many), or the first if the list is shorter.
pub(crate) fn mesh_error_element(error: &MeshError) -> Option<Element> {
    match error {
        MeshError::NonFiniteCoordinate { vertex, .. }
        | MeshError::UnreferencedVertex { vertex, .. }
        | MeshError::NonManifoldVertex { vertex, .. } => Some(Element::Vertex(*vertex)),
        MeshError::IndexOutOfRange { face, .. }
        | MeshError::RepeatedVertexInFace { face, .. }
        | MeshError::ZeroAreaFace { face, .. }
        | MeshError::DuplicateFace { face, .. }
        | MeshError::InconsistentOrientation { face, .. }
        | MeshError::NonOrientable { face, .. } => Some(Element::Face(*face)),
        MeshError::NonManifoldEdge { faces, .. } => {
            faces.get(2).or(faces.first()).map(|&f| Element::Face(f))
        }
        _ => None,
    }
}

/// `:LINE` for an OBJ line (as in `file.obj:12`), ` (mesh m, primitive p, ...)` for glTF.
fn origin_suffix(origin: Option<&Origin>) -> String {
    match origin {
        Some(Origin::Line(line)) => format!(":{line}"),
        Some(o) => format!(" ({o})"),
        None => String::new(),
    }
}

fn gltf_place(mesh: Option<usize>, primitive: Option<usize>, accessor: Option<usize>) -> String {
    let mut s = String::new();
    if let Some(m) = mesh {
        s.push_str(&format!("mesh {m}, "));
    }
    if let Some(p) = primitive {
        s.push_str(&format!("primitive {p}, "));
    }
    if let Some(a) = accessor {
        s.push_str(&format!("accessor {a}, "));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One error of every variant (and every [`ObjProblem`]). The exhaustive `match` in
    /// [`IoError::hint`] makes a new variant fail to compile without a hint; this list makes
    /// it fail this test until it is added here.
    fn one_of_each() -> Vec<IoError> {
        let path = || PathBuf::from("m.obj");
        let os = || std::io::Error::other("denied");
        let line = |problem| IoError::ObjSyntax {
            path: path(),
            line: 3,
            problem,
        };
        vec![
            IoError::Read {
                path: path(),
                source: os(),
            },
            IoError::Write {
                path: path(),
                source: os(),
            },
            IoError::UnknownFormat { path: path() },
            line(ObjProblem::NotUtf8),
            line(ObjProblem::UnknownStatement {
                keyword: "x".into(),
            }),
            line(ObjProblem::WrongValueCount {
                keyword: "v".into(),
                found: 2,
            }),
            line(ObjProblem::BadNumber {
                keyword: "v".into(),
                text: "x".into(),
            }),
            line(ObjProblem::NumberOverflow {
                keyword: "v".into(),
                text: "1e400".into(),
            }),
            line(ObjProblem::ZeroW),
            line(ObjProblem::TooFewCorners { found: 2 }),
            line(ObjProblem::BadCorner { token: "1/".into() }),
            line(ObjProblem::IndexZero { what: "vertex" }),
            line(ObjProblem::IndexOutOfRange {
                what: "vertex",
                index: 9,
                count: 3,
            }),
            line(ObjProblem::Miscounted),
            IoError::InvalidMesh {
                path: path(),
                origin: None,
                source: MeshError::NoVertices,
            },
            IoError::NotPerVertexUv {
                path: path(),
                problem: UvProblem::Absent,
            },
            IoError::Gltf {
                path: path(),
                source: gltf::Error::UnsupportedScheme,
            },
            IoError::GltfData {
                path: path(),
                mesh: Some(0),
                primitive: Some(1),
                accessor: None,
                problem: "bad".into(),
                hint: GLTF_HINT,
            },
            IoError::BadWriteInput {
                path: path(),
                problem: WriteProblem::Empty,
            },
            IoError::Malformed {
                path: path(),
                format: crate::Format::Ply,
                place: Place::Byte {
                    offset: 9,
                    element: "vertex 0".into(),
                },
                problem: "truncated".into(),
                hint: "export the file again; it is cut short or damaged",
            },
        ]
    }

    #[test]
    fn every_error_names_its_file_and_has_a_hint() {
        let errors = one_of_each();
        for e in &errors {
            let (msg, hint) = (e.to_string(), e.hint());
            assert!(msg.starts_with("m.obj"), "{msg}");
            // a sentence of advice, not a restatement of the message
            assert!(
                hint.len() > 30 && !hint.ends_with('.'),
                "{msg}: hint `{hint}`"
            );
            assert!(!msg.contains(hint), "{msg}");
        }
        // every variant is in the list (a new variant breaks this match's compilation)
        let kinds: std::collections::BTreeSet<usize> = errors.iter().map(variant).collect();
        assert_eq!(kinds.len(), VARIANTS, "one IoError per variant");
    }

    const VARIANTS: usize = 10;

    fn variant(e: &IoError) -> usize {
        match e {
            IoError::Read { .. } => 0,
            IoError::Write { .. } => 1,
            IoError::UnknownFormat { .. } => 2,
            IoError::ObjSyntax { .. } => 3,
            IoError::InvalidMesh { .. } => 4,
            IoError::NotPerVertexUv { .. } => 5,
            IoError::Gltf { .. } => 6,
            IoError::GltfData { .. } => 7,
            IoError::BadWriteInput { .. } => 8,
            IoError::Malformed { .. } => 9,
        }
    }
}
