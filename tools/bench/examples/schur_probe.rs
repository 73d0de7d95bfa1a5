//! Probe (not a test): what forming the dense Schur complement costs on real meshes.
//! `cargo run --release -p conformap-bench --example schur_probe -- MESH.obj...`
use std::time::Instant;

use conformap_disk::DiskProblem;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for name in std::env::args().skip(1) {
        let t = Instant::now();
        let mesh = conformap_io::read_mesh(std::path::Path::new(&name))?.mesh;
        let read = t.elapsed().as_secs_f64() * 1e3;
        let p = DiskProblem::new(&mesh)?;
        let st = p.interior_factor().stats().clone();
        let t = Instant::now();
        let g = p.interior_factor().inverse_gram(&p.blocks().ib)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let b = vec![num_complex::Complex64::new(1.0, 0.5); st.n];
        let mut solve = f64::INFINITY;
        for _ in 0..5 {
            let t = Instant::now();
            let x = p.interior_factor().solve_complex(&b);
            std::hint::black_box(x);
            solve = solve.min(t.elapsed().as_secs_f64() * 1e3);
        }
        println!("two-column solve {solve:.1} ms");
        println!(
            "{}: n_I {} n_B {} nnz(G) {} read {read:.0} assemble {:.0} analyse {:.0} factor {:.0} | gram {ms:.0} ms, W entries {} ({:.2} of nnz(G)), panels {} of {}",
            name.rsplit('/').next().unwrap_or(&name),
            st.n,
            p.num_boundary(),
            st.nnz_factor,
            p.assemble_ms,
            st.analyse_ms,
            st.factor_ms,
            g.w_entries,
            g.w_entries as f64 / st.nnz_factor as f64,
            g.panels_visited,
            g.panels
        );
    }
    Ok(())
}
