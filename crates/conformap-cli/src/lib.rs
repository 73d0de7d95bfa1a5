//! The conformap command-line tool as a library: conformal parameterization of triangle
//! meshes over OBJ and glTF.
//!
//! A thin layer over the library crates (argument checking, the one command pipeline,
//! JSON reports, exit codes; no maths). The binary `conformap` parses its arguments into
//! a [`Cli`] and prints what [`Command::run`] returns; `batch` and the Python package run
//! the same commands and get the same typed [`report::Report`].
//!
//! # Modules
//! - [`cli`]: the subcommands and their dispatch.
//! - [`pipeline`]: read → check outputs → memory → solve → metrics → write all or none →
//!   report, shared by every map command ([`pipeline::MapCommand`]), with the argument
//!   groups every map command flattens ([`pipeline::InputArgs`], [`pipeline::OutputArgs`]).
//! - [`commands`]: one module per subcommand (a small `MapCommand` each).
//! - [`report`]: the report's types (design.md's schema).
//! - [`failure`]: failures and their exit codes (0 success, 1 bad input, 2 usage error,
//!   3 numerical failure), and every library-error mapping.
//!
//! # Example
//! ```
//! use conformap_cli::commands::disk::DiskArgs;
//! use conformap_cli::pipeline::{run_map, InputArgs, OutputArgs};
//! # let dir = std::env::temp_dir().join(format!("conformap-cli-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).unwrap();
//! let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/woody.obj");
//! let args = DiskArgs::new(InputArgs::new(mesh), OutputArgs::new(dir.join("woody_uv.obj")));
//! let outcome = run_map(&args)?;
//! let report = outcome.report.expect("a map command reports");
//! assert_eq!(report.command, "disk");
//! assert!(report.solver.converged);
//! assert_eq!(report.metrics.headline().2, 0); // no flipped face
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), conformap_cli::failure::Failure>(())
//! ```

pub mod cli;
pub mod commands;
pub mod failure;
pub mod pipeline;
pub mod report;

pub use cli::{Cli, Command};
