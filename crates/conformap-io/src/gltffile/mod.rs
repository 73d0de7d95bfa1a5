//! glTF 2.0 and GLB: reading via `gltf` (with checked accessors and welding), and writing.

mod accessor;
mod buffers;
mod container;
mod read;
mod weld;
mod write;

pub(crate) use read::read_gltf_raw;
pub(crate) use weld::{face_origin, vertex_origin, PrimRange};
pub(crate) use write::encode_gltf;
