//! Probe (not a test): dense boundary-sized kernels at n_B = N.
use std::time::Instant;

use conformap_operators::DenseCholesky;

fn main() {
    bandwidth();
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(2828);
    let threads: usize = std::env::args()
        .nth(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    // an SPD matrix: a discrete 1D Laplacian-like kernel plus identity
    let mut a = vec![0.0; n * n];
    for j in 0..n {
        for i in 0..n {
            let d = (i as f64 - j as f64).abs();
            a[j * n + i] = 1.0 / (1.0 + d * d);
        }
        a[j * n + j] += n as f64;
    }
    let t = Instant::now();
    let c = DenseCholesky::factor(a.clone(), n, threads).expect("spd");
    let f = t.elapsed().as_secs_f64() * 1e3;
    let mut x = vec![1.0; n];
    let t = Instant::now();
    for _ in 0..10 {
        c.solve_in_place(&mut x, 1);
    }
    let s1 = t.elapsed().as_secs_f64() * 1e2;
    let mut x2 = vec![1.0; 2 * n];
    let t = Instant::now();
    for _ in 0..10 {
        c.solve_in_place(&mut x2, 2);
    }
    let s2 = t.elapsed().as_secs_f64() * 1e2;
    println!(
        "n {n}: factor {f:.0} ms ({:.2} GFMA/s), solve 1 col {s1:.1} ms, 2 cols {s2:.1} ms",
        (n as f64).powi(3) / 6.0 / f / 1e6
    );
}

#[allow(dead_code)]
fn bandwidth() {
    let n = 8 << 20; // 64 MB
    let v: Vec<f64> = (0..n).map(|i| i as f64).collect();
    for _ in 0..3 {
        let t = Instant::now();
        let mut s = [0.0f64; 4];
        for c in v.chunks_exact(4) {
            for l in 0..4 {
                s[l] += c[l];
            }
        }
        let ms = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "read 64 MB: {ms:.1} ms ({:.1} GB/s) {}",
            64e-3 / (ms / 1e3) * 1e3 / 1e3,
            s[0]
        );
    }
}
