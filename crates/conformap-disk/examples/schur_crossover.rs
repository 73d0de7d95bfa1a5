//! Measures what the two Schur-complement paths cost on real meshes (not a test):
//! blocked multi-column solves with the factor of `L_II` (what forming `A` densely costs per
//! column) against two-column solves (what one implicit product costs), and a dense
//! product. `cargo run --release -p conformap-disk --example schur_crossover -- MESH.obj...`
use std::time::Instant;

use conformap_disk::DiskProblem;
use conformap_testkit::read_plain_obj;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for name in std::env::args().skip(1) {
        let mesh = read_plain_obj(std::path::Path::new(&name))?;
        let p = DiskProblem::new(&mesh)?;
        let ni = p.blocks().ii.rows();
        let nb = p.num_boundary();
        let nnz = p.interior_factor().stats().nnz_factor;
        let time_cols = |k: usize, reps: usize| {
            let mut buf = vec![1.0; ni * k];
            let t = Instant::now();
            for _ in 0..reps {
                p.interior_factor().solve_in_place(&mut buf, k);
            }
            t.elapsed().as_secs_f64() * 1e3 / reps as f64
        };
        let two = time_cols(2, 20);
        print!(
            "{}: n_I={ni} n_B={nb} nnz(factor)={nnz} factor {:.0} ms | 2-col solve {two:.2} ms",
            name.rsplit('/').next().unwrap_or(&name),
            p.factor_ms
        );
        for k in [16, 64, 128, 256] {
            let ms = time_cols(k, 2);
            print!(" | {k}-col {:.3} ms/col", ms / k as f64);
        }
        // dense product of an n_B × n_B matrix with two columns
        let a = vec![0.5; nb * nb];
        let x = vec![1.0; 2 * nb];
        let t = Instant::now();
        let mut acc = 0.0;
        for _ in 0..20 {
            for col in a.chunks_exact(nb) {
                let (mut r, mut i) = (0.0, 0.0);
                for (c, (u, v)) in col.iter().zip(x[..nb].iter().zip(&x[nb..])) {
                    r += c * u;
                    i += c * v;
                }
                acc += r + i;
            }
        }
        let dense = t.elapsed().as_secs_f64() * 1e3 / 20.0;
        println!(" | dense product {dense:.3} ms ({acc:.0})");
    }
    Ok(())
}
