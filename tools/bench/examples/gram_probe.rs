//! Probe (not a test): the time of `Cholesky::inverse_gram` with `R = L_IB` on meshes,
//! repeated in one process (min and median of `--runs N`, default 7), for comparing two
//! builds of the formation of the Schur complement on this noisy machine.
//! `cargo run --release -p conformap-bench --example gram_probe -- [--runs N] MESH.obj...`
use std::time::Instant;

use conformap_disk::DiskProblem;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut runs = 7usize;
    let mut files = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--runs" {
            runs = args.next().ok_or("--runs N")?.parse()?;
        } else {
            files.push(a);
        }
    }
    for name in files {
        let mesh = conformap_io::read_mesh(std::path::Path::new(&name))?.mesh;
        let p = DiskProblem::new(&mesh)?;
        let mut times = Vec::new();
        let mut check = 0.0;
        for _ in 0..runs {
            let t = Instant::now();
            let g = p.interior_factor().inverse_gram(&p.blocks().ib)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            check = g.values.iter().sum::<f64>();
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{}: n_B {} inverse_gram min {:.1} median {:.1} ms (sum of entries {check:.12e})",
            name.rsplit('/').next().unwrap_or(&name),
            p.num_boundary(),
            times[0],
            times[times.len() / 2]
        );
    }
    Ok(())
}
