//! glTF 2.0 and GLB: reading via `gltf` (with checked accessors and welding), and writing.

mod accessor;
mod buffers;
mod container;
mod morph;
mod read;
mod weld;
mod write;

pub use morph::{encode_morph_glb, write_morph_glb, MorphGlb};
pub(crate) use read::read_gltf_raw;
pub(crate) use write::encode_gltf;
