//! The per-face edge values of the holomorphic basis, and the uniformity energy, gradient
//! and Hessian (in whitened coordinates) summed straight over the faces from them.
//!
//! A face's layout area is `a_f = ½ Im(conj(A_f) B_f)` with `A_f = Σ_k μ_k a_{f,k}` and
//! `B_f = Σ_k μ_k b_{f,k}` the form's values on the face's edges `v0 → v1` and `v0 → v2`
//! (`a_{f,k}`, `b_{f,k}` those of the whitened basis form `k`). Storing these `4n` reals
//! per face (`n = 2g`) instead of the `n × n` area form `Q̃_f` (`products.rs`) costs
//! `32 n` bytes per face instead of `16 n²` (at genus 23 on armadillo: 127 MB instead of
//! 2.9 GB), and every quantity of `uniform.rs` is a sum of products of them:
//! - `u_f = Q̃_f μ = ¼ (Im(conj(a_f) B_f) + Im(conj(A_f) b_f))` (componentwise);
//! - `Σ r_f Q̃_f = ¼ (X + Xᵀ)`, `X = Σ_f r_f (Re a_f Im b_fᵀ − Im a_f Re b_fᵀ)`.
//!
//! The energy and gradient then cost `O(F n)` and the Hessian `O(F n²)` (dense matrix
//! products over blocks of faces), against `O(F n⁴)` once for the moments of
//! `moments.rs`: [`use_moments`] picks the cheaper of the two for a search.

use conformap_mesh::{EdgeIndex, TriMesh};
use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par};
use rayon::prelude::*;

use crate::forms::blocked::{times_small_in_place, transpose_times};
use crate::forms::cohomology::Cochain;
use crate::forms::dense::{symmetric_eigen, symmetric_function};
use crate::forms::optimal::aggregates::Aggregates;
#[cfg(test)]
use crate::forms::periods::ComplexCochain;
use crate::GlobalError;

/// Smallest eigenvalue of the area form `C`, relative to its largest, accepted as positive
/// definite. Default `1e-12`: a discrete holomorphic basis of a valid mesh has a condition
/// number far below `1e12`; below that the basis is degenerate.
pub const AREA_FORM_MIN_RELATIVE_EIGENVALUE: f64 = 1e-12;

/// Faces per block of the direct sums. Default 4096: a block's four `4096 × n` slices
/// (1.5 MB at genus 23) stay cache-sized, blocks are summed in their order (the result is
/// the same on any number of threads) and spread over the threads.
pub const DIRECT_BLOCK_FACES: usize = 4096;

/// Faces of the coarse level of a direct search: `16384`. A search on at least twice as
/// many faces descends first on every `F / 16384`-th face (weighted), then polishes on all
/// faces: a sample of 16k faces fixes the energy's landscape well enough that the polish
/// takes a few Newton steps (measured in docs/benchmarks.md, issue 23: armadillo's 86k
/// faces), where each full step costs `F / 16384` coarse ones.
pub const COARSE_FACES: usize = 16384;

/// Faces of the coarsest level of a direct search: `2048`. A search with a coarse level
/// ([`coarse_stride`]) descends from its starts on every `F / 2048`-th face first, then
/// refines on the coarse level and polishes on all faces. Far from an optimum the
/// saddle-free Newton takes 10–20 damped steps per start (measured on armadillo's slit
/// surfaces at genus 12 and 15, issue 23), which need only the landscape's rough shape, and
/// each costs a Hessian on the sampled faces. Measured (docs/benchmarks.md, issue 23, third
/// pass): 2048 faces find the same optimum at every step as 4096 did on armadillo, brain,
/// kitten_53k and hand (energies equal to 7 digits), with the objective 25–140 ms shorter
/// per step (armadillo's step 1: 377 → 240 ms; the coarse level then takes about as many
/// steps as before). Not used without a coarse level, so the searches of smaller meshes
/// are unchanged.
pub const COARSEST_FACES: usize = 2048;

