//! One solve of Eq. 34 at a given λ (or the hard limit): the λ-dependent factor, the
//! boundary sweeps on the circle, the interior, and the fold count.

use conformap_disk::DiskProblem;
use num_complex::Complex64;

use super::anchor::Anchor;
use super::boundary::{BoundaryEnergy, SweepOutcome};
use super::system::LandmarkSystem;
use crate::MorphError;

/// One solve of Eq. 34.
pub(super) struct Attempt {
    /// The map of every vertex.
    pub h: Vec<Complex64>,
    /// Its boundary values (the start of the next solve's sweeps).
    pub hb: Vec<Complex64>,
    /// Faces folded by `h` that `g` does not fold (a disk map squeezed to rounding, as
    /// on the maze, has faces folded before any registration; no λ unfolds those).
    pub folds: usize,
    /// What the sweeps did.
    pub outcome: SweepOutcome,
}

/// Everything the solves of one registration share.
pub(super) struct Solver<'a, 'p, 'm> {
    pub problem: &'p DiskProblem<'m>,
    pub system: LandmarkSystem<'p, 'm>,
    /// The solves are measured from the normalized disk map `g`: with the targets at `g`'s
    /// own landmarks they return `g`.
    pub anchor: Anchor<'a>,
    /// `t_j − g(l_j)`.
    pub offsets: Vec<Complex64>,
    pub targets: &'a [Complex64],
    /// Orientation of `g`'s boundary loop (`+1` counter-clockwise).
    pub sigma: f64,
    /// The faces `g` folds (see [`folded_by`]).
    pub folded_in_g: Vec<bool>,
    pub sweep_tol: f64,
    /// The surface's index, for errors.
    pub surface: usize,
}

impl Solver<'_, '_, '_> {
    /// Eq. 34 with weight `lambda` (`None`: the hard limit), the sweeps started at `start`
    /// and capped at `sweeps`; `pin` puts boundary landmarks exactly on the circle at
    /// their targets' direction (hard mode).
    pub fn attempt(
        &self,
        lambda: Option<f64>,
        pin: bool,
        start: &[Complex64],
        sweeps: usize,
    ) -> Result<Attempt, MorphError> {
        let surface = self.surface;
        let op = |source| MorphError::Operator { surface, source };
        let inv_mu = lambda.map_or(0.0, |l| 0.5 / l);
        let pen = self.system.penalized(inv_mu).map_err(op)?;
        let w_d = self.system.linear_term(&pen, &self.offsets);
        let w = self.anchor.linear_term(&pen.s, &w_d);
        let nb = start.len();
        let mut pull = vec![Complex64::new(0.0, 0.0); nb];
        let mut pinned = vec![false; nb];
        let mut hb = start.to_vec();
        for &(j, b) in &self.system.boundary {
            match lambda {
                Some(l) if !pin => pull[b] -= 2.0 * l * self.targets[j],
                _ => {
                    pinned[b] = true;
                    let t = self.targets[j];
                    hb[b] = if t.norm() > 0.0 { t / t.norm() } else { hb[b] };
                }
            }
        }
        let energy = BoundaryEnergy {
            s: &pen.s,
            w: &w,
            pull: &pull,
            pinned: &pinned,
            sigma: self.sigma,
        };
        let outcome = energy.sweep(&mut hb, sweeps, self.sweep_tol);
        let d = self
            .system
            .full_map(&pen, &self.anchor.displacement(&hb), &self.offsets);
        let h = self.anchor.map(&d, &hb);
        if let Some(vertex) = h
            .iter()
            .position(|z| !(z.re.is_finite() && z.im.is_finite()))
        {
            return Err(MorphError::NonFinite { surface, vertex });
        }
        let folds = folded_by(self.problem.mesh().faces(), &h, self.sigma)
            .iter()
            .zip(&self.folded_in_g)
            .filter(|&(&now, &before)| now && !before)
            .count();
        Ok(Attempt {
            h,
            hb,
            folds,
            outcome,
        })
    }
}

/// For every face: whether its image under `map` has signed area of the wrong sign
/// (against `sigma`) or zero, as [`folded_faces`] counts them.
pub(super) fn folded_by(faces: &[[u32; 3]], map: &[Complex64], sigma: f64) -> Vec<bool> {
    faces
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| map[v as usize]);
            let area = ((b - a).conj() * (c - a)).im;
            !(sigma * area > 0.0)
        })
        .collect()
}

/// Faces whose image under `map` has signed area of the wrong sign (against `sigma`, the
/// orientation of the boundary loop) or zero.
pub fn folded_faces(faces: &[[u32; 3]], map: &[Complex64], sigma: f64) -> usize {
    faces
        .iter()
        .filter(|f| {
            let [a, b, c] = f.map(|v| map[v as usize]);
            let area = ((b - a).conj() * (c - a)).im;
            !(sigma * area > 0.0)
        })
        .count()
}
