//! `conformap atlas`: a texture atlas of any mesh. The clap arguments and their job; the
//! job (crate `conformap`) does the work.

use clap::Args;
use conformap::jobs::atlas::AtlasJob;

use crate::args::{InputArgs, OutputArgs};

/// Arguments of `conformap atlas`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): one `vt` per face corner (`f v/vt`, the `v` lines in the input's order), every chart packed into the unit square with one texel density; `--flat`: the atlas as a flat mesh."
)]
pub struct AtlasArgs {
    /// The mesh: any number of components, each a valid manifold surface of any topology.
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` holds one texture coordinate per face corner (`f v/vt`, the `v`
    /// lines in the input's order), all in the unit square; `--flat` the atlas as a flat mesh.
    #[command(flatten)]
    pub output: OutputArgs,
    /// Cones per closed component (and per component with handles); default: 8 there, 0 on
    /// a genus-0 component with boundary.
    #[arg(long)]
    pub cones: Option<usize>,
    /// Texels a side of the texture the margin is measured in.
    #[arg(long, default_value_t = 1024)]
    pub resolution: usize,
    /// Empty texels between charts (half of it at the square's edges).
    #[arg(long, default_value_t = 2.0)]
    pub margin: f64,
}

impl AtlasArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> AtlasJob {
        let mut job = AtlasJob::new(self.input.to_options(), self.output.to_options());
        job.cones = self.cones;
        job.resolution = self.resolution;
        job.margin = self.margin;
        job
    }
}
