//! The boundary of the registration slides along the unit circle: Gauss–Seidel sweeps of
//! exact one-vertex minimizations of the boundary-reduced energy.
//!
//! Why the conformal energy and not `E_D` alone: with the boundary free to slide on the
//! circle, `E_D` has no minimum worth having (it falls towards 0 as the boundary points
//! bunch together: a constant map has no Dirichlet energy). The sweep therefore minimizes
//! `E_D − A + λ Σ_j |h(l_j) − t_j|²`, `A` the area of the boundary polygon (CEM Eq. 7–8:
//! `E_C = E_D − A`). Every boundary polygon inscribed in the unit circle has `A = π` up to
//! its chord error `O(h²)`, so this is Eq. 34 up to a term constant to the discretization
//! error, and at λ = 0 its minimizer is the disk map itself (up to a Möbius transform).
//!
//! One vertex `b` with the others held: on the circle `|h_b| = 1` the energy is
//! `const + Re(h̄_b s_b)` with `s_b = Σ_{c≠b} S_bc h_c + w_b − ½ i σ (h_{b−1} − h_{b+1})
//! − 2λ Σ_{j: l_j = b} t_j` (σ = ±1, the orientation of the boundary loop), minimized
//! exactly by `h_b = −s_b/|s_b|`. Each update lowers the energy (or keeps it), so the
//! sweeps descend monotonically; they stop when no vertex moves more than the tolerance.
//! A move below the rounding of `s_b` is not taken ([`SWEEP_ROUNDING`]).

use num_complex::Complex64;

/// A one-vertex update moves `h_b` only when the move is larger than the rounding of its
/// `s_b`: `SWEEP_ROUNDING · (2 Σ_c |S_bc| + |w_b| + |pull_b| + 1) / |s_b|` radians,
/// `SWEEP_ROUNDING = 8 ε` (ε the f64 machine epsilon; the sum bounds the magnitude of the
/// terms added into `s_b`). A smaller move is noise: taking it would move a boundary that
/// is already at its minimum (e.g. a surface registered onto its own landmarks) by
/// rounding, which the 3D positions amplify where the disk map compresses the mesh by
/// many orders of magnitude (alligator: faces of area 1e-28 in the disk).
const SWEEP_ROUNDING: f64 = 8.0 * f64::EPSILON;

/// What the sweeps did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SweepOutcome {
    /// Sweeps performed.
    pub sweeps: usize,
    /// Whether the largest move of the last sweep was below the tolerance.
    pub converged: bool,
    /// Largest angle (radians) a vertex moved in the last sweep.
    pub last_move: f64,
}

/// The data of the boundary-reduced energy.
pub(crate) struct BoundaryEnergy<'a> {
    /// `S_λ`, column-major `nb × nb` (symmetric).
    pub s: &'a [f64],
    /// `w`.
    pub w: &'a [Complex64],
    /// `−2λ t_j` summed per boundary vertex (zero where no landmark), for the soft mode.
    pub pull: &'a [Complex64],
    /// Boundary vertices held fixed (hard-mode boundary landmarks).
    pub pinned: &'a [bool],
    /// +1 for a counter-clockwise boundary loop, −1 for clockwise.
    pub sigma: f64,
}

impl BoundaryEnergy<'_> {
    /// Gauss–Seidel sweeps on `h` (boundary values, on the unit circle), at most
    /// `max_sweeps`, until no vertex moves more than `tol` radians.
    pub fn sweep(&self, h: &mut [Complex64], max_sweeps: usize, tol: f64) -> SweepOutcome {
        let nb = h.len();
        let mut last_move = f64::INFINITY;
        let mut sweeps = 0;
        // sh[b] = Σ_c S_bc h_c, kept up to date as h changes
        let mut sh = vec![Complex64::new(0.0, 0.0); nb];
        for c in 0..nb {
            let col = &self.s[c * nb..(c + 1) * nb];
            for (acc, &s) in sh.iter_mut().zip(col) {
                *acc += h[c] * s;
            }
        }
        let half_i = Complex64::new(0.0, 0.5 * self.sigma);
        // the rounding of s_b: a move of h_b smaller than this angle is noise
        let noise: Vec<f64> = (0..nb)
            .map(|b| {
                let row: f64 = self.s[b * nb..(b + 1) * nb].iter().map(|v| v.abs()).sum();
                SWEEP_ROUNDING * (2.0 * row + self.w[b].norm() + self.pull[b].norm() + 1.0)
            })
            .collect();
        while sweeps < max_sweeps {
            sweeps += 1;
            let mut largest: f64 = 0.0;
            for b in 0..nb {
                if self.pinned[b] {
                    continue;
                }
                let sbb = self.s[b * nb + b];
                let prev = h[(b + nb - 1) % nb];
                let next = h[(b + 1) % nb];
                let s = sh[b] - h[b] * sbb + self.w[b] + self.pull[b] - half_i * (prev - next);
                let norm = s.norm();
                if !(norm > 0.0) {
                    continue;
                }
                let new = -s / norm;
                let delta = new - h[b];
                let moved = (new * h[b].conj()).arg().abs();
                largest = largest.max(moved);
                if moved <= noise[b] / norm {
                    continue;
                }
                let col = &self.s[b * nb..(b + 1) * nb];
                for (acc, &sv) in sh.iter_mut().zip(col) {
                    *acc += delta * sv;
                }
                h[b] = new;
            }
            last_move = largest;
            if largest <= tol {
                return SweepOutcome {
                    sweeps,
                    converged: true,
                    last_move,
                };
            }
        }
        SweepOutcome {
            sweeps,
            converged: false,
            last_move,
        }
    }
}
