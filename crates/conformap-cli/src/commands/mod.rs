//! One module per subcommand: its clap arguments and their conversion into the job of
//! crate `conformap` (`to_job`), which does the work.

pub mod atlas;
pub mod batch;
pub mod disk;
pub mod flatten;
pub mod global;
pub mod info;
pub mod metrics;
pub mod mobius;
pub mod morph;
pub mod render;
pub mod sphere;
