//! `conformap metrics`: judge a map of a mesh.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::metrics::MetricsJob;

/// Arguments of `conformap metrics`.
#[derive(Debug, Args)]
pub struct MetricsArgs {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (read as
    /// u = 2·vt_x − 1, v = 2·vt_y − 1, the inverse of what `disk` writes), a seamed map
    /// with texture coordinates per face corner (`f v/vt`, as `global` writes; read as
    /// (u, v) = vt, no circle fits), or a flat mesh without texture coordinates whose
    /// (x, y) are the map. A sphere map (`sphere --flat`'s unit-sphere points, or `sphere
    /// -o`'s texture coordinates of a closed genus-0 mesh) is measured on the sphere; a map
    /// on its own refinement of the mesh (`global -o` where it split boundary chords) on
    /// that refinement.
    pub param: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

impl MetricsArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> MetricsJob {
        MetricsJob::new(&self.mesh, &self.param).with_json(self.json)
    }
}
