//! Probe (not a test): analyse + factor of one mesh's `L_II`, repeated in one process, each
//! run printed (the first against the later ones), with the process's page faults.
//! `cargo run --release -p conformap-bench --example factor_probe -- MESH.obj [amd|nd] [RUNS]`
use std::time::Instant;

use conformap_disk::DiskProblem;
use conformap_operators::{Cholesky, CholeskyOptions, Ordering};

fn faults() -> u64 {
    // minor faults of this process: field 10 of /proc/self/stat
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            s.rsplit(')')
                .next()
                .and_then(|t| t.split_whitespace().nth(7))
                .and_then(|v| v.parse().ok())
        })
        .unwrap_or(0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("MESH.obj")?;
    let ordering = match args.next().as_deref() {
        Some("nd") => Ordering::NestedDissection,
        _ => Ordering::Amd,
    };
    let runs: usize = args.next().map_or(Ok(4), |r| r.parse())?;
    let mesh = conformap_io::read_mesh(std::path::Path::new(&path))?.mesh;
    let problem = DiskProblem::new(&mesh)?;
    let opts = CholeskyOptions::DEFAULT.with_ordering(ordering);
    for run in 0..runs {
        let f0 = faults();
        let t = Instant::now();
        let c = Cholesky::factor_with(&problem.blocks().ii, &opts)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "run {run}: analyse {:.0} factor {:.0} total {ms:.0} ms, {} page faults",
            c.stats().analyse_ms,
            c.stats().factor_ms,
            faults() - f0
        );
    }
    Ok(())
}
