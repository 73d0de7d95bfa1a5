//! Wavefront OBJ: our own parallel reader (lines, chunked parsing, per-vertex `vt`) and
//! the writer.

mod lines;
mod parse;
mod read;
mod write;

pub(crate) use parse::decimal;
pub(crate) use read::read_obj_raw;
pub(crate) use write::{
    encode_obj, encode_obj_with_corner_uv, encode_obj_with_uv, face_lines, obj_header,
    vertex_lines, Encoded,
};
