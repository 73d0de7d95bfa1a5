//! One job per command. The map jobs ([`disk::DiskJob`], [`sphere::SphereJob`],
//! [`mobius::MobiusJob`], [`global::GlobalJob`]) implement [`crate::pipeline::MapJob`] and
//! run through [`crate::pipeline::run_map`]; [`info::InfoJob`] and [`metrics::MetricsJob`]
//! only read and describe; [`render::RenderJob`] draws any map; [`morph::MorphJob`] morphs
//! through key surfaces.

pub mod atlas;
pub mod disk;
pub mod disk_holes;
pub mod disk_tiny;
pub mod flatten;
pub mod global;
pub mod global_solved;
pub mod global_topology;
pub mod info;
pub mod metrics;
pub mod mobius;
pub mod morph;
mod morph_frames;
mod morph_input;
pub mod param;
pub mod param_match;
pub mod render;
pub mod sphere;
