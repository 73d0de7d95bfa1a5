//! `conformap batch`: one map command over many meshes.
//! The clap arguments; their job ([`conformap::BatchJob`]) is built by
//! [`crate::cli::batch_job`], which parses the options after `--` as the command's own.

use std::path::PathBuf;

use clap::Args;
use conformap::BatchCommand;

use crate::args::{choice, parse_size};

/// Arguments of `conformap batch`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Example (every input mapped by the default ccem-qn, refused with exit 3 \
    if it did not converge; the summary line names inputs stopped at the iteration cap):\n  \
    conformap batch --command disk --out-dir out/ fixtures/woody.obj fixtures/alligator.obj -- --strict"
)]
pub struct BatchArgs {
    /// The command run on every input.
    #[arg(long, value_parser = choice::<BatchCommand>())]
    pub command: BatchCommand,
    /// Where the outputs go: `DIR/<stem>.<ext>` and `DIR/<stem>.json` (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Inputs run at once (each on one thread), as far as their memory estimates fit.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=256))]
    pub jobs: u32,
    /// Skip an input whose outputs all exist already.
    #[arg(long)]
    pub skip_existing: bool,
    /// Also write the JSON lines here.
    #[arg(long, value_name = "R.jsonl")]
    pub report: Option<PathBuf>,
    /// Output mesh format (obj, gltf, glb). Default: the input's.
    #[arg(long)]
    pub ext: Option<String>,
    /// Also write `DIR/<stem>_surface.png` and `DIR/<stem>_map.png` (as --png of the command).
    #[arg(long)]
    pub png: bool,
    /// The memory all jobs together may use (bytes, or with K/M/G/T); passed to every run
    /// as its --max-memory. Default: the memory available at the start.
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
    /// Meshes, and manifests (any other extension: one path per line, or CSV with a `path`
    /// column; relative paths from the manifest's directory).
    #[arg(required = true, value_name = "MANIFEST|MESH")]
    pub inputs: Vec<PathBuf>,
    /// Options of the command, after `--` (e.g. `-- --strict`, `-- --method harmonic`).
    #[arg(last = true, value_name = "OPTIONS")]
    pub options: Vec<String>,
}
