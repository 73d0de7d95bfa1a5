//! The linear algebra of the registration (CEM Eq. 34) on one surface, reduced to its
//! boundary.
//!
//! With `E_D(h) = ½ hᴴ L h` (CEM Eq. 5) and `μ = 2λ`, the interior of the minimizer of
//! `E_D(h) + λ Σ_j |h(l_j) − t_j|²` for given boundary values `h_B` solves
//! `(L_II + μ PᵀP) h_I = −L_IB h_B + μ Pᵀ t`, `P` selecting the interior landmarks. The
//! disk problem's factorization `F` of `L_II` is reused for every λ through the
//! Sherman–Morrison–Woodbury identity: with `Z = F⁻¹Pᵀ` (one solve per landmark),
//! `G = PZ` and `M = G + I/μ` (`m × m`, `m` the number of landmarks),
//!
//! `h_I = y + Z M⁻¹ (t − P y)`, `y = F⁻¹(−L_IB h_B)`,
//!
//! and the energy as a function of `h_B` alone is `½ h_Bᴴ S_λ h_B + Re(h_Bᴴ w) + c` with
//! `S_λ = S₀ + Y M⁻¹ Yᵀ`, `S₀ = L_BB − L_BI F⁻¹ L_IB` (the harmonic Schur complement),
//! `Y = L_BI Z` and `w = Y M⁻¹ t`. The hard constraint `P h_I = t` is the limit
//! `1/μ = 0` (`M = G`, Lagrange multipliers). Changing λ refactors only the `m × m` matrix
//! `M`; the sparse factor is never touched.

use conformap_disk::DiskProblem;
use conformap_operators::{DenseCholesky, OperatorError};
use num_complex::Complex64;

/// The λ-independent part: `Z`, `G`, `Y`, `S₀` and where the landmarks are.
#[derive(Debug)]
pub(crate) struct LandmarkSystem<'p, 'm> {
    problem: &'p DiskProblem<'m>,
    /// For every interior landmark: (position in the landmark list, interior index).
    pub interior: Vec<(usize, usize)>,
    /// For every boundary landmark: (position in the landmark list, boundary index).
    pub boundary: Vec<(usize, usize)>,
    /// `Z = F⁻¹ Pᵀ`, `n_I × m`, column-major.
    z: Vec<f64>,
    /// `G = P Z`, `m × m`, column-major.
    g: Vec<f64>,
    /// `Y = L_BI Z`, `n_B × m`, column-major.
    y: Vec<f64>,
    /// `S₀`, `n_B × n_B`, column-major.
    pub s0: Vec<f64>,
}

/// The λ-dependent part: `M⁻¹` applied through its factor, `S_λ`.
#[derive(Debug)]
pub(crate) struct Penalized {
    m_factor: Option<DenseCholesky>,
    /// `S_λ`, `n_B × n_B`, column-major.
    pub s: Vec<f64>,
}

impl<'p, 'm> LandmarkSystem<'p, 'm> {
    /// Builds `Z`, `G`, `Y` and `S₀` for the landmarks `vertices` of `problem`'s mesh.
    pub fn new(problem: &'p DiskProblem<'m>, vertices: &[u32]) -> Result<Self, OperatorError> {
        let part = problem.partition();
        let blocks = problem.blocks();
        let factor = problem.interior_factor();
        let ni = part.interior.len();
        let nb = part.boundary.len();
        let mut interior = Vec::new();
        let mut boundary = Vec::new();
        for (j, &v) in vertices.iter().enumerate() {
            let local = part.local[v as usize] as usize;
            if part.is_interior[v as usize] {
                interior.push((j, local));
            } else {
                boundary.push((j, local));
            }
        }
        let m = interior.len();
        let mut z = vec![0.0; ni * m];
        for (c, &(_, i)) in interior.iter().enumerate() {
            z[c * ni + i] = 1.0;
        }
        factor.solve_in_place(&mut z, m);
        let mut g = vec![0.0; m * m];
        for c in 0..m {
            for (r, &(_, i)) in interior.iter().enumerate() {
                g[c * m + r] = z[c * ni + i];
            }
        }
        // exactly symmetric (the solves agree to rounding only)
        for c in 0..m {
            for r in 0..c {
                let avg = 0.5 * (g[c * m + r] + g[r * m + c]);
                g[c * m + r] = avg;
                g[r * m + c] = avg;
            }
        }
        let mut y = vec![0.0; nb * m];
        for (b, col) in blocks.ib.outer_iterator().enumerate() {
            for c in 0..m {
                y[c * nb + b] = col.iter().map(|(i, &v)| v * z[c * ni + i]).sum();
            }
        }
        let gram = factor.inverse_gram(&blocks.ib)?;
        let mut s0: Vec<f64> = gram.values.iter().map(|v| -v).collect();
        for (c, col) in blocks.bb.outer_iterator().enumerate() {
            for (r, &v) in col.iter() {
                s0[c * nb + r] += v;
            }
        }
        Ok(Self {
            problem,
            interior,
            boundary,
            z,
            g,
            y,
            s0,
        })
    }

