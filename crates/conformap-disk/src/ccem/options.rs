//! Options of [`crate::ccem`]: the descent variant, stopping rules, Wolfe constants, the
//! bijectivity guard and the Schur-complement path, each with its default and why.

use crate::ccem::schur::SchurMode;
use crate::cem::CemOptions;
use crate::options::{at_least_one, finite_non_negative, invalid, with_setters};
use crate::DiskError;

/// The descent direction of CCEM.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum CcemVariant {
    /// Steepest descent with the quadratic step (Algorithm 4.1).
    Gradient,
    /// BFGS on the angles (Algorithm 4.2), safeguarded by the same line search (default).
    #[default]
    QuasiNewton,
}

/// Where CCEM starts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum CcemStart {
    /// The boundary of the CEM map with these options (the paper: 20 iterations, tolerance
    /// 1e-6 relative). Costs the Angenent factorization plus one interior solve and one
    /// `L_BB` solve per CEM iteration.
    Cem(CemOptions),
    /// The arc-length boundary of [`crate::harmonic_arc_length`]: no work at all, but more
    /// CCEM iterations, and a worse local minimum on alligator.
    ArcLength,
    /// The boundary of Angenent's initial map (CEM Eq. 13–16), computed from the dense Schur
    /// complement `A` that CCEM forms anyway: its right-hand side rides along in the pass
    /// that forms `A`, then one dense solve with `A` (`n_B³/3` flops) — no second
    /// factorization and no CEM iterations. (With the implicit `A` it costs the second
    /// factorization of [`crate::initial::angenent_boundary`].)
    Angenent,
    /// The discrete harmonic measure of the boundary seen from an interior vertex near the
    /// centre (the boundary of the conformal map sending that vertex to 0, in the
    /// continuum), then moved along the disk's Möbius automorphisms to the lowest `E_C`
    /// (see the `mobius_align` module notes in the crate docs): one solve with `L_II`,
    /// which rides along in the pass that forms the dense `A`, no dense solve, and a few
    /// products with `A`. Default: on the generated squares and disks it starts within
    /// 1e-3 relative of the minimum, where Angenent's map starts 3–30 % above it, and cuts
    /// CCEM-QN's iterations 49 → 3 (250k-face square), 29 → 1 (disk), 31 → 7 (hand.obj).
    HarmonicMeasure,
}

/// Options of [`crate::ccem`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CcemOptions {
    /// Descent direction. Default: [`CcemVariant::QuasiNewton`] (fewer iterations and
    /// line-search evaluations than the gradient method on every class-a mesh).
    pub variant: CcemVariant,
    /// Iteration cap. Default: 1000. Iterations cost boundary-sized work once `A` is
    /// dense, so the default runs to the energy tolerance, not to the papers' 20
    /// iterations; 1000 is a backstop that the class-a meshes stay far below.
    pub max_iter: usize,
    /// Relative energy-drop tolerance: the run stops at a Wolfe step that lowers `E_C` by
    /// at most `tol · E_C`. In the quasi-Newton variant such a step first restarts BFGS
    /// from `H₀` when it holds two or more pairs, and the run stops only when the fresh
    /// model meets the tolerance too (its first step, or the predicted decrease `−½ ∇E·d`
    /// of its preconditioned Newton step). Default: `1e-9`, chosen by measurement: with
    /// BFGS, on every class-a mesh it lands within 1e-6 (relative) of the energy converged
    /// at `1e-12`, at 5–30% fewer iterations (the goal was 0.5%); relative, because the
    /// papers' absolute `1e-7` is loose when `E_C ≈ 3e-3`.
    pub tol: f64,
    /// Sufficient-decrease constant `γ₁` of Eq. 4.7. Default: `1e-4`, the usual choice
    /// (Nocedal & Wright §3.1); the paper asks only `0 < γ₁ < γ₂ < 1`.
    pub gamma1: f64,
    /// Curvature constant `γ₂` of Eq. 4.9, `γ₁ < γ₂ < 1`. Default: `0.9`, the usual choice
    /// for Newton-like and gradient directions whose first trial step is well scaled (the
    /// quadratic step of Eq. 4.6, or 1 for quasi-Newton): most first trials are accepted.
    pub gamma2: f64,
    /// Fraction of the distance to the nearest boundary collision a step may take.
    /// Default: `0.99`, the paper's `ρ` (every gap keeps at least 1% of its length per
    /// step).
    pub rho: f64,
    /// Floor on the angle between consecutive boundary vertices, radians. Default:
    /// `1e-13`, about 140 units in the last place of an angle near `2π` (`8.9e-16`). Closer
    /// vertices are not resolved by f64 (`e^{iθ}` differ in their last bits), so the guard
    /// holds such gaps at the floor and says so in the report.
    pub min_gap: f64,
    /// Energy evaluations allowed per line search. Default: 30 (a search needs 1–3 on
    /// most steps).
    pub max_line_evals: usize,
    /// How the Schur complement is applied. Default: [`SchurMode::Auto`].
    pub schur: SchurMode,
    /// Starting boundary. Default: [`CcemStart::HarmonicMeasure`] (the paper starts from
    /// CEM, which costs a second factorization and 20 interior solves; the Möbius-aligned
    /// harmonic measure costs one more right-hand side in the pass that forms `A` and a few
    /// products, and CCEM-QN reaches the same minimum from it in 1–7 iterations on the
    /// generated meshes and most class-a meshes: see the crate README).
    pub start: CcemStart,
    /// Quasi-Newton memory (curvature pairs kept; 0 = all). Default: 0, every curvature
    /// pair of the run (the full BFGS of Algorithm 4.2, applied by the two-loop recursion
    /// in `O(k n_B)` per iteration).
    pub qn_memory: usize,
    /// Record every accepted step in [`crate::LineSearchReport::steps`] (for checking the Wolfe
    /// conditions). Default: `false`.
    pub record_steps: bool,
    /// Precondition the quasi-Newton variant with the exact Hessian of `E_C(θ)` at the
    /// start: BFGS's initial inverse Hessian `H₀` is that Hessian's inverse (factored once,
    /// `n_B³ / 6` multiply–adds) instead of `(sᵀy / yᵀy) I`, and the first step is the
    /// Newton step. Only with the dense Schur complement; also at a start whose gaps had to
    /// be repaired (alligator.obj: 151 iterations without, 49 with; igea_open.obj: 125
    /// without, 40 with, to a minimum 7.6e-5 lower). If a line search along a
    /// preconditioned direction finds no decrease, the preconditioner is dropped and the
    /// run continues as the plain Algorithm 4.2. Default: `true` (3–10× fewer iterations to
    /// the same minimum on the class-a meshes and the generated squares: see the crate
    /// README).
    pub hessian_preconditioner: bool,
    /// Boundary length from which the Hessian preconditioner is the cyclic band of the
    /// Hessian (half-width 128, factored by the sparse Cholesky in `n_B b²`) instead of the
    /// whole Hessian (dense modified `LBLᵀ`, `n_B³ / 3` flops: about twice the sparse
    /// factorization of `L_II` on a height field over a square). A descent preconditioned
    /// by the band re-aligns along the Möbius orbit at its stops (the band leaves out the
    /// far couplings that set those two soft directions) and goes on while that lowers
    /// `E_C`. Default: 2000. Measured (start + iterations, whole Hessian → band): 1M-face
    /// square (`n_B = 2,828`) 289 → 178 ms, 2M (4,000) 620 → 311 ms; at
    /// `n_B ≈ 1,000–1,500` the two cost the same or the band more (1M-face cap, 1,050:
    /// 30 → 35 ms; 250k square, 1,416: 54 → 57 ms). Every class-a mesh (`n_B ≤ 433`,
    /// maze's implicit `A` aside) keeps the whole Hessian.
    pub banded_hessian_min_nb: usize,
}