/// Newton iterations per start assumed by [`use_moments`]: `40`. Measured at high genus
/// (issue 23): 33 per start on armadillo's coarse level at genus 12, 48 on spot at genus 15
/// (the saddle-free Newton needs many damped steps far from an optimum; converged starts
/// on low-genus surfaces take 5–15).
pub const NEWTON_ITERATIONS_ESTIMATE: usize = 40;

/// Newton iterations per start on all faces after the coarse level, assumed by
/// [`use_moments`]: `3` (from a coarse optimum Newton converges quadratically).
pub const POLISH_ITERATIONS_ESTIMATE: usize = 3;

/// The stride of the coarse level of a direct search on `faces` faces
/// (`faces / COARSE_FACES`), or `None` when the faces are too few for it to pay (a stride
/// below 2).
pub fn coarse_stride(faces: usize) -> Option<usize> {
    Some(faces / COARSE_FACES).filter(|&s| s >= 2)
}

/// The strides of the coarse levels of a direct search on `faces` faces, coarsest first:
/// `faces / COARSEST_FACES` and [`coarse_stride`] when there is a coarse level, nothing
/// otherwise.
pub fn coarse_strides(faces: usize) -> Vec<usize> {
    match coarse_stride(faces) {
        Some(stride) => vec![(faces / COARSEST_FACES).max(stride), stride],
        None => Vec::new(),
    }
}

/// Whether the moments of `moments.rs` (built once: `2 F m²` flops, `m = n(n+1)/2`, then
/// `O(n⁴)` per Newton step) cost less than the direct sums (about `6 F n²` flops per
/// Newton step; with a coarse level, [`NEWTON_ITERATIONS_ESTIMATE`] steps on
/// [`COARSE_FACES`] faces and [`POLISH_ITERATIONS_ESTIMATE`] on all) for a search of
/// `starts` starts on `faces` faces. The moments win at low genus and with many starts (the
/// default search of `global`: genus 4 with 104 starts), the direct sums at high genus with
/// few starts and many faces (the topological optimization's 4 starts on armadillo's 86k
/// faces from genus 12 on: at genus 23, `2e11` flops of moments against `5e10` of direct
/// Newton; on spot's 5.9k faces the moments up to genus 22). The coarsest level
/// ([`COARSEST_FACES`]) is not counted: the direct sums are chosen where they were before it,
/// and cost less there.
pub fn use_moments(faces: usize, n: usize, starts: usize) -> bool {
    let (f, nf) = (faces as f64, n as f64);
    let m = nf * (nf + 1.0) / 2.0;
    let moments = 2.0 * f * m * m;
    let hessian = |faces: f64| 6.0 * faces * nf * nf;
    let per_start = match coarse_stride(faces) {
        Some(stride) => {
            NEWTON_ITERATIONS_ESTIMATE as f64 * hessian((faces / stride) as f64)
                + POLISH_ITERATIONS_ESTIMATE as f64 * hessian(f)
        }
        None => NEWTON_ITERATIONS_ESTIMATE as f64 * hessian(f),
    };
    moments <= starts as f64 * per_start
}

/// The basis forms' values on the two edges `v0 → v1` (`a`) and `v0 → v2` (`b`) of each
/// of the user's faces (`faces × n` matrices, unwhitened), the surface shares, and the
/// whitening `W`: the models work in whitened coordinates `μ` (basis coefficients
/// `λ = W μ`), applying `W` to the coefficients and to the `n`-sized sums.
#[derive(Debug, Clone)]
pub struct FaceForms {
    /// `2g`.
    pub n: usize,
    /// `Re a_{f,k}`.
    pub ar: Mat<f64>,
    /// `Im a_{f,k}`.
    pub ai: Mat<f64>,
    /// `Re b_{f,k}`.
    pub br: Mat<f64>,
    /// `Im b_{f,k}`.
    pub bi: Mat<f64>,
    /// Surface area share `S_f / ΣS` of each face.
    pub s: Vec<f64>,
    /// `W = C^{-1/2}` (row-major): `λ = W μ`.
    pub w: Vec<f64>,
    /// `C^{1/2}` (row-major): `μ = C^{1/2} λ`.
    pub w_inv: Vec<f64>,
    /// Weight of every face in the sums: 1, or the sampling ratio of [`Self::sample`].
    pub weight: f64,
    /// The uniformity energy of each (unwhitened) basis form, from the same pass.
    pub basis_energy: Vec<f64>,
}

