//! The command line: the subcommands, their jobs and their dispatch.

use std::ffi::OsString;

use clap::{Parser, Subcommand};
use conformap::{BatchJob, BatchTemplate, Choice, Failure, MapJob, Outcome};

use crate::commands::atlas::AtlasArgs;
use crate::commands::flatten::FlattenArgs;
use crate::commands::{batch::BatchArgs, render::RenderArgs};
use crate::commands::{disk::DiskArgs, info::InfoArgs, metrics::MetricsArgs};
use crate::commands::{
    global::GlobalArgs, mobius::MobiusArgs, morph::MorphArgs, sphere::SphereArgs,
};

/// Conformal (angle-preserving) parameterization of triangle meshes.
#[derive(Debug, Parser)]
#[command(name = "conformap", version, about, long_about = None)]
pub struct Cli {
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
    /// No progress display and no summary line on stderr (errors are still printed).
    #[arg(long, short, global = true)]
    pub quiet: bool,
}

impl Cli {
    /// The parser: clap's, with a negative number after a flag taken as its value, so that
    /// `--max-iter -1` is refused by that flag's own check (exit 2, naming it) rather than
    /// with clap's tip to write `-- -1`, which does not work for a flag's value.
    pub fn command_line() -> clap::Command {
        <Self as clap::CommandFactory>::command()
            .mut_subcommands(|c| c.allow_negative_numbers(true))
    }

    /// Parses `argv` with [`Cli::command_line`].
    ///
    /// # Errors
    /// clap's usage error (printed by `clap::Error::exit`, exit 2).
    pub fn try_parse_args<I, T>(argv: I) -> Result<Self, clap::Error>
    where
        I: IntoIterator<Item = T>,
        T: Into<OsString> + Clone,
    {
        let mut matches = Self::command_line().try_get_matches_from(argv)?;
        <Self as clap::FromArgMatches>::from_arg_matches_mut(&mut matches)
    }
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Topology and validity of a mesh.
    Info(InfoArgs),
    /// Conformal map of a disk-like mesh (one boundary loop) onto the unit disk.
    Disk(DiskArgs),
    /// Judge a map of a mesh (ours or another tool's): planar, seamed, or on the sphere.
    Metrics(MetricsArgs),
    /// Boundary first flattening of a mesh with boundary: a free boundary (lengths kept,
    /// the least area distortion), a rectangle or polygon with exact corners, a circle, or
    /// given boundary scale factors or angles.
    Flatten(FlattenArgs),
    /// A texture atlas of any mesh: every component charted (closed ones cut through 8
    /// cones and their handles), charts split where they would overlap, all packed into the
    /// unit square with one texel density; one `vt` per face corner.
    Atlas(AtlasArgs),
    /// Conformal map of a closed genus-0 mesh onto the unit sphere.
    Sphere(SphereArgs),
    /// Optimal Möbius transformation of a disk or sphere map (uniformity or emphasized area).
    Mobius(MobiusArgs),
    /// Global conformal map of a surface with handles (genus ≥ 1) or several boundary
    /// loops by a holomorphic 1-form: a seamed layout, one `vt` per corner.
    Global(GlobalArgs),
    /// Draw a map of a mesh (ours or another tool's): the surface with a checkerboard, the
    /// flat map coloured by distortion, or the angle-distortion histogram.
    Render(RenderArgs),
    /// Run `disk`, `sphere`, `global`, `flatten` or `atlas` over many meshes: one JSON line
    /// per input, a summary line.
    Batch(BatchArgs),
    /// Morph through two or more disk-like surfaces with landmarks (CEM §6): S1's mesh at
    /// every frame, on each key surface at its key frame.
    Morph(MorphArgs),
}

impl Command {
    /// Runs the subcommand's job.
    ///
    /// # Errors
    /// The job's [`Failure`], which says the exit code; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        match self {
            Self::Info(args) => args.to_job().run(),
            Self::Metrics(args) => args.to_job().run(),
            Self::Disk(args) => args.to_job().run(),
            Self::Flatten(args) => args.to_job().run(),
            Self::Atlas(args) => args.to_job().run(),
            Self::Sphere(args) => args.to_job().run(),
            Self::Mobius(args) => args.to_job().run(),
            Self::Global(args) => args.to_job().run(),
            Self::Render(args) => args.to_job().run(),
            Self::Batch(args) => conformap::batch::run(&batch_job(args)?),
            Self::Morph(args) => args.to_job().run(),
        }
    }
}

/// The job of `conformap batch`: the options after `--` parsed as the command's own (so
/// a batch input runs exactly as that command would).
///
/// # Errors
/// Usage: options that do not fit the command.
pub fn batch_job(args: &BatchArgs) -> Result<BatchJob, Failure> {
    let name = args.command.name();
    let mut argv: Vec<OsString> = vec!["conformap".into(), name.into(), "MESH".into()];
    argv.extend(["-o".into(), "OUT".into()]);
    argv.extend(args.options.iter().map(Into::into));
    let cli = Cli::try_parse_args(&argv).map_err(|e| {
        Failure::Usage(format!(
            "the options after -- do not fit `conformap {name}`: {}",
            e.to_string()
                .lines()
                .next()
                .unwrap_or_default()
                .trim_start_matches("error: ")
        ))
    })?;
    let template = match &cli.command {
        Command::Disk(a) => BatchTemplate::Disk(a.to_job()),
        Command::Sphere(a) => BatchTemplate::Sphere(a.to_job()),
        Command::Global(a) => BatchTemplate::Global(a.to_job()),
        Command::Flatten(a) => BatchTemplate::Flatten(a.to_job()),
        Command::Atlas(a) => BatchTemplate::Atlas(a.to_job()),
        _ => return Err(Failure::Usage(format!("`{name}` cannot run in a batch"))),
    };
    let mut job = BatchJob::new(template, &args.out_dir, args.inputs.clone()).with_jobs(args.jobs);
    job.skip_existing = args.skip_existing;
    job.report = args.report.clone();
    job.ext = args.ext.clone();
    job.png = args.png;
    job.max_memory = args.max_memory;
    Ok(job)
}
