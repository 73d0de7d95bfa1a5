//! The registration measured from the surface's own normalized disk map `g`, so that a
//! surface registered onto its own landmark positions is left exactly where it is.
//!
//! Why: the energy of Eq. 34 with the boundary sliding on the circle,
//! `E_C(h) + λ Σ_j |h(l_j) − t_j|²` (`E_C = E_D − A`, see `boundary`), is minimized by the
//! discrete conformal map only up to the tolerance of the disk method, and the
//! normalization `m₁` (a Möbius transform) does not keep a discrete map harmonic. `g` is
//! therefore not a critical point of the registration energy: registered with its own
//! landmark values as targets, the boundary sweeps slide it along the energy's nearly flat
//! Möbius directions (measured: up to 49 % of the diagonal on woody, 7 % on spothead) and
//! a morph of a surface onto itself was not the identity.
//!
//! The fix tilts the energy by the linear term that makes `g` critical: with `c = ∇E_C(g)`
//! (interior part `r_I = (L g)_I`, boundary part tangent to the circle), the registration
//! minimizes `E_C(h) − Re⟨c, h⟩ + λ Σ_j |h(l_j) − t_j|²`. Written for the displacement
//! `d = h − g`, the interior is `h_I = g_I + d_I` with `d_I` the landmark-corrected
//! harmonic extension of `d_B` towards the offset targets `t_j − g(l_j)` (the linear
//! system of `system`, unchanged), and the boundary-reduced energy keeps its form
//! `½ h_Bᴴ S_λ h_B + Re(h_Bᴴ w) + const` with `w = w_d + q_B − S_λ g_B − c_B^⊤` (`w_d` the
//! linear term for the offset targets, `q_B = (L g)_B`, `c_B^⊤` the tangential part of the
//! boundary gradient of `E_C` at `g`). With `t_j = g(l_j)`: `d = 0` solves the interior
//! exactly and every one-vertex minimization of the sweeps returns `g_b`, so `h = g` to
//! rounding. The tilt is of the size of the disk method's residual, so registrations of
//! different surfaces are changed by that much only.

use conformap_disk::DiskProblem;
use num_complex::Complex64;

/// `g` and the linear term that makes it a critical point of the registration energy.
pub(crate) struct Anchor<'g> {
    /// `g(v)` for every vertex.
    g: &'g [Complex64],
    /// `g` on the boundary, in the partition's boundary order.
    pub gb: Vec<Complex64>,
    /// `q_B − c_B^⊤` per boundary vertex (the part of `w` that does not depend on λ).
    tilt: Vec<Complex64>,
    /// For every vertex: its index within the boundary (`None` for interior vertices).
    boundary_index: Vec<Option<usize>>,
}

impl<'g> Anchor<'g> {
    /// The anchor of `g` on `problem`'s mesh; `sigma` is the orientation of `g`'s boundary
    /// loop (`+1` counter-clockwise).
    pub fn new(problem: &DiskProblem<'_>, g: &'g [Complex64], sigma: f64) -> Self {
        let part = problem.partition();
        let blocks = problem.blocks();
        let gb = part.boundary_values(g);
        let gi = part.interior_values(g);
        // q_B = L_BI g_I + L_BB g_B
        let mut q = blocks.bi_mul(&gi);
        for (c, col) in blocks.bb.outer_iterator().enumerate() {
            for (r, &v) in col.iter() {
                q[r] += gb[c] * v;
            }
        }
        let nb = gb.len();
        let half_i = Complex64::new(0.0, 0.5 * sigma);
        let tilt = (0..nb)
            .map(|b| {
                let (prev, next) = (gb[(b + nb - 1) % nb], gb[(b + 1) % nb]);
                // the boundary gradient of E_C = E_D − A at g, and its part along the
                // circle (g_b is a unit vector: i g_b Im(c ḡ_b))
                let c = q[b] - half_i * (prev - next);
                let tangential = Complex64::new(0.0, (c * gb[b].conj()).im) * gb[b];
                q[b] - tangential
            })
            .collect();
        let mut boundary_index = vec![None; g.len()];
        for (k, &v) in part.boundary.iter().enumerate() {
            boundary_index[v as usize] = Some(k);
        }
        Self {
            g,
            gb,
            tilt,
            boundary_index,
        }
    }

    /// The offset targets `t_j − g(l_j)` of the displacement.
    pub fn offsets(&self, vertices: &[u32], targets: &[Complex64]) -> Vec<Complex64> {
        vertices
            .iter()
            .zip(targets)
            .map(|(&v, &t)| t - self.g[v as usize])
            .collect()
    }

    /// The boundary displacement `h_B − g_B`.
    pub fn displacement(&self, hb: &[Complex64]) -> Vec<Complex64> {
        hb.iter().zip(&self.gb).map(|(&h, &g)| h - g).collect()
    }

    /// `w = w_d + q_B − S_λ g_B − c_B^⊤` for `S_λ` (`s`, column-major `n_B × n_B`) and the
    /// linear term `w_d` of the offset targets.
    pub fn linear_term(&self, s: &[f64], w_d: &[Complex64]) -> Vec<Complex64> {
        let nb = self.gb.len();
        let mut w: Vec<Complex64> = w_d.iter().zip(&self.tilt).map(|(&a, &b)| a + b).collect();
        for (c, &gc) in self.gb.iter().enumerate() {
            let col = &s[c * nb..(c + 1) * nb];
            for (wr, &sv) in w.iter_mut().zip(col) {
                *wr -= gc * sv;
            }
        }
        w
    }

    /// The registered map `g + d`, with the boundary exactly `hb` (on the circle).
    pub fn map(&self, d: &[Complex64], hb: &[Complex64]) -> Vec<Complex64> {
        self.g
            .iter()
            .zip(d)
            .zip(&self.boundary_index)
            .map(|((&g, &d), b)| b.map_or(g + d, |b| hb[b]))
            .collect()
    }
}