/// `out += alpha · lhs · rhs`, one thread (the blocks are spread over the threads).
fn gemm(out: &mut Mat<f64>, lhs: MatRef<'_, f64>, rhs: MatRef<'_, f64>, alpha: f64) {
    matmul(out.as_mut(), Accum::Add, lhs, rhs, alpha, Par::Seq);
}

fn row_major(m: &Mat<f64>) -> Vec<f64> {
    let (r, c) = (m.nrows(), m.ncols());
    (0..r * c).map(|k| m[(k / c, k % c)]).collect()
}

impl FaceForms {
    /// The whitened edge values of the first `faces` faces of `mesh` under the holomorphic
    /// basis `forms` (one complex value per edge of `edges`).
    ///
    /// # Errors
    /// [`GlobalError::DegenerateFormBasis`] if the total area form `C` is not positive
    /// definite.
    #[cfg(test)]
    pub fn new(
        mesh: &TriMesh,
        edges: &EdgeIndex,
        forms: &[ComplexCochain],
        faces: usize,
    ) -> Result<Self, GlobalError> {
        let n = forms.len();
        let (mut ar, mut ai) = (Mat::<f64>::zeros(faces, n), Mat::<f64>::zeros(faces, n));
        let (mut br, mut bi) = (Mat::<f64>::zeros(faces, n), Mat::<f64>::zeros(faces, n));
        let at = face_edges(edges, faces);
        for (k, form) in forms.iter().enumerate() {
            let (c0, c1) = (ar.col_as_slice_mut(k), ai.col_as_slice_mut(k));
            for (r, &[(e1, s1), _]) in at.iter().enumerate() {
                let a = s1 * form[e1];
                c0[r] = a.re;
                c1[r] = a.im;
            }
            let (c2, c3) = (br.col_as_slice_mut(k), bi.col_as_slice_mut(k));
            for (r, &[_, (e2, s2)]) in at.iter().enumerate() {
                let b = -(s2 * form[e2]);
                c2[r] = b.re;
                c3[r] = b.im;
            }
        }
        Self::finish(mesh, faces, [ar, ai, br, bi])
    }

    /// The per-face edge values of the holomorphic basis `a_k = h_k + i Σ_j Λ_jk h_j` of the
    /// real harmonic forms `h` and the conjugation `Λ` (`lambda`, row-major `n × n`), without
    /// the basis itself: the real parts are the harmonic forms' edge values and the
    /// imaginary parts their product with `Λ` (`Im a = Re a · Λ`, one dense `faces × n` by
    /// `n × n` product per edge), so the `edges × n` complex basis (125 MB on armadillo's
    /// 15-slit double covering) need not exist at all ([`crate::GlobalMap::basis_forms`]
    /// builds it on demand). The same values, up to rounding, as the test-only `new` from
    /// that basis (tested on eightsim).
    ///
    /// # Errors
    /// [`GlobalError::DegenerateFormBasis`] if the total area form `C` is not positive
    /// definite.
    pub fn from_harmonic(
        mesh: &TriMesh,
        edges: &EdgeIndex,
        h: &[Cochain],
        lambda: &[f64],
        faces: usize,
    ) -> Result<Self, GlobalError> {
        let n = h.len();
        let at = face_edges(edges, faces);
        // the four matrices written once each (no zero fill first), four tasks over the
        // cores: most of the time is faulting in their fresh pages (83 MB on armadillo's
        // 15-slit covering), which the cores do side by side
        let gather = |which: usize| {
            let (corner, sign) = if which < 2 { (0, 1.0) } else { (1, -1.0) };
            let mut m = Mat::<f64>::from_fn(faces, n, |r, k| {
                let (e, s) = at[r][corner];
                sign * s * h[k][e]
            });
            if which % 2 == 1 {
                times_small_in_place(&mut m, lambda);
            }
            m
        };
        let ((ar, ai), (br, bi)) = rayon::join(
            || rayon::join(|| gather(0), || gather(1)),
            || rayon::join(|| gather(2), || gather(3)),
        );
        Self::finish(mesh, faces, [ar, ai, br, bi])
    }

