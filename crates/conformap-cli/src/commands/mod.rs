//! One module per subcommand. The map commands (`disk`, `sphere`, `mobius`, `global`) implement
//! [`crate::pipeline::MapCommand`]; `info` and `metrics` only read and describe;
//! `render` draws any map; `batch` runs a map command over many meshes.

pub mod batch;
pub mod batch_inputs;
pub mod disk;
pub mod disk_holes;
pub mod global;
pub mod global_topology;
pub mod info;
pub mod metrics;
pub mod mobius;
pub mod morph;
pub mod param;
pub mod render;
pub mod sphere;
