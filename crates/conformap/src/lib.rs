//! The conformap application layer: one job per command (disk, sphere, mobius, global,
//! morph, render, info, metrics, batch) over the conformap library crates, with typed
//! reports and all-or-nothing outputs.
//!
//! It sits between the library crates (conformap-mesh, -io, -operators, -disk, -global,
//! -metrics, -render, -morph) and the two front ends (the `conformap` binary, the Python
//! package). It never parses a command line and never prints: a front end builds a job,
//! runs it, and shows the [`Outcome`] or the [`Failure`] (which carries its exit class and
//! a hint).
//!
//! # Example
//! ```
//! use conformap::{DiskJob, Failure, InputOptions, MapJob, OutputOptions};
//! # let dir = std::env::temp_dir().join(format!("conformap-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).map_err(Failure::input)?;
//! let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/woody.obj");
//! let job = DiskJob::new(InputOptions::new(mesh), OutputOptions::new(dir.join("woody_uv.obj")));
//! let report = job.run()?.report.ok_or_else(|| Failure::input("no report"))?;
//! assert_eq!(report.command, "disk");
//! assert_eq!(report.method, "ccem-qn");
//! assert!(report.solver.summary.converged);
//! let (conformal_energy, mean_angle_deg, flipped) = report.metrics.headline();
//! assert_eq!(flipped, 0);
//! assert!(conformal_energy < 0.07, "E_C = {conformal_energy}"); // woody: 0.0615
//! assert!(mean_angle_deg < 6.0, "mean angle distortion {mean_angle_deg}°"); // 5.69°
//! # std::fs::remove_dir_all(&dir).map_err(Failure::input)?;
//! # Ok::<(), Failure>(())
//! ```
//!
//! # Modules
//! - [`jobs`]: one module per command, each with its job type.
//! - [`pipeline`]: read → check every output path → memory check → solve → metrics → stage
//!   outputs → commit all or none → report, shared by every map job ([`MapJob`],
//!   [`run_map`]); [`run_in_memory`] for a mesh already in memory.
//! - [`batch`]: one map job over many meshes, in parallel within a memory budget.
//! - [`report`]: the report's types (stable field names).
//! - [`failure`]: failures, their exit classes (1 bad input, 2 usage, 3 numerical) and hints.
//! - [`choice`](mod@choice): named option values (`"ccem-qn"`) parsed the same way by every front end.
//!
//! # Adding a command
//! 1. A module `jobs/<name>.rs` with a `#[non_exhaustive]` `<Name>Job` holding
//!    [`InputOptions`], [`OutputOptions`] and its own options (documented defaults,
//!    `new`, `with_*` builders); option enums declared with [`choice!`].
//! 2. `impl MapJob for <Name>Job`: `name`, `work`, `input`, `output`, `peak_bytes` (asked
//!    of the solver crate's memory model), `solve` (library calls, then the solver's
//!    `summary()` and a typed [`report::SolverDetail`] for the `solver` object, typed
//!    [`report::MetricsExtra`] and [`report::Sections`] for the rest); `check_usage` /
//!    `other_inputs` where needed.
//! 3. Re-export the job here; the CLI gets a clap struct with `to_job()` and a variant whose
//!    arm runs it; the Python package a function turning arrays into the job and calling
//!    [`run_in_memory`].

pub mod batch;
pub mod choice;
pub mod failure;
pub mod jobs;
pub mod pipeline;
pub mod report;

pub use batch::{BatchCommand, BatchJob, BatchTemplate};
pub use choice::{Choice, UnknownChoice};
pub use failure::Failure;
pub use jobs::{
    atlas::AtlasJob, disk::DiskJob, flatten::FlattenJob, global::GlobalJob, info::InfoJob,
    metrics::MetricsJob, mobius::MobiusJob, morph::MorphJob, render::RenderJob, sphere::SphereJob,
};
pub use pipeline::{run_in_memory, run_map, InputOptions, MapJob, Outcome, OutputOptions, Solved};
pub use report::Report;
