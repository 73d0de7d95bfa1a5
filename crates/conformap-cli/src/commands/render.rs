//! `conformap render`: a picture of a map.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::render::{ParamDomain, RenderColor, RenderJob, RenderView, DEFAULT_SIZE};

use crate::args::choice;

/// Arguments of `conformap render`.
#[derive(Debug, Clone, Args)]
pub struct RenderArgs {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (the -o of disk or
    /// sphere, or another tool's), or a flat mesh (the --flat of disk or sphere).
    pub param: PathBuf,
    /// The picture: .png (or .svg for --view histogram).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Which picture.
    #[arg(long, value_parser = choice::<RenderView>(), default_value_t = RenderView::Surface)]
    pub view: RenderView,
    /// What colours the faces (default: checker on the surface, angle on the map).
    #[arg(long, value_parser = choice::<RenderColor>())]
    pub color: Option<RenderColor>,
    /// Width and height in pixels (the histogram is 5/8 as high).
    #[arg(long, default_value_t = DEFAULT_SIZE,
          value_parser = clap::value_parser!(u32).range(16..=16384))]
    pub size: u32,
    /// Turn of the camera around the picture's up axis, degrees.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub azimuth: f64,
    /// Tilt of the camera over the object, degrees (positive looks down on it).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub elevation: f64,
    /// Where the map lands.
    #[arg(long, value_parser = choice::<ParamDomain>(), default_value_t = ParamDomain::Auto)]
    pub domain: ParamDomain,
}

impl RenderArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> RenderJob {
        let mut job = RenderJob::new(&self.mesh, &self.param, &self.output)
            .with_view(self.view)
            .with_size(self.size);
        job.color = self.color;
        job.azimuth = self.azimuth;
        job.elevation = self.elevation;
        job.domain = self.domain;
        job
    }
}
