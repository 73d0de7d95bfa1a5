//! The command line: the subcommands and their dispatch.

use clap::{Parser, Subcommand};

use crate::commands::{batch::BatchArgs, render::RenderArgs};
use crate::commands::{disk::DiskArgs, info::InfoArgs, metrics::MetricsArgs};
use crate::commands::{
    global::GlobalArgs, mobius::MobiusArgs, morph::MorphArgs, sphere::SphereArgs,
};
use crate::failure::Failure;
use crate::pipeline::{run_map, Outcome};

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

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Topology and validity of a mesh.
    Info(InfoArgs),
    /// Conformal map of a disk-like mesh (one boundary loop) onto the unit disk.
    Disk(DiskArgs),
    /// Judge a planar map of a mesh (ours or another tool's).
    Metrics(MetricsArgs),
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
    /// Run `disk` or `sphere` over many meshes: one JSON line per input, a summary line.
    Batch(BatchArgs),
    /// Morph through two or more disk-like surfaces with landmarks (CEM §6): S1's mesh at
    /// every frame, on each key surface at its key frame.
    Morph(MorphArgs),
}

impl Command {
    /// Runs the subcommand.
    ///
    /// # Errors
    /// The command's [`Failure`], which says the exit code; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        match self {
            Self::Info(args) => crate::commands::info::run(args),
            Self::Metrics(args) => crate::commands::metrics::run(args),
            Self::Disk(args) => run_map(args),
            Self::Sphere(args) => run_map(args),
            Self::Mobius(args) => run_map(args),
            Self::Global(args) => run_map(args),
            Self::Render(args) => crate::commands::render::run(args),
            Self::Batch(args) => crate::commands::batch::run(args),
            Self::Morph(args) => crate::commands::morph::run(args),
        }
    }
}
