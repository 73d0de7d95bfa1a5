//! Tall-and-skinny products over the edges or faces of a surface, block by block: the
//! `n × n` Gram-type sums `Σ_r l_r r_rᵀ` of the wedge and Gram matrices (the area form of
//! `optimal/faces.rs` and the holomorphic basis of `periods.rs` use the same blocks).
//!
//! The factors are never stored whole (`rows × n` values, 62 MB per matrix at genus 15 on
//! armadillo's double covering): each block of [`PRODUCT_BLOCK_ROWS`] rows is filled,
//! multiplied on one thread, and the blocks are spread over the threads by rayon's work
//! stealing and summed in their order (the result does not depend on the thread count).
//! Rayon's idle threads sleep, where a parallel dense product spins on a barrier: on a
//! machine shared with other work the blocked sums slow down with the load, not by 5×
//! (measured on armadillo, docs/benchmarks.md, issue 23).

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatMut, Par};
use rayon::prelude::*;

/// Rows per block: `4096`. Two `4096 × n` factors (2 MB at `n = 30`) stay cache-sized.
pub const PRODUCT_BLOCK_ROWS: usize = 4096;

/// The `(start, len)` of every block of `rows` rows.
pub(crate) fn blocks(rows: usize) -> Vec<(usize, usize)> {
    (0..rows)
        .step_by(PRODUCT_BLOCK_ROWS)
        .map(|s| (s, PRODUCT_BLOCK_ROWS.min(rows - s)))
        .collect()
}

/// `Σ_blocks Lᵀ R` (`n × n`) over `rows` rows, where `fill(start, len, L, R)` writes the
/// block's rows `start..start + len` of both factors (`len × n` each, zeroed on entry).
pub(crate) fn inner_products<F>(rows: usize, n: usize, fill: F) -> Mat<f64>
where
    F: Fn(usize, usize, MatMut<'_, f64>, MatMut<'_, f64>) + Sync,
{
    let parts: Vec<Mat<f64>> = blocks(rows)
        .par_iter()
        .map(|&(start, len)| {
            let (mut l, mut r) = (Mat::<f64>::zeros(len, n), Mat::<f64>::zeros(len, n));
            fill(start, len, l.as_mut(), r.as_mut());
            let mut out = Mat::<f64>::zeros(n, n);
            matmul(
                out.as_mut(),
                Accum::Replace,
                l.transpose(),
                r.as_ref(),
                1.0,
                Par::Seq,
            );
            out
        })
        .collect();
    let mut total = Mat::<f64>::zeros(n, n);
    for p in &parts {
        for j in 0..n {
            for i in 0..n {
                total[(i, j)] += p[(i, j)];
            }
        }
    }
    total
}