    /// The area form, the basis energies and the whitening of the per-face edge values
    /// `[Re a, Im a, Re b, Im b]` (`faces × n` each, not yet whitened).
    fn finish(
        mesh: &TriMesh,
        faces: usize,
        [ar, ai, br, bi]: [Mat<f64>; 4],
    ) -> Result<Self, GlobalError> {
        let n = ar.ncols();
        // C = Σ_f Q_f = ¼ (X + Xᵀ), X = Re aᵀ Im b − Im aᵀ Re b
        let (x, y) = rayon::join(|| transpose_times(&ar, &bi), || transpose_times(&ai, &br));
        let c: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                0.25 * (x[(i, j)] - y[(i, j)] + x[(j, i)] - y[(j, i)])
            })
            .collect();
        let (eig, _) = symmetric_eigen(&c, n);
        let (lo, hi) = eig
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
        if !(lo > AREA_FORM_MIN_RELATIVE_EIGENVALUE * hi) {
            return Err(GlobalError::DegenerateFormBasis {
                reason: "the layout area is not a positive definite form of the coefficients",
            });
        }
        let areas = conformap_operators::face_areas(mesh);
        let surface_area: f64 = areas[..faces].iter().sum();
        let s: Vec<f64> = areas[..faces].iter().map(|x| x / surface_area).collect();
        // basis form k: a_f = ½ Im(conj(a_fk) b_fk) over its total area C_kk
        let basis_energy = (0..n)
            .into_par_iter()
            .map(|k| {
                let (a_r, a_i) = (ar.col_as_slice(k), ai.col_as_slice(k));
                let (b_r, b_i) = (br.col_as_slice(k), bi.col_as_slice(k));
                let total = c[k * n + k];
                (0..faces)
                    .map(|f| (0.5 * (a_r[f] * b_i[f] - a_i[f] * b_r[f]) / total - s[f]).powi(2))
                    .sum()
            })
            .collect();
        // the whitening is applied to the coefficients and to the `n`-sized sums, never to
        // the `faces × n` matrices (four dense products of them per model, ~20 ms on
        // armadillo's 15-slit covering, saved)
        let w = symmetric_function(&c, n, |x| 1.0 / x.sqrt());
        let w_inv = symmetric_function(&c, n, f64::sqrt);
        Ok(Self {
            n,
            ar,
            ai,
            br,
            bi,
            s,
            w,
            w_inv,
            weight: 1.0,
            basis_energy,
        })
    }

    /// Every `stride`-th face (from face 0), weighted by `faces / sampled` so that the
    /// sums estimate the full ones: the coarse level of the two-level search (same
    /// whitening, so a coarse optimum is a start for the full energy).
    pub fn sample(&self, stride: usize) -> Self {
        let rows: Vec<usize> = (0..self.faces()).step_by(stride.max(1)).collect();
        let pick = |m: &Mat<f64>| Mat::<f64>::from_fn(rows.len(), self.n, |r, k| m[(rows[r], k)]);
        Self {
            n: self.n,
            ar: pick(&self.ar),
            ai: pick(&self.ai),
            br: pick(&self.br),
            bi: pick(&self.bi),
            s: rows.iter().map(|&f| self.s[f]).collect(),
            w: self.w.clone(),
            w_inv: self.w_inv.clone(),
            weight: self.weight * self.faces() as f64 / rows.len() as f64,
            basis_energy: self.basis_energy.clone(),
        }
    }

    /// Number of faces.
    pub fn faces(&self) -> usize {
        self.s.len()
    }

    /// Basis coefficients `λ = W μ`.
    pub fn coefficients(&self, mu: &[f64]) -> Vec<f64> {
        mat_vec(&self.w, mu)
    }

    /// Whitened coordinates `μ = C^{1/2} λ` of basis coefficients.
    pub fn whiten(&self, lambda: &[f64]) -> Vec<f64> {
        mat_vec(&self.w_inv, lambda)
    }

    /// The whitened edge values `[Re a, Im a, Re b, Im b]` (the matrices times `W`),
    /// built for the models that need every face's whitened area form (the moments, the
    /// per-face products).
    pub fn whitened(&self) -> Whitened {
        let mut m = [&self.ar, &self.ai, &self.br, &self.bi].map(Mat::clone);
        for x in &mut m {
            times_small_in_place(x, &self.w);
        }
        Whitened(m)
    }

    /// The block ranges of the direct sums.
    fn blocks(&self) -> Vec<(usize, usize)> {
        (0..self.faces())
            .step_by(DIRECT_BLOCK_FACES)
            .map(|s| (s, (s + DIRECT_BLOCK_FACES).min(self.faces()) - s))
            .collect()
    }

    /// `A_f`, `B_f` (real and imaginary parts) of the rows `start..start + len` for the
    /// basis coefficients `lambda = W μ`.
    fn edge_values(&self, lambda: &[f64], start: usize, len: usize) -> [Vec<f64>; 4] {
        [&self.ar, &self.ai, &self.br, &self.bi].map(|m| {
            let mut out = vec![0.0; len];
            for (k, &c) in lambda.iter().enumerate() {
                let col = &m.col_as_slice(k)[start..start + len];
                for (o, x) in out.iter_mut().zip(col) {
                    *o += c * x;
                }
            }
            out
        })
    }

    /// `E(μ) = Σ_f (a_f/|μ|² − s_f)²` for `μ ≠ 0` (any length), summed over the faces.
    pub fn energy(&self, mu: &[f64]) -> f64 {
        let norm2: f64 = mu.iter().map(|x| x * x).sum();
        let lambda = self.coefficients(mu);
        let parts: Vec<f64> = self
            .blocks()
            .par_iter()
            .map(|&(start, len)| {
                let [a_r, a_i, b_r, b_i] = self.edge_values(&lambda, start, len);
                (0..len)
                    .map(|r| {
                        let a = 0.5 * (a_r[r] * b_i[r] - a_i[r] * b_r[r]);
                        (a / norm2 - self.s[start + r]).powi(2)
                    })
                    .sum::<f64>()
            })
            .collect();
        self.weight * parts.iter().sum::<f64>()
    }

    /// The aggregates of `uniform.rs` at a unit `μ`, summed over the faces (blocks in
    /// parallel, added in their order).
    pub fn aggregates(&self, mu: &[f64]) -> Aggregates {
        let n = self.n;
        let lambda = self.coefficients(mu);
        let parts: Vec<Partial> = self
            .blocks()
            .par_iter()
            .map(|&(start, len)| self.block_aggregates(&lambda, start, len))
            .collect();
        let mut total = Partial::zeros(n);
        for p in &parts {
            total.add(p);
        }
        total.scale(self.weight);
        // the sums over the unwhitened basis, whitened: `v ↦ W v`, `M ↦ W M W` (`W`
        // symmetric)
        total.whiten(&self.w);
        let Partial {
            energy,
            rho,
            a2,
            big_r,
            au,
            uu,
            x,
        } = total;
        let rq = (0..n * n)
            .map(|k| 0.25 * (x[(k / n, k % n)] + x[(k % n, k / n)]))
            .collect();
        Aggregates {
            energy,
            rho,
            a2,
            big_r,
            au,
            uu: row_major(&uu),
            rq,
        }
    }

    /// `E` and `∇E = 4 (R − ρ μ)` at a unit `μ`, summed over the faces in `O(F n)` (no
    /// Hessian): `R_k = Σ_f r_f u_{f,k}` with
    /// `u_{f,k} = ¼ (Re a_k Im B − Im a_k Re B + Re A Im b_k − Im A Re b_k)`, so
    /// `R = ¼ (Re aᵀ(r Im B) − Im aᵀ(r Re B) + Im bᵀ(r Re A) − Re bᵀ(r Im A))`.
    pub fn first_order(&self, mu: &[f64]) -> (f64, Vec<f64>) {
        let n = self.n;
        let lambda = self.coefficients(mu);
        let parts: Vec<(f64, f64, Vec<f64>)> = self
            .blocks()
            .par_iter()
            .map(|&(start, len)| {
                let [a_r, a_i, b_r, b_i] = self.edge_values(&lambda, start, len);
                let (mut energy, mut rho) = (0.0, 0.0);
                let mut weighted = [
                    vec![0.0; len],
                    vec![0.0; len],
                    vec![0.0; len],
                    vec![0.0; len],
                ];
                for r in 0..len {
                    let area = 0.5 * (a_r[r] * b_i[r] - a_i[r] * b_r[r]);
                    let res = area - self.s[start + r];
                    energy += res * res;
                    rho += res * area;
                    weighted[0][r] = res * b_i[r];
                    weighted[1][r] = -res * b_r[r];
                    weighted[2][r] = res * a_r[r];
                    weighted[3][r] = -res * a_i[r];
                }
                let dot = |m: &Mat<f64>, k: usize, w: &[f64]| -> f64 {
                    m.col_as_slice(k)[start..start + len]
                        .iter()
                        .zip(w)
                        .map(|(x, y)| x * y)
                        .sum()
                };
                let big_r = (0..n)
                    .map(|k| {
                        0.25 * (dot(&self.ar, k, &weighted[0])
                            + dot(&self.ai, k, &weighted[1])
                            + dot(&self.bi, k, &weighted[2])
                            + dot(&self.br, k, &weighted[3]))
                    })
                    .collect();
                (energy, rho, big_r)
            })
            .collect();
        let (mut energy, mut rho, mut big_r) = (0.0, 0.0, vec![0.0; n]);
        for (e, p, r) in &parts {
            energy += e;
            rho += p;
            for (a, b) in big_r.iter_mut().zip(r) {
                *a += b;
            }
        }
        let c = self.weight;
        let big_r = mat_vec(&self.w, &big_r);
        let gradient = (0..n).map(|i| 4.0 * c * (big_r[i] - rho * mu[i])).collect();
        (c * energy, gradient)
    }

    /// The six sums of [`crate::forms::optimal::uniform::EnergyModel::great_circle`] for
    /// unit, orthogonal `mu` and `w`: on face `f`, with `α`, `γ` the areas under `μ` and
    /// `w` and `β` the cross term `¼ (Im(conj(A_μ) B_w) + Im(conj(A_w) B_μ))`, the area at
    /// `cos θ μ + sin θ w` is `p + q cos 2θ + r sin 2θ` with `p = (α + γ)/2`,
    /// `q = (α − γ)/2`, `r = β`; the sums are `Σ (p − s)²`, `Σ (p − s) q`, `Σ (p − s) r`,
    /// `Σ q²`, `Σ r²`, `Σ q r` (weighted). One `O(F n)` pass.
    pub fn great_circle(&self, mu: &[f64], w: &[f64]) -> [f64; 6] {
        let (lm, lw) = (self.coefficients(mu), self.coefficients(w));
        let parts: Vec<[f64; 6]> = self
            .blocks()
            .par_iter()
            .map(|&(start, len)| {
                let [mr, mi, nr, ni] = self.edge_values(&lm, start, len);
                let [wr, wi, vr, vi] = self.edge_values(&lw, start, len);
                let mut c = [0.0; 6];
                for r in 0..len {
                    let alpha = 0.5 * (mr[r] * ni[r] - mi[r] * nr[r]);
                    let gamma = 0.5 * (wr[r] * vi[r] - wi[r] * vr[r]);
                    let beta =
                        0.25 * ((mr[r] * vi[r] - mi[r] * vr[r]) + (wr[r] * ni[r] - wi[r] * nr[r]));
                    let p = 0.5 * (alpha + gamma) - self.s[start + r];
                    let q = 0.5 * (alpha - gamma);
                    let rr = beta;
                    c[0] += p * p;
                    c[1] += p * q;
                    c[2] += p * rr;
                    c[3] += q * q;
                    c[4] += rr * rr;
                    c[5] += q * rr;
                }
                c
            })
            .collect();
        let mut total = [0.0; 6];
        for p in &parts {
            for (t, x) in total.iter_mut().zip(p) {
                *t += x;
            }
        }
        total.map(|x| x * self.weight)
    }

    fn block_aggregates(&self, lambda: &[f64], start: usize, len: usize) -> Partial {
        let n = self.n;
        let [a_r, a_i, b_r, b_i] = self.edge_values(lambda, start, len);
        fn col(m: &Mat<f64>, k: usize, start: usize, len: usize) -> &[f64] {
            &m.col_as_slice(k)[start..start + len]
        }
        let area: Vec<f64> = (0..len)
            .map(|r| 0.5 * (a_r[r] * b_i[r] - a_i[r] * b_r[r]))
            .collect();
        let res: Vec<f64> = (0..len).map(|r| area[r] - self.s[start + r]).collect();
        // u_f = ¼ (Re a Im B − Im a Re B + Re A Im b − Im A Re b); the two terms of
        // X = Re aᵀ (r Im b) − Im aᵀ (r Re b), the left factors read in place
        let mut u = Mat::<f64>::zeros(len, n);
        let mut rhs_i = Mat::<f64>::zeros(len, n);
        let mut rhs_r = Mat::<f64>::zeros(len, n);
        for k in 0..n {
            let (ar, ai, br, bi) = (
                col(&self.ar, k, start, len),
                col(&self.ai, k, start, len),
                col(&self.br, k, start, len),
                col(&self.bi, k, start, len),
            );
            for (r, uk) in u.col_as_slice_mut(k).iter_mut().enumerate() {
                *uk = 0.25 * (ar[r] * b_i[r] - ai[r] * b_r[r] + a_r[r] * bi[r] - a_i[r] * br[r]);
            }
            let (qi, qr) = (rhs_i.col_as_slice_mut(k), rhs_r.col_as_slice_mut(k));
            for r in 0..len {
                qi[r] = res[r] * bi[r];
                qr[r] = -res[r] * br[r];
            }
        }
        let mut p = Partial::zeros(n);
        for r in 0..len {
            p.energy += res[r] * res[r];
            p.rho += res[r] * area[r];
            p.a2 += area[r] * area[r];
        }
        for k in 0..n {
            let c = u.col_as_slice(k);
            p.big_r[k] = c.iter().zip(&res).map(|(x, y)| x * y).sum();
            p.au[k] = c.iter().zip(&area).map(|(x, y)| x * y).sum();
        }
        gemm(&mut p.uu, u.transpose(), u.as_ref(), 1.0);
        let (ar, ai) = (
            self.ar.as_ref().subrows(start, len),
            self.ai.as_ref().subrows(start, len),
        );
        gemm(&mut p.x, ar.transpose(), rhs_i.as_ref(), 1.0);
        gemm(&mut p.x, ai.transpose(), rhs_r.as_ref(), 1.0);
        p
    }
}

