//! The conformap command-line tool: conformal parameterization of triangle meshes over OBJ
//! and glTF.
//!
//! A thin layer over the library crates: argument checking, JSON reports, exit codes.
//! Exit codes: 0 success, 1 bad input, 2 usage error, 3 numerical failure.

mod commands;
mod failure;
mod report;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::commands::{disk::DiskArgs, info::InfoArgs, metrics::MetricsArgs};
use crate::commands::{mobius::MobiusArgs, sphere::SphereArgs};

/// Conformal (angle-preserving) parameterization of triangle meshes.
#[derive(Debug, Parser)]
#[command(name = "conformap", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(args) => commands::info::run(&args),
        Command::Disk(args) => commands::disk::run(&args),
        Command::Metrics(args) => commands::metrics::run(&args),
        Command::Sphere(args) => commands::sphere::run(&args),
        Command::Mobius(args) => commands::mobius::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            eprintln!("error: {failure}");
            if let Some(hint) = failure.hint() {
                eprintln!("hint: {hint}");
            }
            ExitCode::from(failure.exit_code())
        }
    }
}
