//! A fold-free landmark warp of a registered disk: the landmarks are moved onto their
//! goals by a composition of small smooth displacements of the plane, each checked for
//! folds (halved when one would fold).
//!
//! Why a warp and not a larger λ in Eq. 34: the minimizer of `E_D + λ Σ|h(l_j) − t_j|²`
//! pulls a landmark with a point force, whose response is the discrete Green's function
//! (a `log r` singularity): when a landmark has to move more than a few triangle sizes,
//! the ring around it folds, whatever path λ takes to its final value (the system is
//! linear, so moving the constraints in steps with one operator ends where one step
//! does). A displacement field that is smooth at the landmarks and small per step does
//! not have that singularity, and the composition of near-identity maps stays a
//! bijection.
//!
//! One step: with `p_j` the landmarks' current positions and `δ_j` this step's share of
//! the way to the goals, the displacement of every point `x` of the disk is
//! `d(x) = (1 − |x|²) Σ_j c_j φ(|x − p_j| / ρ)`, with Wendland's compactly supported
//! `φ(r) = (1 − r)⁴ (4r + 1)` (C², positive definite in the plane, so the interpolation
//! conditions `d(p_i) = δ_i` have exactly one solution `c`) and the factor `1 − |x|²`
//! that keeps the unit circle (the boundary) in place. Every vertex moves by `d`; the
//! step is accepted when no face folds, otherwise it is halved. The last step puts the
//! landmarks exactly on their goals.

use conformap_operators::DenseCholesky;
use num_complex::Complex64;
use serde::Serialize;

use super::solve::folded_faces;

/// Support radius ρ of the warp's kernel, in units of the unit disk: `0.5`. The faces'
/// landmarks lie 0.05–0.4 apart in the normalized disks; a support of a few landmark
/// spacings spreads each landmark's move over its neighbourhood (smooth, small
/// gradients) while a landmark far away is not dragged along. Measured on the shared
/// faces (see the crate README): 0.3–0.8 give the same landmark errors and no folds.
pub const WARP_SUPPORT: f64 = 0.5;

/// Largest move of a landmark in one warp step, relative to [`WARP_SUPPORT`]: `0.05`.
/// The displacement's gradient is then of order 0.05–0.2 (far from the 1 at which a
/// step can fold), so steps are rarely halved; the shared faces need 10–25 steps.
pub const WARP_STEP: f64 = 0.05;

/// Cap on the warp's steps, accepted and rejected together: `1024` (a step halved 10
/// times over; the shared faces need under 30). At the cap the warp stops short of the
/// goals and the report says so.
pub const WARP_MAX_STEPS: usize = 1024;

/// Options of the landmark warp.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct WarpOptions {
    /// Kernel support radius ρ. Default: [`WARP_SUPPORT`].
    pub support: f64,
    /// Largest landmark move per step, relative to `support`. Default: [`WARP_STEP`].
    pub step: f64,
    /// Cap on the steps. Default: [`WARP_MAX_STEPS`].
    pub max_steps: usize,
}

impl WarpOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        support: WARP_SUPPORT,
        step: WARP_STEP,
        max_steps: WARP_MAX_STEPS,
    };
}

impl Default for WarpOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What the warp did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WarpReport {
    /// Steps accepted.
    pub steps: usize,
    /// Steps rejected (they would have folded a face) and halved.
    pub rejected: usize,
    /// Whether the landmarks reached their goals (false: the step cap stopped it).
    pub reached: bool,
    /// The largest distance (in the disk) a landmark was moved.
    pub largest_move: f64,
}

/// Wendland's `φ_{3,1}(r) = (1 − r)⁴ (4r + 1)` for `r < 1`, 0 beyond.
fn wendland(r: f64) -> f64 {
    if r >= 1.0 {
        0.0
    } else {
        let s = 1.0 - r;
        let s2 = s * s;
        s2 * s2 * (4.0 * r + 1.0)
    }
}

