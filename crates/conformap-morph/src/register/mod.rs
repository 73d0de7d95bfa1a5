//! Landmark registration between two disks (CEM §6, Eq. 34): the map `h` of one surface's
//! normalized disk onto another's, minimizing `E_R = E_D(h) + λ Σ_j |h(l_j) − t_j|²` with
//! the boundary on the unit circle (sliding allowed), then checked for folds.
//!
//! - [`system`]: the sparse part, reusing the disk map's factorization of `L_II` for every
//!   λ (Woodbury: only an `m × m` matrix is refactored when λ changes);
//! - [`boundary`]: the sliding boundary (exact one-vertex minimizations on the circle);
//! - here: the driver, the fold check and the λ back-off.

mod boundary;
mod system;

use std::time::Instant;

use conformap_disk::DiskProblem;
use num_complex::Complex64;
use serde::Serialize;

use crate::MorphError;
use boundary::{polygon_area, BoundaryEnergy};
use system::LandmarkSystem;

/// The landmark weight λ of Eq. 34 by default: `1000`. With `E_D = ½ fᴴ L f` on a unit
/// disk (`E_D ≈ π`) a landmark's pull is resisted by a stiffness of order
/// `1/(L⁻¹)_jj ≈ 2π / log(1/h) ≈ 1–3` on meshes of 10⁴ vertices, so the part of the
/// landmark mismatch left is about `1/(1 + 2λ (L⁻¹)_jj)`: 1e-3–3e-4 of it at λ = 1000
/// (measured on the shared faces: landmark errors 0.1–0.3 % of the diagonal → ≤ 0.01 %),
/// with no fold on them. Smaller λ leaves larger errors; larger λ approaches the hard mode.
pub const DEFAULT_LAMBDA: f64 = 1000.0;

/// Cap on the boundary sweeps: `2000`. One sweep costs `n_B²` multiply–adds (the dense
/// reduced energy), a few milliseconds for 2000 sweeps at `n_B ≈ 150`; measured on the
/// shared faces the sweeps stop at the tolerance after 100–600.
pub const REGISTER_MAX_SWEEPS: usize = 2000;

/// The sweeps stop when no boundary vertex moved more than this many radians in a sweep:
/// `1e-10` (a thousandth of a boundary gap of `1e-7`, far below anything the frames show).
pub const REGISTER_SWEEP_TOL: f64 = 1e-10;

/// When a soft registration folds, λ is divided by this (`4`) and the registration redone.
pub const LAMBDA_BACKOFF: f64 = 4.0;

/// At most this many back-offs (`12`: λ down by 4¹² ≈ 1.7e7) before the least-folded
/// registration is kept with a note.
pub const MAX_LAMBDA_BACKOFFS: usize = 12;

/// After a back-off found a λ without folds, this many (`3`) geometric bisections between
/// it and the last λ that folded look for a larger λ without folds (the interval shrinks
/// from a factor 4 to 4^(1/8) ≈ 1.19; each costs one registration, 30–80 ms on the faces).
pub const LAMBDA_BISECTIONS: usize = 3;

/// How landmarks enter the registration.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub enum LandmarkMode {
    /// The penalty of Eq. 34 with this λ (must be finite and > 0).
    Soft(f64),
    /// Landmarks exactly on their targets (the limit λ → ∞, by Lagrange multipliers).
    Hard,
}

/// Options of the registration.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RegisterOptions {
    /// Soft (with λ) or hard landmarks. Default: `Soft(DEFAULT_LAMBDA)`.
    pub mode: LandmarkMode,
    /// Default: [`REGISTER_MAX_SWEEPS`].
    pub max_sweeps: usize,
    /// Default: [`REGISTER_SWEEP_TOL`].
    pub sweep_tol: f64,
}

impl RegisterOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        mode: LandmarkMode::Soft(DEFAULT_LAMBDA),
        max_sweeps: REGISTER_MAX_SWEEPS,
        sweep_tol: REGISTER_SWEEP_TOL,
    };
}

