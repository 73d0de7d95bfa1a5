//! Tall-and-skinny products over the faces of a surface, block by block: the `n × n`
//! sums `Σ_r l_r r_rᵀ` of the area form, and the `rows × n` product of the harmonic forms
//! with the conjugation matrix.
//!
//! The factors are never stored whole (`rows × n` values, 62 MB per matrix at genus 15 on
//! armadillo's double covering): each block of [`PRODUCT_BLOCK_ROWS`] rows is filled,
//! multiplied on one thread, and the blocks are spread over the threads by rayon's work
//! stealing and summed in their order (the result does not depend on the thread count).
//! Rayon's idle threads sleep, where a parallel dense product spins on a barrier: on a
//! machine shared with other work the blocked sums slow down with the load, not by 5×
//! (measured on armadillo, docs/benchmarks.md, issue 23).

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};
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

/// `Lᵀ R` (`n × n`) for two `rows × n` column-major matrices, block by block of rows.
pub(crate) fn transpose_times(l: &Mat<f64>, r: &Mat<f64>) -> Mat<f64> {
    let n = l.ncols();
    let parts: Vec<Mat<f64>> = blocks(l.nrows())
        .par_iter()
        .map(|&(start, len)| {
            let mut out = Mat::<f64>::zeros(n, r.ncols());
            matmul(
                out.as_mut(),
                Accum::Replace,
                l.as_ref().subrows(start, len).transpose(),
                r.as_ref().subrows(start, len),
                1.0,
                Par::Seq,
            );
            out
        })
        .collect();
    let mut total = Mat::<f64>::zeros(n, r.ncols());
    for p in &parts {
        for j in 0..r.ncols() {
            for i in 0..n {
                total[(i, j)] += p[(i, j)];
            }
        }
    }
    total
}

/// `M ← M B` for the `rows × n` column-major `m` and the `n × n` `b` (row-major), in place,
/// block by block of rows: one thread per block, each product on one thread from a copy of
/// the block (no second `rows × n` matrix).
pub(crate) fn times_small_in_place(m: &mut Mat<f64>, b: &[f64]) {
    let n = m.ncols();
    let bm = Mat::<f64>::from_fn(n, n, |i, j| b[i * n + j]);
    m.as_mut()
        .par_row_chunks_mut(PRODUCT_BLOCK_ROWS)
        .for_each(|block| {
            let copy = block.to_owned();
            matmul(
                block,
                Accum::Replace,
                copy.as_ref(),
                bm.as_ref(),
                1.0,
                Par::Seq,
            );
        });
}
