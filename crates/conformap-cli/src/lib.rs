//! The conformap command-line tool as a library: conformal parameterization of triangle
//! meshes over OBJ and glTF.
//!
//! The front end of crate `conformap`, which does the work: the binary parses its
//! arguments into a [`Cli`], turns the subcommand into its job (`to_job`), runs it and
//! prints what it returns; no maths and no report building here.
//!
//! # Modules
//! - [`cli`]: the subcommands and their dispatch.
//! - [`commands`]: one module per subcommand: its clap arguments and `to_job`.
//! - [`args`]: the argument groups every map command flattens ([`args::InputArgs`],
//!   [`args::OutputArgs`]) and the parser of named choices.
//! - [`progress`]: the spinner and the batch bar on stderr.
//!
//! # Example
//! ```
//! use clap::Parser;
//! use conformap_cli::{Cli, Command};
//! # let dir = std::env::temp_dir().join(format!("conformap-cli-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).unwrap();
//! let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/woody.obj");
//! let out = dir.join("woody_uv.obj");
//! let cli = Cli::try_parse_from(["conformap", "disk", mesh, "-o", out.to_str().unwrap()])?;
//! let Command::Disk(args) = &cli.command else { unreachable!() };
//! let job = args.to_job();
//! assert_eq!(job.method.to_string(), "ccem-qn");
//! let report = cli.command.run()?.report.expect("a map command reports");
//! assert!(report.solver.summary.converged);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod args;
pub mod cli;
pub mod commands;
pub mod progress;

pub use cli::{Cli, Command};