impl Default for RegisterOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a registration did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RegistrationReport {
    /// `"soft"` or `"hard"`.
    pub mode: &'static str,
    /// λ asked for (`None` in hard mode).
    pub lambda_requested: Option<f64>,
    /// λ used (lower than asked after a fold back-off; `None` in hard mode).
    pub lambda_used: Option<f64>,
    /// `E_R = E_D + λ Σ|h(l_j) − t_j|²` of the result (Eq. 34; `E_D` in hard mode).
    pub energy: f64,
    /// `E_D = ½ hᴴ L h` of the result.
    pub dirichlet_energy: f64,
    /// `E_D` of the unregistered (normalized) disk map, for comparison.
    pub dirichlet_energy_before: f64,
    /// `|h(l_j) − t_j|` per landmark, in the disk.
    pub landmark_disk_errors: Vec<f64>,
    /// Faces whose registered image is folded or degenerate (signed area against the
    /// boundary's orientation).
    pub folded_faces: usize,
    /// Boundary sweeps of the final registration.
    pub sweeps: usize,
    /// Whether they met the tolerance.
    pub converged: bool,
    /// Registrations tried (1 + back-offs).
    pub attempts: usize,
    /// Things to know (back-offs, folds left).
    pub notes: Vec<String>,
    /// Milliseconds: forming `Z` and `S₀` (solves with the disk map's factor).
    pub setup_ms: f64,
    /// Milliseconds: everything per λ (the `m × m` factor, `S_λ`, sweeps, interior, fold
    /// check), all attempts.
    pub solve_ms: f64,
}

/// A registered disk: the new map value of every vertex and the report.
#[derive(Debug, Clone, PartialEq)]
pub struct Registration {
    /// `h(v)` for every vertex of the surface.
    pub map: Vec<Complex64>,
    /// What was done.
    pub report: RegistrationReport,
}

