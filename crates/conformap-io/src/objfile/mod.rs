//! Wavefront OBJ: reading via `tobj` plus our own line scan, and writing.

mod read;
mod scan;
mod write;

pub(crate) use read::{read_obj, read_obj_raw};
pub(crate) use write::{encode_obj, encode_obj_with_uv};
