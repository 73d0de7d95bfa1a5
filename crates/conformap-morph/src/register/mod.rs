//! Landmark registration between two disks (CEM §6, Eq. 34): the map `h` of one surface's
//! normalized disk onto another's, minimizing `E_R = E_D(h) + λ Σ_j |h(l_j) − t_j|²` with
//! the boundary on the unit circle (sliding allowed), then checked for folds.
//!
//! - [`system`]: the sparse part, reusing the disk map's factorization of `L_II` for every
//!   λ (Woodbury: only an `m × m` matrix is refactored when λ changes);
//! - [`boundary`]: the sliding boundary (exact one-vertex minimizations on the circle);
//! - [`anchor`]: the solves measured from the surface's own disk map (so that its own
//!   landmark positions as targets give it back unchanged);
//! - [`solve`]: one solve at a given λ;
//! - [`search`]: where that folds, the largest λ without a fold and the warp from there;
//! - [`warp`]: the fold-free landmark warp that finishes what Eq. 34 cannot do without
//!   folding;
//! - here: the options, the report, the driver and the fold check.

mod anchor;
mod boundary;
mod search;
mod solve;
mod system;
mod warp;

use std::time::Instant;

use conformap_disk::DiskProblem;
use num_complex::Complex64;
use serde::Serialize;

use crate::MorphError;
use anchor::Anchor;
use conformap_operators::planar::polygon_area;
use search::unfold;
pub use solve::folded_faces;
use solve::{folded_by, Solver};
use system::LandmarkSystem;
pub(crate) use warp::warp_landmarks;
pub use warp::{WarpOptions, WarpReport, WARP_MAX_STEPS, WARP_STEP, WARP_SUPPORT};

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

/// Cap on the boundary sweeps of each solve of the search for the largest λ without a
/// fold: `200`. Folds appear next to the landmarks and are set by λ, hardly by the last
/// digits of the sliding boundary, so the search does not wait for the sweeps to
/// converge (500–2000 at the λ it tries on the shared faces); the λ it finds is then
/// solved with [`REGISTER_MAX_SWEEPS`] and checked again.
pub const SEARCH_SWEEPS: usize = 200;

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
    /// The fold-free landmark warp that follows Eq. 34 when it folds. Default:
    /// [`WarpOptions::DEFAULT`].
    pub warp: WarpOptions,
}

impl RegisterOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        mode: LandmarkMode::Soft(DEFAULT_LAMBDA),
        max_sweeps: REGISTER_MAX_SWEEPS,
        sweep_tol: REGISTER_SWEEP_TOL,
        warp: WarpOptions::DEFAULT,
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
    /// λ of the Eq. 34 solve kept: the requested one when it did not fold, else the
    /// largest λ found without a fold, which the landmark warp then starts from (also in
    /// hard mode); `None` for a hard solve that did not fold.
    pub lambda_used: Option<f64>,
    /// `E_R = E_D + λ Σ|h(l_j) − t_j|²` of the result with the requested λ (Eq. 34;
    /// `E_D` in hard mode).
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
    /// Eq. 34 solves (1, or 1 + back-offs + bisections).
    pub attempts: usize,
    /// The landmark warp after the back-off (`None` when Eq. 34 at the requested λ did
    /// not fold).
    pub warp: Option<WarpReport>,
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
/// `vertices` land on (soft: near) `targets` (Eq. 34), boundary sliding on the circle,
/// without folding a face:
///
/// 1. Eq. 34 at the requested λ (hard: the λ → ∞ limit), its boundary sweeps stopped at
///    [`SEARCH_SWEEPS`]. If nothing folds, it is solved again with the full sweeps and
///    is the registration.
/// 2. Otherwise the landmark positions of step 1 become the goals (hard: the targets
///    exactly), and Eq. 34 is solved again with λ divided by [`LAMBDA_BACKOFF`] until
///    nothing folds (at most [`MAX_LAMBDA_BACKOFFS`] times), then [`LAMBDA_BISECTIONS`]
///    geometric bisections keep the largest λ without a fold: the most the linear
///    system can do without folding.
/// 3. A fold-free landmark warp (a composition of small smooth displacements, each
///    checked for folds, [`WarpOptions`]) moves the landmarks of that map the rest of
///    the way onto their goals.
///
/// Every solve is measured from `g` (the energy is tilted so that `g` is its critical
/// point: with `targets` at `g`'s own landmark values the registration returns `g`
/// exactly, see `anchor`), and a fold is a face folded by the solve that `g` does not
/// fold (faces a disk map squeezed to rounding already folds are no λ's doing).
///
/// The report says which steps ran.
///
/// # Errors
/// [`MorphError::InvalidOption`] for λ not finite and positive or bad warp options;
/// [`MorphError::Operator`] if a solve fails (or two landmarks coincide in the disk);
/// [`MorphError::NonFinite`] for a singular landmark system.
pub fn register_disk(
    problem: &DiskProblem<'_>,
    g: &[Complex64],
    vertices: &[u32],
    targets: &[Complex64],
    options: &RegisterOptions,
    surface: usize,
) -> Result<Registration, MorphError> {
    check_options(options)?;
    let t0 = Instant::now();
    let system = LandmarkSystem::new(problem, vertices)
        .map_err(|source| MorphError::Operator { surface, source })?;
    let setup_ms = ms(t0);
    let t1 = Instant::now();
    let gb = problem.partition().boundary_values(g);
    let sigma = if polygon_area(&gb) >= 0.0 { 1.0 } else { -1.0 };
    let anchor = Anchor::new(problem, g, sigma);
    let solver = Solver {
        problem,
        system,
        offsets: anchor.offsets(vertices, targets),
        anchor,
        targets,
        sigma,
        folded_in_g: folded_by(problem.mesh().faces(), g, sigma),
        sweep_tol: options.sweep_tol,
        surface,
    };
    let requested = match options.mode {
        LandmarkMode::Soft(l) => Some(l),
        LandmarkMode::Hard => None,
    };
    let hard = requested.is_none();
    // searching solves stop their sweeps at SEARCH_SWEEPS; a solve that is kept is
    // redone from there with the full sweeps
    let search = options.max_sweeps.min(SEARCH_SWEEPS);
    let mut attempts = 1;
    let quick = solver.attempt(requested, hard, &gb, search)?;
    let first = if quick.folds == 0 {
        attempts += 1;
        solver.attempt(requested, hard, &quick.hb, options.max_sweeps)?
    } else {
        quick
    };
    let (map, outcome, used, warp, notes) = if first.folds == 0 {
        let mut h = first.h;
        if hard {
            pin_interior_landmarks(problem, &mut h, vertices, targets);
        }
        (h, first.outcome, requested, None, Vec::new())
    } else {
        let u = unfold(&solver, g, vertices, first, requested, options, search)?;
        attempts += u.attempts;
        (u.map, u.outcome, u.lambda, Some(u.warp), u.notes)
    };
    let done = Done {
        map,
        outcome,
        used,
        warp,
        notes,
        attempts,
    };
    Ok(done.into_registration(&solver, g, vertices, requested, options, [setup_ms, ms(t1)]))
}