/// Registers the normalized disk map `g` of `problem`'s mesh so that its landmarks
/// `vertices` land on (soft: near) `targets` (Eq. 34), boundary sliding on the circle.
/// A soft registration that folds is redone with λ divided by [`LAMBDA_BACKOFF`] until it
/// does not (at most [`MAX_LAMBDA_BACKOFFS`] times); the report says so.
///
/// # Errors
/// [`MorphError::InvalidOption`] for λ not finite and positive; [`MorphError::Operator`]
/// if a solve fails; [`MorphError::NonFinite`] for a singular landmark system.
pub fn register_disk(
    problem: &DiskProblem<'_>,
    g: &[Complex64],
    vertices: &[u32],
    targets: &[Complex64],
    options: &RegisterOptions,
    surface: usize,
) -> Result<Registration, MorphError> {
    if let LandmarkMode::Soft(l) = options.mode {
        if !(l > 0.0 && l.is_finite()) {
            return Err(MorphError::InvalidOption {
                name: "lambda",
                reason: format!("must be finite and > 0, got {l}"),
            });
        }
    }
    let op = |source| MorphError::Operator { surface, source };
    let t0 = Instant::now();
    let system = LandmarkSystem::new(problem, vertices).map_err(op)?;
    let setup_ms = ms(t0);
    let t1 = Instant::now();
    let part = problem.partition();
    let gb = part.boundary_values(g);
    let sigma = if polygon_area(&gb) >= 0.0 { 1.0 } else { -1.0 };
    let mesh = problem.mesh();
    let mut lambda = match options.mode {
        LandmarkMode::Soft(l) => Some(l),
        LandmarkMode::Hard => None,
    };
    let mut notes = Vec::new();
    let mut attempts = 0;
    let mut best: Option<(Vec<Complex64>, usize, boundary::SweepOutcome, Option<f64>)> = None;
    let attempt = |lambda: Option<f64>| -> Result<_, MorphError> {
        let inv_mu = lambda.map_or(0.0, |l| 0.5 / l);
        let pen = system.penalized(inv_mu).map_err(op)?;
        let w = system.linear_term(&pen, targets);
        let nb = gb.len();
        let mut pull = vec![Complex64::new(0.0, 0.0); nb];
        let mut pinned = vec![false; nb];
        let mut hb = gb.clone();
        for &(j, b) in &system.boundary {
            match lambda {
                Some(l) => pull[b] -= 2.0 * l * targets[j],
                None => {
                    pinned[b] = true;
                    let t = targets[j];
                    hb[b] = if t.norm() > 0.0 { t / t.norm() } else { hb[b] };
                }
            }
        }
        let energy = BoundaryEnergy {
            s: &pen.s,
            w: &w,
            pull: &pull,
            pinned: &pinned,
            sigma,
        };
        let outcome = energy.sweep(&mut hb, options.max_sweeps, options.sweep_tol);
        let h = system.full_map(&pen, &hb, targets);
        if let Some(vertex) = h
            .iter()
            .position(|z| !(z.re.is_finite() && z.im.is_finite()))
        {
            return Err(MorphError::NonFinite { surface, vertex });
        }
        let folds = folded_faces(mesh.faces(), &h, sigma);
        Ok((h, folds, outcome))
    };
    // phase 1: divide λ by LAMBDA_BACKOFF until nothing folds
    let mut folded_at: Option<f64> = None;
    loop {
        attempts += 1;
        let (h, folds, outcome) = attempt(lambda)?;
        if best.as_ref().is_none_or(|b| folds < b.1) {
            best = Some((h, folds, outcome, lambda));
        }
        match lambda {
            Some(l) if folds > 0 && attempts <= MAX_LAMBDA_BACKOFFS => {
                let lower = l / LAMBDA_BACKOFF;
                notes.push(format!(
                    "λ = {l:e} folds {folds} face(s): registration redone with λ = {lower:e}"
                ));
                folded_at = Some(l);
                lambda = Some(lower);
            }
            _ => break,
        }
    }
    // phase 2: bisect (geometrically) between the last λ that folded and the first that
    // did not, keeping the largest λ without a fold
    if let (Some(mut hi), Some((_, 0, _, Some(mut lo)))) = (folded_at, best.as_ref()) {
        for _ in 0..LAMBDA_BISECTIONS {
            let mid = (hi * lo).sqrt();
            attempts += 1;
            let (h, folds, outcome) = attempt(Some(mid))?;
            if folds == 0 {
                lo = mid;
                best = Some((h, folds, outcome, Some(mid)));
            } else {
                hi = mid;
            }
        }
        notes.push(format!(
            "largest λ without a fold found by {LAMBDA_BISECTIONS} bisections: λ = {lo:e}"
        ));
    }
    let Some((map, folds, outcome, used)) = best else {
        return Err(MorphError::NonFinite { surface, vertex: 0 });
    };
    if folds > 0 {
        notes.push(format!(
            "{folds} face(s) stay folded in the registered disk ({})",
            if used.is_some() {
                "after every λ back-off"
            } else {
                "hard landmarks: try the soft mode"
            }
        ));
    }
    if !outcome.converged {
        notes.push(format!(
            "boundary sweeps stopped at the cap {} (last move {:.2e} rad)",
            options.max_sweeps, outcome.last_move
        ));
    }
    let errors: Vec<f64> = vertices
        .iter()
        .zip(targets)
        .map(|(&v, &t)| (map[v as usize] - t).norm())
        .collect();
    let dirichlet = problem.dirichlet_energy(&map);
    let penalty = used.map_or(0.0, |l| l * errors.iter().map(|e| e * e).sum::<f64>());
    Ok(Registration {
        report: RegistrationReport {
            mode: if used.is_some() { "soft" } else { "hard" },
            lambda_requested: match options.mode {
                LandmarkMode::Soft(l) => Some(l),
                LandmarkMode::Hard => None,
            },
            lambda_used: used,
            energy: dirichlet + penalty,
            dirichlet_energy: dirichlet,
            dirichlet_energy_before: problem.dirichlet_energy(g),
            landmark_disk_errors: errors,
            folded_faces: folds,
            sweeps: outcome.sweeps,
            converged: outcome.converged,
            attempts,
            notes,
            setup_ms,
            solve_ms: ms(t1),
        },
        map,
    })
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

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
