//! `conformap disk`: conformal map onto the unit disk (or the disk with circular holes).
//! The clap arguments and their job; the job (crate `conformap`) does the work.

use clap::Args;
use conformap::jobs::disk::{DiskJob, FactorOrder, Method};

use crate::args::{choice, InputArgs, OutputArgs};

/// Arguments of `conformap disk`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Texture coordinates (-o): one `vt` per vertex, vt = ((u+1)/2, (v+1)/2) for the map u + iv in the unit disk (with holes: the same disk, the holes as circles inside it); `--flat`: the points (u, v, 0)."
)]
pub struct DiskArgs {
    /// The mesh and how to read it: genus 0 with one boundary loop (the unit disk) or
    /// several (the unit disk with circular holes, by Koebe's iteration).
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` holds texture coordinates vt = ((u+1)/2, (v+1)/2).
    #[command(flatten)]
    pub output: OutputArgs,
    /// Method.
    #[arg(long, value_parser = choice::<Method>(), default_value_t = Method::CcemQn)]
    pub method: Method,
    /// With several boundary loops: the loop (0-based, as `conformap info` lists them) mapped
    /// onto the unit circle. Default: the longest.
    #[arg(long, value_name = "K")]
    pub outer: Option<usize>,
    /// Iteration cap (default: CCEM 1000, CEM 20 as in the papers; several loops: Koebe
    /// sweeps, 200).
    #[arg(long)]
    pub max_iter: Option<usize>,
    /// Relative energy tolerance (default: CCEM 1e-9, CEM 1e-6; several loops: the circle
    /// residual ending the Koebe sweeps, 1e-4, before the polish makes the circles exact).
    #[arg(long)]
    pub tol: Option<f64>,
    /// Keep the folds of a `harmonic` or `cem` map (for comparison with the papers' plain
    /// algorithms) instead of repairing them: by default every method's map is flip-free
    /// (the repair is listed in the report's notes).
    #[arg(long)]
    pub keep_folds: bool,
    /// Fill-reducing ordering of the factorization of the interior Laplacian (one boundary
    /// loop; the map is the same to rounding, only its cost changes)
    #[arg(long, value_parser = choice::<FactorOrder>(), default_value_t = FactorOrder::Auto)]
    pub ordering: FactorOrder,
}

impl DiskArgs {
    /// The job these arguments ask for.
    pub fn to_job(&self) -> DiskJob {
        let mut job = DiskJob::new(self.input.to_options(), self.output.to_options())
            .with_method(self.method)
            .with_max_iter(self.max_iter)
            .with_tol(self.tol);
        job.outer = self.outer;
        job.keep_folds = self.keep_folds;
        job.ordering = self.ordering;
        job
    }
}
