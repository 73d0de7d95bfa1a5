//! `conformap global`: global conformal map by a holomorphic 1-form.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::global::{Conjugate, FormObjective, GlobalJob};

use crate::args::{choice, InputArgs, OutputArgs};

/// Arguments of `conformap global`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): one `vt` per face corner (`f v/vt`; glTF: vertices split along the seams), the layout fitted into the unit square: vt = (layout − uv_offset) · uv_scale, both in the report's `global` section; across a seam the two sides differ by a period (a translation). `--flat`: the layout itself as positions (u, v, 0)."
)]
pub struct GlobalArgs {
    /// The mesh (connected; genus ≥ 1, or ≥ 2 boundary loops) and how to read it.
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` the mesh with one `vt` per corner (`f v/vt`; glTF: vertices split
    /// along the seams); `--flat` the fundamental domain with the layout as positions.
    #[command(flatten)]
    pub output: OutputArgs,
    /// The holomorphic basis form to lay out (0 ≤ K < 2g), overriding `--objective`.
    #[arg(long, value_name = "K")]
    pub form: Option<usize>,
    /// The conjugate forms.
    #[arg(long, value_parser = choice::<Conjugate>(), default_value_t = Conjugate::Nearest)]
    pub conjugate: Conjugate,
    /// Which form to lay out (Jin et al. §3.2–3.3, §3.6).
    #[arg(long, value_parser = choice::<FormObjective>(), default_value_t = FormObjective::Uniform)]
    pub objective: FormObjective,
    /// The faces to emphasize or de-emphasize: one 0-based face index per line, `#`
    /// comments (the format `mobius --region` reads). Needed by `--objective emphasize` and
    /// `de-emphasize`.
    #[arg(long, value_name = "FACES.txt")]
    pub region: Option<PathBuf>,
    /// The vertices (0-based, comma-separated) where `--objective zeros` puts the form's
    /// zeros.
    #[arg(long, value_name = "V1,V2,…", value_delimiter = ',', num_args = 1..)]
    pub zeros: Option<Vec<usize>>,
    /// Random starts of the uniform search (besides the 2g basis forms). Default: the
    /// library's.
    #[arg(long, value_name = "N")]
    pub starts: Option<usize>,
    /// Root vertex of the homology generators' shortest-path tree (0-based). Default 0.
    #[arg(long, value_name = "V")]
    pub root: Option<usize>,
    /// Topological optimization (Jin et al. §3.5): slit the surface at the extreme points
    /// of its map (limb tips) and map the slit surface by its most uniform form, greedily;
    /// returns the most uniform layout seen, the starting map included. Also takes closed
    /// genus-0 meshes (the starting map is then the uniform-Möbius sphere map) and disks
    /// (the uniform-Möbius disk map).
    #[arg(long)]
    pub topology_opt: bool,
    /// Most slits of `--topology-opt`. Default: the library's (16).
    #[arg(long, value_name = "N", requires = "topology_opt")]
    pub max_slits: Option<usize>,
    /// Slit length of `--topology-opt` as a fraction of the bounding-box diagonal.
    /// Default: the library's (0.04).
    #[arg(long, value_name = "F", requires = "topology_opt")]
    pub slit_length: Option<f64>,
}

impl GlobalArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> GlobalJob {
        let mut job = GlobalJob::new(self.input.to_options(), self.output.to_options())
            .with_objective(self.objective)
            .with_topology_opt(self.topology_opt);
        job.form = self.form;
        job.conjugate = self.conjugate;
        job.region = self.region.clone();
        job.zeros = self.zeros.clone();
        job.starts = self.starts;
        job.root = self.root;
        job.max_slits = self.max_slits;
        job.slit_length = self.slit_length;
        job
    }
}
