//! Probe (not a test): factorization of `L_II` with AMD against nested dissection.
//!
//! `cargo run --release -p conformap-bench --example ordering_probe -- [--runs N] MESH.obj...`
//! prints, per mesh and ordering, the median analyse and factor times (ms) and the
//! factor's non-zeros and flops (2 × multiply–adds), and what forming the Schur complement's `L_IBᵀ L_II⁻¹ L_IB` with
//! that factor costs (median ms and multiply–adds).
use std::time::Instant;

use conformap_disk::DiskProblem;
use conformap_operators::{Cholesky, CholeskyOptions, Ordering};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut runs = 3usize;
    let mut files = Vec::new();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        if a == "--runs" {
            runs = args.next().ok_or("--runs N")?.parse()?;
        } else {
            files.push(a);
        }
    }
    println!(
        "| mesh | V | ordering | analyse ms | factor ms | total ms | nnz(L) | factor Gflop | Schur ms | Schur Gflop |"
    );
    println!("|---|---:|---|---:|---:|---:|---:|---:|---:|---:|");
    for f in files {
        let mesh = conformap_io::read_mesh(std::path::Path::new(&f))?.mesh;
        let problem = DiskProblem::new(&mesh)?;
        let ii = &problem.blocks().ii;
        for (name, ordering) in [
            ("AMD", Ordering::Amd),
            ("nested dissection", Ordering::NestedDissection),
        ] {
            let opts = CholeskyOptions::DEFAULT.with_ordering(ordering);
            let (mut an, mut fa, mut tot) = (Vec::new(), Vec::new(), Vec::new());
            let (mut nnz, mut schur, mut flop, mut fflop) = (0, Vec::new(), 0.0, 0.0);
            for _ in 0..runs {
                let t = Instant::now();
                let c = Cholesky::factor_with(ii, &opts)?;
                tot.push(t.elapsed().as_secs_f64() * 1e3);
                an.push(c.stats().analyse_ms);
                fa.push(c.stats().factor_ms);
                nnz = c.stats().nnz_factor;
                let t = Instant::now();
                std::hint::black_box(c.inverse_gram(&problem.blocks().ib)?);
                schur.push(t.elapsed().as_secs_f64() * 1e3);
                flop = 2e-9 * c.inverse_gram_cost(&problem.blocks().ib)?;
                fflop = 2e-9 * c.factor_cost();
            }
            let name_of = std::path::Path::new(&f)
                .file_name()
                .map_or(f.clone(), |n| n.to_string_lossy().to_string());
            println!(
                "| {name_of} | {} | {name} | {:.0} | {:.0} | {:.0} | {nnz} | {fflop:.2} | {:.0} | {flop:.2} |",
                mesh.num_vertices(),
                median(an),
                median(fa),
                median(tot),
                median(schur)
            );
        }
    }
    Ok(())
}
