//! `conformap mobius`: optimal Möbius transformation of a disk or sphere map.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::mobius::{Domain, MobiusJob, Objective, DEFAULT_MAX_AREA_SCALE};

use crate::args::{choice, InputArgs, OutputArgs};

/// Arguments of `conformap mobius`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): as the command that made the map writes them: disk, vt = ((u+1)/2, (v+1)/2); sphere, the equirectangular projection u = (atan2(y, x) + π)/2π, v = (asin z + π/2)/π, one per face corner, split along the seam meridian; `--flat`: (u, v, 0) or the unit-sphere points."
)]
pub struct MobiusArgs {
    /// The 3D mesh and how to read it.
    #[command(flatten)]
    pub input: InputArgs,
    /// The map. Disk: texture coordinates (u = 2·vt_x − 1, v = 2·vt_y − 1, as `disk` writes)
    /// or a flat mesh whose (x, y) are the map. Sphere: a mesh whose positions are the
    /// unit-sphere points (`sphere --flat`), or else equirectangular texture coordinates
    /// (as `sphere -o` writes).
    pub param: PathBuf,
    /// The outputs: `-o` holds the moved map as texture coordinates (disk:
    /// ((u+1)/2, (v+1)/2); sphere: equirectangular, as `sphere` writes).
    #[command(flatten)]
    pub output: OutputArgs,
    /// Domain of the map.
    #[arg(long, value_parser = choice::<Domain>())]
    pub domain: Domain,
    /// Energy to optimize.
    #[arg(long, value_parser = choice::<Objective>())]
    pub objective: Objective,
    /// Faces to emphasize: a text file with one 0-based face index per line (blank lines and
    /// lines starting with # are skipped). Required with --objective emphasize.
    #[arg(long)]
    pub region: Option<PathBuf>,
    /// Largest area magnification the emphasizing Möbius map may apply (> 1; only for
    /// --objective emphasize): the share of an emphasized region has no maximum, it tends to
    /// 100 % as the map degenerates.
    #[arg(long, default_value_t = DEFAULT_MAX_AREA_SCALE)]
    pub max_area_scale: f64,
}

impl MobiusArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> MobiusJob {
        let mut job = MobiusJob::new(
            self.input.to_options(),
            &self.param,
            self.output.to_options(),
            self.domain,
            self.objective,
        );
        job.region = self.region.clone();
        job.max_area_scale = self.max_area_scale;
        job
    }
}
