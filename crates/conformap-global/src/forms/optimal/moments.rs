//! The second moments of the per-face area forms: the uniformity energy, its gradient and
//! its Hessian at any coefficient vector without touching the faces again.
//!
//! With the per-face forms packed as vectors `v_f` (the upper triangle of `Q̃_f`, see
//! `products.rs`) and the unit coefficients `μ` packed as `z = pack(μμᵀ)` (off-diagonal
//! entries doubled, so that `a_f = μᵀ Q̃_f μ = v_f · z`), the energy is the quadratic form
//!
//! `E(μ) = Σ_f (v_f·z − s_f)² = zᵀ T z − 2 b·z + c`, with `T = Σ_f v_f v_fᵀ`,
//! `b = Σ_f s_f v_f`, `c = Σ_f s_f²`.
//!
//! `T` is built once per surface (one Gram product over the faces, `F · m²` flops for
//! `m = n(n+1)/2`, `n = 2g`); afterwards every energy costs `m²` and every Hessian `n⁴`
//! flops, independent of the mesh size: a multistart of hundreds of Newton runs on a genus-4
//! surface takes milliseconds. No cancellation is to fear: `E` is of the order of `c`
//! (the faces' shares do not all match), so the three terms are of one magnitude.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};

use crate::forms::optimal::aggregates::Aggregates;
use crate::forms::optimal::faces::FaceForms;
use crate::forms::optimal::products::AreaProducts;

/// Faces per block of the Gram product `T = Σ v_f v_fᵀ`. Default 4096: the block of packed
/// vectors (`4096 × m` values, 1.2 MB at genus 4) stays in cache-sized pieces and the
/// memory is bounded whatever the face count.
pub const GRAM_BLOCK_FACES: usize = 4096;

/// `T`, `b`, `c` of the energy as a quadratic form in `z = pack(μμᵀ)`.
#[derive(Debug, Clone)]
pub struct Moments {
    /// `2g`.
    pub n: usize,
    /// `n(n+1)/2`.
    pub m: usize,
    /// Packed index of `(i, j)` (symmetric), row-major `n × n`.
    index: Vec<usize>,
    /// `T`, row-major `m × m`, symmetric.
    t: Vec<f64>,
    /// `b`.
    b: Vec<f64>,
    /// `c`.
    c: f64,
}

impl Moments {
    /// The moments of `p`'s faces.
    pub fn new(p: &AreaProducts) -> Self {
        Self::build(p.n, &p.s, |f, i, j| p.face(f)[i * p.n + j])
    }

    /// The moments of `faces`' area forms, streamed block by block from the edge values
    /// (no `n × n` form per face is ever stored).
    pub fn from_faces(faces: &FaceForms) -> Self {
        let whitened = faces.whitened();
        Self::build(faces.n, &faces.s, |f, i, j| {
            whitened.area_form_entry(f, i, j)
        })
    }

    /// The moments of the area forms `entry(f, i, j) = Q̃_f[i][j]` of the faces of shares
    /// `s`.
    fn build(n: usize, s: &[f64], entry: impl Fn(usize, usize, usize) -> f64) -> Self {
        let m = n * (n + 1) / 2;
        let mut index = vec![0; n * n];
        let mut pairs = Vec::with_capacity(m);
        for i in 0..n {
            for j in i..n {
                index[i * n + j] = pairs.len();
                index[j * n + i] = pairs.len();
                pairs.push((i, j));
            }
        }
        let faces = s.len();
        let mut t = Mat::<f64>::zeros(m, m);
        let mut b = vec![0.0; m];
        let mut start = 0;
        while start < faces {
            let end = (start + GRAM_BLOCK_FACES).min(faces);
            let block = Mat::<f64>::from_fn(end - start, m, |r, col| {
                let (i, j) = pairs[col];
                entry(start + r, i, j)
            });
            matmul(
                t.as_mut(),
                Accum::Add,
                block.transpose(),
                block.as_ref(),
                1.0,
                Par::rayon(0),
            );
            for r in 0..end - start {
                let s = s[start + r];
                for (col, bc) in b.iter_mut().enumerate() {
                    *bc += s * block[(r, col)];
                }
            }
            start = end;
        }
        let c = s.iter().map(|s| s * s).sum();
        let t = (0..m * m).map(|k| t[(k / m, k % m)]).collect();
        Self {
            n,
            m,
            index,
            t,
            b,
            c,
        }
    }

