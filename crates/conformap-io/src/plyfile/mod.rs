//! Stanford PLY: our own reader (ASCII, binary of either byte order; the header in
//! `header.rs`, the body in `read.rs`) and a binary writer (`write.rs`).

mod header;
mod read;
mod write;

pub(crate) use read::read_ply_raw;
pub(crate) use write::{encode_ply, PlyUv};