/// The whitened edge values of a [`FaceForms`] (see [`FaceForms::whitened`]).
pub struct Whitened([Mat<f64>; 4]);

impl Whitened {
    /// `Q̃_f[i][j] = ¼ (Im(conj(a_i) b_j) + Im(conj(a_j) b_i))`.
    pub fn area_form_entry(&self, f: usize, i: usize, j: usize) -> f64 {
        let [ar, ai, br, bi] = &self.0;
        let m = |k: usize, l: usize| ar[(f, k)] * bi[(f, l)] - ai[(f, k)] * br[(f, l)];
        0.25 * (m(i, j) + m(j, i))
    }
}

/// One block's share of [`Aggregates`] (`x`: `Σ r_f (Re a Im bᵀ − Im a Re bᵀ)`).
struct Partial {
    energy: f64,
    rho: f64,
    a2: f64,
    big_r: Vec<f64>,
    au: Vec<f64>,
    uu: Mat<f64>,
    x: Mat<f64>,
}

impl Partial {
    fn zeros(n: usize) -> Self {
        Self {
            energy: 0.0,
            rho: 0.0,
            a2: 0.0,
            big_r: vec![0.0; n],
            au: vec![0.0; n],
            uu: Mat::zeros(n, n),
            x: Mat::zeros(n, n),
        }
    }