    /// Number of boundary vertices.
    pub fn nb(&self) -> usize {
        self.problem.partition().boundary.len()
    }

    /// `M = G + inv_mu · I` factored and `S_λ` formed. `inv_mu = 1/(2λ)`, 0 for the hard
    /// constraint.
    pub fn penalized(&self, inv_mu: f64) -> Result<Penalized, OperatorError> {
        let m = self.interior.len();
        let nb = self.nb();
        let mut s = self.s0.clone();
        if m == 0 {
            return Ok(Penalized { m_factor: None, s });
        }
        let mut mm = self.g.clone();
        for k in 0..m {
            mm[k * m + k] += inv_mu;
        }
        let chol = DenseCholesky::factor(mm, m, 1)?;
        // X = M⁻¹ Yᵀ (m × nb), then S += Y X
        let mut x = vec![0.0; m * nb];
        for b in 0..nb {
            for c in 0..m {
                x[b * m + c] = self.y[c * nb + b];
            }
        }
        chol.solve_in_place(&mut x, nb);
        for col in 0..nb {
            for c in 0..m {
                let xc = x[col * m + c];
                let yc = &self.y[c * nb..(c + 1) * nb];
                let sc = &mut s[col * nb..(col + 1) * nb];
                for (sr, &yr) in sc.iter_mut().zip(yc) {
                    *sr += yr * xc;
                }
            }
        }
        Ok(Penalized {
            m_factor: Some(chol),
            s,
        })
    }

    /// The interior targets `t` of the interior landmarks (in [`Self::interior`] order).
    fn interior_targets(&self, targets: &[Complex64]) -> Vec<Complex64> {
        self.interior.iter().map(|&(j, _)| targets[j]).collect()
    }

    /// `w = Y M⁻¹ t` (boundary-sized).
    pub fn linear_term(&self, pen: &Penalized, targets: &[Complex64]) -> Vec<Complex64> {
        let nb = self.nb();
        let Some(chol) = &pen.m_factor else {
            return vec![Complex64::new(0.0, 0.0); nb];
        };
        let c = solve_m(chol, &self.interior_targets(targets));
        (0..nb)
            .map(|b| {
                c.iter()
                    .enumerate()
                    .map(|(k, &ck)| ck * self.y[k * nb + b])
                    .sum()
            })
            .collect()
    }

    /// The whole map: the interior `y + Z M⁻¹ (t − P y)` for the boundary values `hb`,
    /// scattered with `hb` into vertex order.
    pub fn full_map(
        &self,
        pen: &Penalized,
        hb: &[Complex64],
        targets: &[Complex64],
    ) -> Vec<Complex64> {
        let part = self.problem.partition();
        let ni = part.interior.len();
        let rhs: Vec<Complex64> = self
            .problem
            .blocks()
            .ib_mul(hb)
            .into_iter()
            .map(|v| -v)
            .collect();
        let mut hi = self.problem.interior_factor().solve_complex(&rhs);
        if let Some(chol) = &pen.m_factor {
            let r: Vec<Complex64> = self
                .interior
                .iter()
                .map(|&(j, i)| targets[j] - hi[i])
                .collect();
            let c = solve_m(chol, &r);
            for (k, &ck) in c.iter().enumerate() {
                let zk = &self.z[k * ni..(k + 1) * ni];
                for (h, &zv) in hi.iter_mut().zip(zk) {
                    *h += ck * zv;
                }
            }
        }
        part.assemble(&hi, hb)
    }
}

/// `M⁻¹ r` for complex `r` (real and imaginary parts as two columns).
fn solve_m(chol: &DenseCholesky, r: &[Complex64]) -> Vec<Complex64> {
    let m = r.len();
    let mut buf: Vec<f64> = r
        .iter()
        .map(|z| z.re)
        .chain(r.iter().map(|z| z.im))
        .collect();
    chol.solve_in_place(&mut buf, 2);
    (0..m).map(|k| Complex64::new(buf[k], buf[m + k])).collect()
}
