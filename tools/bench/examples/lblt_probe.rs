//! Probe (not a test): the dense modified `LBLᵀ` (the Hessian preconditioner) against the
//! dense Cholesky at boundary sizes. `cargo run --release -p conformap-bench --example lblt_probe -- N...`
use std::time::Instant;

use conformap_operators::{DenseCholesky, DenseModifiedLblt};

fn main() {
    for n in std::env::args()
        .skip(1)
        .filter_map(|s| s.parse::<usize>().ok())
    {
        let mut a = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                a[j * n + i] = -1.0 / (1.0 + (i as f64 - j as f64).powi(2));
            }
            a[j * n + j] = 4.0;
        }
        let (mut tl, mut tc) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..3 {
            let t = Instant::now();
            let f = DenseModifiedLblt::factor(a.clone(), n, 0, 1e-12).expect("lblt");
            tl = tl.min(t.elapsed().as_secs_f64() * 1e3);
            std::hint::black_box(f.modified);
            let t = Instant::now();
            let c = DenseCholesky::factor(a.clone(), n, 0).expect("spd");
            tc = tc.min(t.elapsed().as_secs_f64() * 1e3);
            std::hint::black_box(c.dim());
        }
        println!("n {n}: modified LBLᵀ {tl:.1} ms, Cholesky {tc:.1} ms");
    }
}