impl CcemOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        variant: CcemVariant::QuasiNewton,
        max_iter: 1000,
        tol: 1e-9,
        gamma1: 1e-4,
        gamma2: 0.9,
        rho: 0.99,
        min_gap: 1e-13,
        max_line_evals: 30,
        schur: SchurMode::Auto,
        start: CcemStart::HarmonicMeasure,
        qn_memory: 0,
        record_steps: false,
        hessian_preconditioner: true,
        banded_hessian_min_nb: 2000,
    };

    with_setters! {
        with_variant(variant: CcemVariant);
        with_max_iter(max_iter: usize);
        with_tol(tol: f64);
    }

    /// Sets the Wolfe constants [`Self::gamma1`] and [`Self::gamma2`].
    #[must_use]
    pub fn with_wolfe(mut self, gamma1: f64, gamma2: f64) -> Self {
        self.gamma1 = gamma1;
        self.gamma2 = gamma2;
        self
    }

    with_setters! {
        with_rho(rho: f64);
        with_min_gap(min_gap: f64);
        with_max_line_evals(max_line_evals: usize);
        with_schur(schur: SchurMode);
        with_start(start: CcemStart);
        with_qn_memory(qn_memory: usize);
        with_hessian_preconditioner(hessian_preconditioner: bool);
        with_banded_hessian_min_nb(banded_hessian_min_nb: usize);
        with_record_steps(record_steps: bool);
    }

    /// Checks the ranges: `tol ≥ 0`, `0 < γ₁ < γ₂ < 1`, `0 < ρ ≤ 1`, `min_gap ≥ 0`,
    /// `max_line_evals ≥ 1`, all finite.
    ///
    /// # Errors
    /// [`DiskError::InvalidOption`] naming the option.
    pub fn validate(&self) -> Result<(), DiskError> {
        finite_non_negative("tol", self.tol)?;
        if !(self.gamma1 > 0.0 && self.gamma1 < self.gamma2 && self.gamma2 < 1.0) {
            return invalid("gamma1/gamma2", "need 0 < gamma1 < gamma2 < 1");
        }
        if !(self.rho > 0.0 && self.rho <= 1.0) {
            return invalid("rho", "need 0 < rho ≤ 1");
        }
        finite_non_negative("min_gap", self.min_gap)?;
        at_least_one("max_line_evals", self.max_line_evals)
    }
}

impl Default for CcemOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