/// Moves the interior landmarks `landmarks[j]` (vertices of `faces`, positions `map`)
/// onto `goals[j]`, keeping the unit circle and every face's orientation `sigma`.
/// `active[j]` false leaves landmark `j` out (e.g. a boundary landmark, placed by the
/// boundary sweep). The map must not fold on entry; it does not fold on exit.
///
/// # Errors
/// [`conformap_operators::OperatorError`] if two landmarks coincide (the interpolation
/// matrix is singular).
pub(crate) fn warp_landmarks(
    map: &mut [Complex64],
    faces: &[[u32; 3]],
    landmarks: &[u32],
    goals: &[Complex64],
    active: &[bool],
    sigma: f64,
    options: &WarpOptions,
) -> Result<WarpReport, conformap_operators::OperatorError> {
    let moving: Vec<(u32, Complex64)> = landmarks
        .iter()
        .zip(goals)
        .zip(active)
        .filter(|(_, &a)| a)
        .map(|((&v, &q), _)| (v, q))
        .collect();
    let m = moving.len();
    let rho = options.support;
    let gap = |map: &[Complex64]| {
        moving
            .iter()
            .map(|&(v, q)| (q - map[v as usize]).norm())
            .fold(0.0, f64::max)
    };
    let largest_move = gap(map);
    let mut report = WarpReport {
        steps: 0,
        rejected: 0,
        reached: m == 0 || largest_move == 0.0,
        largest_move,
    };
    if report.reached {
        return Ok(report);
    }
    let per_step = options.step * rho;
    // the share of a full step this step tries: halved after a rejected step, doubled
    // (up to 1) after an accepted one
    let mut share: f64 = 1.0;
    let mut trial = map.to_vec();
    loop {
        let left = gap(map);
        if left == 0.0 {
            break;
        }
        if report.steps + report.rejected >= options.max_steps {
            return Ok(report);
        }
        // this step's fraction of the way left (1: the last step)
        let t = (share * per_step / left).min(1.0);
        let p: Vec<Complex64> = moving.iter().map(|&(v, _)| map[v as usize]).collect();
        let mut phi = vec![0.0; m * m];
        for c in 0..m {
            for r in 0..m {
                phi[c * m + r] = wendland((p[r] - p[c]).norm() / rho);
            }
        }
        let chol = DenseCholesky::factor(phi, m, 1)?;
        // right-hand sides: δ_j / (1 − |p_j|²), real and imaginary parts as two columns
        let mut rhs = vec![0.0; 2 * m];
        for (j, &(_, q)) in moving.iter().enumerate() {
            let delta = t * (q - p[j]) / (1.0 - p[j].norm_sqr());
            rhs[j] = delta.re;
            rhs[m + j] = delta.im;
        }
        chol.solve_in_place(&mut rhs, 2);
        let coef: Vec<Complex64> = (0..m).map(|j| Complex64::new(rhs[j], rhs[m + j])).collect();
        for (out, &x) in trial.iter_mut().zip(map.iter()) {
            let taper = 1.0 - x.norm_sqr();
            let mut d = Complex64::new(0.0, 0.0);
            if taper > 0.0 {
                for (pj, cj) in p.iter().zip(&coef) {
                    let r = (x - pj).norm() / rho;
                    if r < 1.0 {
                        d += cj * wendland(r);
                    }
                }
            }
            *out = x + taper.max(0.0) * d;
        }
        if t == 1.0 {
            for &(v, q) in &moving {
                trial[v as usize] = q;
            }
        }
        if folded_faces(faces, &trial, sigma) > 0 {
            report.rejected += 1;
            share *= 0.5;
            continue;
        }
        map.copy_from_slice(&trial);
        report.steps += 1;
        share = (2.0 * share).min(1.0);
        if t == 1.0 {
            break;
        }
    }
    report.reached = true;
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A polar grid of the unit disk: `rings` rings of `spokes` vertices and the centre.
    fn polar_disk(rings: usize, spokes: usize) -> (Vec<Complex64>, Vec<[u32; 3]>) {
        let mut pts = vec![Complex64::new(0.0, 0.0)];
        for r in 1..=rings {
            for s in 0..spokes {
                let a = std::f64::consts::TAU * s as f64 / spokes as f64;
                pts.push(Complex64::from_polar(r as f64 / rings as f64, a));
            }
        }
        let id = |r: usize, s: usize| (1 + (r - 1) * spokes + s % spokes) as u32;
        let mut faces = Vec::new();
        for s in 0..spokes {
            faces.push([0, id(1, s), id(1, s + 1)]);
        }
        for r in 1..rings {
            for s in 0..spokes {
                faces.push([id(r, s), id(r + 1, s), id(r + 1, s + 1)]);
                faces.push([id(r, s), id(r + 1, s + 1), id(r, s + 1)]);
            }
        }
        (pts, faces)
    }

    #[test]
    fn landmarks_reach_their_goals_without_folds() {
        let (mut pts, faces) = polar_disk(30, 64);
        assert_eq!(folded_faces(&faces, &pts, 1.0), 0);
        // two landmarks pulled 0.3 apart in opposite directions, one pushed sideways
        let lm = [1 + 10 * 64, 1 + 10 * 64 + 32, 1 + 5 * 64 + 16];
        let start: Vec<Complex64> = lm.iter().map(|&v| pts[v as usize]).collect();
        let goals = [
            start[0] + Complex64::new(0.15, 0.1),
            start[1] + Complex64::new(-0.15, 0.1),
            start[2] + Complex64::new(0.2, 0.0),
        ];
        let boundary_before: Vec<Complex64> = pts[pts.len() - 64..].to_vec();
        let r = warp_landmarks(
            &mut pts,
            &faces,
            &lm,
            &goals,
            &[true; 3],
            1.0,
            &WarpOptions::DEFAULT,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(r.reached && r.steps >= 8, "{r:?}");
        for (&v, g) in lm.iter().zip(&goals) {
            assert_eq!(pts[v as usize], *g);
        }
        assert_eq!(folded_faces(&faces, &pts, 1.0), 0);
        // the boundary did not move
        for (a, b) in pts[pts.len() - 64..].iter().zip(&boundary_before) {
            assert!((a - b).norm() < 1e-15);
        }
    }

    #[test]
    fn inactive_landmarks_and_zero_moves_do_nothing() {
        let (mut pts, faces) = polar_disk(8, 16);
        let before = pts.clone();
        let r = warp_landmarks(
            &mut pts,
            &faces,
            &[3],
            &[Complex64::new(0.5, 0.5)],
            &[false],
            1.0,
            &WarpOptions::DEFAULT,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(r.reached && r.steps == 0);
        assert_eq!(pts, before);
    }
}
