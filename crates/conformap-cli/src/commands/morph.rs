//! `conformap morph`: morph through key surfaces with landmarks.
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use std::path::PathBuf;

use clap::Args;
use conformap::jobs::morph::MorphJob;

/// Arguments of `conformap morph`.
#[derive(Debug, Clone, Args)]
pub struct MorphArgs {
    /// The key surfaces S1 S2 [S3 …] (disk-like meshes: one boundary loop, no handles).
    /// Every frame has S1's vertices and faces.
    #[arg(required = true, num_args = 1..)]
    pub surfaces: Vec<PathBuf>,
    /// One landmark file per surface, in the same order: `<0-based vertex> <name>` per
    /// line, the same names in the same order in every file. The first landmark goes to
    /// the centre of the disk, the second fixes the rotation (both interior vertices).
    #[arg(long, required = true, num_args = 1..)]
    pub landmarks: Vec<PathBuf>,
    /// Number of frames (key surface k at frame round(k(N−1)/(K−1))).
    #[arg(long)]
    pub frames: usize,
    /// `OUT.glb` (S1 with one morph target per key surface and an animation of their
    /// weights, one keyframe per frame at 24 frames per second) or `DIR/` (created when
    /// missing: `frame_0000.obj` …; frame files of an earlier run this run did not write
    /// are removed).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Landmark weight λ of Eq. 34 (default: the library's `DEFAULT_LAMBDA`). Where
    /// Eq. 34 folds, the largest λ without a fold and a fold-free landmark warp bring the
    /// landmarks to where λ puts them (the report says so).
    #[arg(long, conflicts_with = "hard")]
    pub lambda: Option<f64>,
    /// Put the landmarks exactly on their counterparts (hard constraints; where they
    /// fold, the same fold-free landmark warp finishes).
    #[arg(long)]
    pub hard: bool,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Refuse (exit 1, nothing computed) if the estimated peak memory exceeds SIZE (bytes,
    /// or with K/M/G/T, e.g. 4G), checked before reading the surfaces and before solving.
    /// Default: the memory available (Linux MemAvailable, within the cgroup limit); no
    /// check where that is unknown.
    #[arg(long, value_name = "SIZE", value_parser = crate::args::parse_size)]
    pub max_memory: Option<u64>,
}

impl MorphArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> MorphJob {
        let mut job = MorphJob::new(
            self.surfaces.clone(),
            self.landmarks.clone(),
            self.frames,
            &self.output,
        );
        job.lambda = self.lambda;
        job.hard = self.hard;
        job.report = self.report.clone();
        job.max_memory = self.max_memory;
        job
    }
}
