//! Mesh file I/O for conformap: OBJ, glTF/GLB, PLY, STL, OFF, GIfTI and FreeSurfer readers
//! and writers with errors that name the file and the place in it.
//!
//! Depends on `conformap-mesh` (every mesh read passes [`TriMesh::try_new`]), `fast-float2`,
//! `memchr`, `rayon`, `ryu`, `itoa`, `gltf`, `serde_json`, `quick-xml`, `base64`, `flate2`
//! and `thiserror`; never does any maths on the mesh and never prints.
//!
//! - [`read_mesh`] / [`read_mesh_from_bytes`]: OBJ (our own parser, in parallel chunks, with
//!   correctly rounded numbers, line numbers and checked indices), glTF and GLB (via `gltf`, with checked accessors, node
//!   transforms and welding of seam-split vertices). They return a [`LoadedMesh`]: the
//!   validated mesh, per-vertex texture coordinates if the file has them, and a
//!   [`SourceInfo`] mapping mesh vertices and faces back to the file. PLY (ASCII and
//!   binary), STL (welded), OFF, GIfTI surfaces and FreeSurfer surfaces (found by their
//!   magic when the name has no extension) are read by our own code (GIfTI's XML with
//!   `quick-xml`); their errors are [`IoError::Malformed`] with a [`Place`].
//! - [`write_mesh_with_uv`]: the mesh with one texture coordinate per vertex;
//!   [`write_mesh_with_corner_uv`]: the mesh with a seamed map ([`CornerUv`], `f v/vt`);
//!   [`write_flat`]: any points and triangles (a flat or spherical map); [`ObjFrames`]:
//!   many frames of one set of triangles (a morph), the face lines formatted once. PLY
//!   takes the map per vertex or per corner; GIfTI and FreeSurfer take surfaces (a sphere
//!   map at radius 100), [`write_vertex_data`] per-vertex overlays. Output appears complete
//!   or not at all.
//! - [`read_raw_mesh`] / [`read_raw_mesh_from_bytes`]: the same parsing without validation,
//!   for callers that repair first ([`RawMesh::validate`] is the rest of [`read_mesh`]).
//! - [`IoError`]: the one error type; variants name the file and the line ([`Origin`]) or
//!   glTF mesh/primitive/accessor, buffer or GLB chunk; [`IoError::hint`] says what to do.
//!
//! Vertex order is kept: for OBJ, mesh vertex `k` is the file's `k`-th `v` line, so `vt`
//! index `k` of an output belongs to input vertex `k`. OBJ numbers are written in Rust's
//! shortest round-trip form, so OBJ → OBJ is exact; glTF stores f32, so positions and
//! texture coordinates pass through f32 there.
//!
//! # Example
//! ```
//! use conformap_io::{read_mesh_from_bytes, Format, IoError, ObjProblem};
//!
//! // a unit square as one quad (fan-triangulated), with per-vertex texture coordinates
//! let obj = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n\
//!             vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
//!             f 1/1 2/2 3/3 4/4\n";
//! let loaded = read_mesh_from_bytes(obj, Format::Obj)?;
//! assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
//! assert_eq!(loaded.per_vertex_uv()?[2], [1.0, 1.0]);
//!
//! // errors name the line
//! let err = read_mesh_from_bytes(b"v 0 0 0\nf 1 2 0\n", Format::Obj).unwrap_err();
//! assert!(matches!(
//!     err,
//!     IoError::ObjSyntax { line: 2, problem: ObjProblem::IndexOutOfRange { index: 2, .. }, .. }
//! ));
//! # Ok::<(), IoError>(())
//! ```
//!
//! [`TriMesh::try_new`]: conformap_mesh::TriMesh::try_new

mod api;
mod atomic;
mod coincident;
mod corner_uv;
mod cursor;
mod error;
mod frames;
mod freesurfer;
mod gifti;
mod gltffile;
mod loaded;
mod objfile;
mod off_keyword;
mod offfile;
mod origins;
mod plyfile;
mod raw;
mod read;
mod stlfile;

pub use api::{
    read_mesh, read_mesh_from_bytes, write_flat, write_flat_like, write_mesh_with_corner_uv,
    write_mesh_with_uv, write_vertex_data, SPHERE_RADIUS, UNIT_SPHERE_TOLERANCE,
};
pub use coincident::{coincident_vertices, weld_coincident, Welded};
pub use corner_uv::CornerUv;
pub use error::{IoError, ObjProblem, Origin, Place, UvProblem, WriteProblem};
pub use frames::ObjFrames;
pub use gltffile::{encode_morph_glb, write_morph_glb, MorphGlb};
pub use loaded::{
    CoordinateTransform, Format, LoadedMesh, SourceInfo, SurfaceMetadata, VertexText, NO_VERTEX,
    READ_PEAK_BYTES_PER_FILE_BYTE,
};
pub use raw::RawMesh;
pub use read::{read_raw_mesh, read_raw_mesh_from_bytes};

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctest;
