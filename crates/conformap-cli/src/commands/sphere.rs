//! `conformap sphere`: conformal map of a closed genus-0 mesh onto the unit sphere.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use clap::Args;
use conformap::jobs::sphere::{SphereJob, SphereMobius};

use crate::args::{choice, InputArgs, OutputArgs};

/// Arguments of `conformap sphere`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): the equirectangular (longitude/latitude) projection of the sphere point, u = (atan2(y, x) + π)/2π, v = (asin z + π/2)/π, one per face corner: a face crossing the seam meridian gets its corners' u ± 1 so that u is continuous within it, a pole vertex takes the u of each of its faces; `--flat`: the unit-sphere points."
)]
pub struct SphereArgs {
    /// The mesh (closed, connected, genus 0) and how to read it.
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` holds the equirectangular projection of the sphere point,
    /// u = (atan2(y, x) + π)/2π, v = (asin z + π/2)/π, one per face corner (split along
    /// the meridian u = 0 ≡ 1, so no face spans the texture); `--flat` the unit-sphere points.
    #[command(flatten)]
    pub output: OutputArgs,
    /// Möbius normalization of the map.
    #[arg(long, value_parser = choice::<SphereMobius>(), default_value_t = SphereMobius::None)]
    pub mobius: SphereMobius,
}

impl SphereArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> SphereJob {
        SphereJob::new(self.input.to_options(), self.output.to_options()).with_mobius(self.mobius)
    }
}