    /// `c = Σ s_f²`: the scale of the energy (the energy of a layout with zero area
    /// everywhere), for rounding-level tolerances.
    pub fn scale(&self) -> f64 {
        self.c
    }

    /// `z = pack(μμᵀ)/|μ|²`.
    fn pack(&self, mu: &[f64]) -> Vec<f64> {
        let n = self.n;
        let norm2: f64 = mu.iter().map(|x| x * x).sum();
        let mut z = Vec::with_capacity(self.m);
        for i in 0..n {
            for j in i..n {
                let w = if i == j { 1.0 } else { 2.0 };
                z.push(w * mu[i] * mu[j] / norm2);
            }
        }
        z
    }

    /// `T z`.
    fn t_times(&self, z: &[f64]) -> Vec<f64> {
        let m = self.m;
        (0..m)
            .map(|r| {
                self.t[r * m..(r + 1) * m]
                    .iter()
                    .zip(z)
                    .map(|(a, b)| a * b)
                    .sum()
            })
            .collect()
    }

    /// `E(μ)` for `μ ≠ 0` (any length).
    pub fn energy(&self, mu: &[f64]) -> f64 {
        let z = self.pack(mu);
        let tz = self.t_times(&z);
        let a2: f64 = z.iter().zip(&tz).map(|(a, b)| a * b).sum();
        let bz: f64 = z.iter().zip(&self.b).map(|(a, b)| a * b).sum();
        a2 - 2.0 * bz + self.c
    }

    /// The per-face aggregates of `uniform::evaluate` at a unit `μ`, from the moments.
    pub fn aggregates(&self, mu: &[f64]) -> Aggregates {
        let (n, m) = (self.n, self.m);
        let z = self.pack(mu);
        let g_packed = self.t_times(&z);
        let a2: f64 = z.iter().zip(&g_packed).map(|(a, b)| a * b).sum();
        let bz: f64 = z.iter().zip(&self.b).map(|(a, b)| a * b).sum();
        let full = |packed: &[f64]| -> Vec<f64> {
            (0..n * n)
                .map(|k| packed[self.index[k]])
                .collect::<Vec<_>>()
        };
        let g = full(&g_packed);
        let b = full(&self.b);
        let times_mu = |a: &[f64], i: usize| -> f64 { (0..n).map(|j| a[i * n + j] * mu[j]).sum() };
        let au: Vec<f64> = (0..n).map(|i| times_mu(&g, i)).collect();
        let bu: Vec<f64> = (0..n).map(|i| times_mu(&b, i)).collect();
        let big_r: Vec<f64> = au.iter().zip(&bu).map(|(a, b)| a - b).collect();
        let rq: Vec<f64> = g.iter().zip(&b).map(|(a, b)| a - b).collect();
        // uu_ij = Σ_f (Q̃_f μ)_i (Q̃_f μ)_j = Σ_kl μ_k μ_l T[(i,k), (j,l)]
        let mut uu = vec![0.0; n * n];
        for i in 0..n {
            for j in i..n {
                let mut sum = 0.0;
                for k in 0..n {
                    let row = &self.t[self.index[i * n + k] * m..][..m];
                    let inner: f64 = (0..n).map(|l| mu[l] * row[self.index[j * n + l]]).sum();
                    sum += mu[k] * inner;
                }
                uu[i * n + j] = sum;
                uu[j * n + i] = sum;
            }
        }
        Aggregates {
            energy: a2 - 2.0 * bz + self.c,
            rho: a2 - bz,
            a2,
            big_r,
            au,
            uu,
            rq,
        }
    }
}
