//! `conformap info`: topology and validity of a mesh.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::info::InfoJob;

/// Arguments of `conformap info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The mesh (.obj, .gltf, .glb).
    pub mesh: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Describe the mesh as `disk --repair` would map it (after the repairs it needs).
    #[arg(long)]
    pub repair: bool,
}

impl InfoArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> InfoJob {
        let mut job = InfoJob::new(&self.mesh).with_json(self.json);
        job.repair = self.repair;
        job
    }
}