/// The result of the solves, before the report.
struct Done {
    map: Vec<Complex64>,
    outcome: boundary::SweepOutcome,
    used: Option<f64>,
    warp: Option<WarpReport>,
    notes: Vec<String>,
    attempts: usize,
}

impl Done {
    /// The registration with its report (the fold check, the notes, the landmark errors
    /// and the energies); `ms`: setup and solve milliseconds.
    fn into_registration(
        mut self,
        solver: &Solver<'_, '_, '_>,
        g: &[Complex64],
        vertices: &[u32],
        requested: Option<f64>,
        options: &RegisterOptions,
        ms: [f64; 2],
    ) -> Registration {
        let problem = solver.problem;
        let map = self.map;
        let folds = folded_faces(problem.mesh().faces(), &map, solver.sigma);
        if folds > 0 {
            self.notes.push(format!(
                "{folds} face(s) stay folded in the registered disk"
            ));
        }
        let outcome = self.outcome;
        if !outcome.converged {
            self.notes.push(format!(
                "boundary sweeps stopped at the cap {} (last move {:.2e} rad)",
                options.max_sweeps, outcome.last_move
            ));
        }
        let errors: Vec<f64> = vertices
            .iter()
            .zip(solver.targets)
            .map(|(&v, &t)| (map[v as usize] - t).norm())
            .collect();
        let dirichlet = problem.dirichlet_energy(&map);
        let penalty = requested.map_or(0.0, |l| l * errors.iter().map(|e| e * e).sum::<f64>());
        Registration {
            report: RegistrationReport {
                mode: if requested.is_none() { "hard" } else { "soft" },
                lambda_requested: requested,
                lambda_used: self.used,
                energy: dirichlet + penalty,
                dirichlet_energy: dirichlet,
                dirichlet_energy_before: problem.dirichlet_energy(g),
                landmark_disk_errors: errors,
                folded_faces: folds,
                sweeps: outcome.sweeps,
                converged: outcome.converged,
                attempts: self.attempts,
                warp: self.warp,
                notes: self.notes,
                setup_ms: ms[0],
                solve_ms: ms[1],
            },
            map,
        }
    }
}

/// λ finite and positive, the warp's support and step finite and positive.
fn check_options(options: &RegisterOptions) -> Result<(), MorphError> {
    if let LandmarkMode::Soft(l) = options.mode {
        if !(l > 0.0 && l.is_finite()) {
            return Err(MorphError::InvalidOption {
                name: "lambda",
                reason: format!("must be finite and > 0, got {l}"),
            });
        }
    }
    let w = &options.warp;
    if !(w.support > 0.0 && w.support.is_finite() && w.step > 0.0 && w.step.is_finite()) {
        return Err(MorphError::InvalidOption {
            name: "warp",
            reason: format!(
                "support and step must be finite and > 0, got {} and {}",
                w.support, w.step
            ),
        });
    }
    Ok(())
}

/// Hard mode: the interior landmarks exactly on their targets (the solve leaves
/// rounding).
fn pin_interior_landmarks(
    problem: &DiskProblem<'_>,
    h: &mut [Complex64],
    vertices: &[u32],
    targets: &[Complex64],
) {
    let part = problem.partition();
    for (&v, &t) in vertices.iter().zip(targets) {
        if part.is_interior[v as usize] {
            h[v as usize] = t;
        }
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
