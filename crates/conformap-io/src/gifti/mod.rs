//! GIfTI (`.gii`): surfaces read (`read.rs`, `decode.rs`) and written with per-vertex data
//! arrays (`write.rs`).

mod decode;
mod read;
mod write;

pub(crate) use read::read_gifti_raw;
pub(crate) use write::{encode_gifti_data, encode_gifti_surface};