    fn scale(&mut self, c: f64) {
        self.energy *= c;
        self.rho *= c;
        self.a2 *= c;
        for x in self.big_r.iter_mut().chain(self.au.iter_mut()) {
            *x *= c;
        }
        for j in 0..self.uu.ncols() {
            for i in 0..self.uu.nrows() {
                self.uu[(i, j)] *= c;
                self.x[(i, j)] *= c;
            }
        }
    }

    /// The sums of the unwhitened basis made those of the whitened one: `v ↦ W v` for
    /// `R`, `au`; `M ↦ W M W` for `uu` and `x` (`W` symmetric, row-major).
    fn whiten(&mut self, w: &[f64]) {
        let n = self.big_r.len();
        self.big_r = mat_vec(w, &self.big_r);
        self.au = mat_vec(w, &self.au);
        let wm = Mat::<f64>::from_fn(n, n, |i, j| w[i * n + j]);
        for m in [&mut self.uu, &mut self.x] {
            let t = &wm * &*m;
            *m = &t * &wm;
        }
    }

    fn add(&mut self, o: &Self) {
        self.energy += o.energy;
        self.rho += o.rho;
        self.a2 += o.a2;
        for (a, b) in self.big_r.iter_mut().zip(&o.big_r) {
            *a += b;
        }
        for (a, b) in self.au.iter_mut().zip(&o.au) {
            *a += b;
        }
        for j in 0..self.uu.ncols() {
            for i in 0..self.uu.nrows() {
                self.uu[(i, j)] += o.uu[(i, j)];
                self.x[(i, j)] += o.x[(i, j)];
            }
        }
    }
}

/// `M v` for a row-major `n × n` matrix.
fn mat_vec(m: &[f64], v: &[f64]) -> Vec<f64> {
    let n = v.len();
    (0..n)
        .map(|i| (0..n).map(|j| m[i * n + j] * v[j]).sum())
        .collect()
}

/// Each of the first `faces` faces' two edges from its first corner (`v0 → v1`, `v0 → v2`)
/// and their orientations, looked up once for all forms.
fn face_edges(edges: &EdgeIndex, faces: usize) -> Vec<[(usize, f64); 2]> {
    (0..faces)
        .map(|f| [3 * f, 3 * f + 2].map(|h| (edges.edge_of[h] as usize, edges.sign(h))))
        .collect()
}
