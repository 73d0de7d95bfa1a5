//! `conformap atlas`: a texture atlas of any mesh. The clap arguments and their job; the
//! job (crate `conformap`) does the work.

use clap::{Args, ValueEnum};
use conformap::jobs::atlas::{AtlasJob, ConeChoice, Polish, DEFAULT_MAX_AREA_SPREAD};

use crate::args::{InputArgs, OutputArgs};

/// Arguments of `conformap atlas`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): one `vt` per face corner (`f v/vt`, the `v` lines in the input's order), every chart packed into the unit square with one texel density (`--pack none`: the charts in their own coordinates; `--scale per-chart`: one density per chart); `--flat`: the atlas as a flat mesh.\n\nCone file (`--cones FILE`): one `<vertex> <cone angle in degrees>` per line, 0-based vertices in the order of the `v` lines, `#` comments; interior vertices only, angles in (0, 720]; on a closed genus-0 component the curvatures 360 − angle must add up to 720 (Gauss–Bonnet). The report's atlas.cone_list holds a run's cones in that form."
)]
pub struct AtlasArgs {
    /// The mesh: any number of components, each a valid surface of any topology; a
    /// non-manifold vertex or edge is split there (the report's `non_manifold` says where,
    /// `--vertex-map` writes each output vertex's input vertex).
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` holds one texture coordinate per face corner (`f v/vt`, the `v`
    /// lines in the input's order), all in the unit square; `--flat` the atlas as a flat mesh.
    #[command(flatten)]
    pub output: OutputArgs,
    /// N: cones per closed component (and per component with handles), placed
    /// automatically; default: 8 there, 0 on a genus-0 component with boundary. `auto`: as
    /// many per component as bring its area spread to --max-area-spread (at most 32).
    /// FILE: the cones as given, `<vertex> <cone angle in degrees>` per line.
    #[arg(long, value_name = "N|auto|FILE")]
    pub cones: Option<String>,
    /// With --cones auto: the area spread (sd of the log area ratio) to reach on each
    /// component.
    #[arg(long, value_name = "S", default_value_t = DEFAULT_MAX_AREA_SPREAD)]
    pub max_area_spread: f64,
    /// `square`: charts turned and packed into the unit square; `none`: charts kept in
    /// their own coordinates (about 3D units), side by side, `vt` outside `[0,1]²`.
    #[arg(long, value_enum, default_value = "square")]
    pub pack: Pack,
    /// `uniform`: one texel density for the whole atlas; `per-chart`: every component's
    /// charts scaled together to the same texture area (a density per component).
    #[arg(long, value_enum, default_value = "uniform")]
    pub scale: Scale,
    /// Texels a side of the texture the margin is measured in.
    #[arg(long, default_value_t = 1024)]
    pub resolution: usize,
    /// Empty texels between charts (half of it at the square's edges).
    #[arg(long, default_value_t = 2.0)]
    pub margin: f64,
    /// Seamless: cone angles multiples of 90° and every seam a rotation by a multiple of
    /// 90° plus a translation (genus ≥ 1: a holomorphic 1-form's layout, whose seams are
    /// translations); charts packed with quarter turns only. Costs area distortion.
    #[arg(long)]
    pub seamless: bool,
    /// Which charts to polish after they are flattened: one Gauss–Newton step on the area
    /// and angle distortion with the seams held rigid (lower area spread and angle
    /// distortion, one more factorization per chart; with --seamless the seams keep their
    /// quarter turns). `auto`: charts whose cone metric spreads 0.5 or more, on components
    /// of up to 20,000 vertices (where it pays and costs little); `always` (bare
    /// `--polish`): every chart with cones; `never`.
    #[arg(
        long,
        value_enum,
        value_name = "WHEN",
        default_value = "auto",
        num_args = 0..=1,
        require_equals = true,
        default_missing_value = "always"
    )]
    pub polish: PolishWhen,
}

/// `--pack`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Pack {
    /// Packed into the unit square.
    Square,
    /// Kept in their own coordinates.
    None,
}

/// `--polish`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PolishWhen {
    /// Where it pays and costs little.
    Auto,
    /// Every chart with cones.
    Always,
    /// No chart.
    Never,
}

/// `--scale`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Scale {
    /// One texel density.
    Uniform,
    /// One density per chart.
    PerChart,
}

impl AtlasArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> AtlasJob {
        let mut job = AtlasJob::new(self.input.to_options(), self.output.to_options());
        match self.cones.as_deref() {
            None => {}
            Some("auto") => job.cone_choice = ConeChoice::Auto,
            Some(n) => match n.parse::<usize>() {
                Ok(count) => job.cones = Some(count),
                Err(_) => job.cone_choice = ConeChoice::File(n.into()),
            },
        }
        job.max_area_spread = self.max_area_spread;
        job.pack_none = self.pack == Pack::None;
        job.per_chart_scale = self.scale == Scale::PerChart;
        job.resolution = self.resolution;
        job.margin = self.margin;
        job.seamless = self.seamless;
        job.polish = match self.polish {
            PolishWhen::Auto => Polish::Auto,
            PolishWhen::Always => Polish::Always,
            PolishWhen::Never => Polish::Never,
        };
        job
    }
}
