//! The minimization of a CCEM run up to a valid map: the descent, its preconditioner
//! refreshes and Möbius re-alignments at the stops, the harmonic extension, and the raised
//! gap floor when the map folds.

use std::time::Instant;

use num_complex::Complex64;

use crate::angles::{largest_gap, min_gap, project_to_floor, GAP_FLOOR_STEP};
use crate::ccem::descent::{Descent, Stop};
use crate::ccem::energy::{evaluate, Eval};
use crate::ccem::hessian::{Preconditioner, HESSIAN_BAND};
use crate::ccem::mobius_align::align;
use crate::laplacian_choice::count_flipped;
use crate::problem::DiskProblem;
use crate::DiskError;

/// Refreshes of the Hessian preconditioner at a tolerance stop with gaps held at the floor
/// (each costs one dense factorization, `n_B³ / 6` multiply–adds). igea_open.obj (7 gaps
/// held): 2 refreshes take the harmonic-measure start's stop from E_C = 2.909386e-2 to
/// 2.909322e-2, below the 2.909366e-2 that Angenent's start reached.
pub(crate) const HELD_REFRESHES: usize = 4;

/// The Hessian preconditioner at `at`: its band from `min_nb` boundary vertices on
/// ([`CcemOptions::banded_hessian_min_nb`]; falling back to the whole Hessian if the band
/// cannot be factored), else the whole Hessian.
pub(super) fn precondition(a: &[f64], at: &Eval, min_nb: usize) -> Option<Preconditioner> {
    if at.theta.len() >= min_nb {
        if let Some(p) = Preconditioner::banded(a, at, HESSIAN_BAND) {
            return Some(p);
        }
    }
    Preconditioner::at(a, at)
}

/// Möbius re-alignments at the stops of a descent preconditioned by the banded Hessian
/// (each a few products with `A`).
pub(crate) const BANDED_REALIGNMENTS: usize = 3;

/// Minimizes, maps the interior, and checks the map for folds. A fold with gaps at the
/// floor means the floor is below what f64 resolves for this mesh: the floor is raised
/// ([`GAP_FLOOR_STEP`]) and the minimization continues from the angles projected onto it,
/// up to `floor_max`. Returns the last iterate, why it stopped, the map, its flipped
/// faces (0) and the milliseconds spent in harmonic solves and fold checks.
///
/// # Errors
/// [`DiskError::Folded`] when the map still folds at the highest floor, or folds with no
/// gap at the floor (the cotangent weights of the mesh, not the boundary, fold it).
pub(super) fn minimize_valid(
    problem: &DiskProblem<'_>,
    descent: &mut Descent<'_, '_, '_>,
    mut cur: Eval,
    floor_max: f64,
    notes: &mut Vec<String>,
) -> Result<(Eval, Stop, Vec<Complex64>, usize, f64), DiskError> {
    let mut finish_ms = 0.0;
    loop {
        let (mut last, mut stop) = descent.minimize(cur);
        // gaps held at the floor bend the energy surface away from what the Hessian at the
        // start describes, and the tolerance stop can come early: refresh the
        // preconditioner where the descent stopped and go on while that still lowers E_C
        let mut refreshes = 0;
        while descent.held > 0
            && stop == Stop::Tolerance
            && descent.precond.is_some()
            && refreshes < HELD_REFRESHES
        {
            let Some(a) = descent.schur.dense() else {
                break;
            };
            let before = last.energy;
            descent.precond = precondition(a, &last, descent.options.banded_hessian_min_nb);
            descent.bfgs.reset();
            refreshes += 1;
            let (next, s) = descent.minimize(last);
            last = next;
            stop = s;
            if !(before - last.energy > descent.options.tol * last.energy.abs()) {
                break;
            }
        }
        if refreshes > 0 {
            notes.push(format!(
                "{refreshes} Hessian refreshes at the stops with gaps held at the floor"
            ));
        }
        // a banded preconditioner leaves out the far couplings that set the two soft
        // Möbius directions: at its stop, align along the orbit again and go on while that
        // lowers E_C by more than the tolerance
        let mut realigned = 0;
        while descent.precond.as_ref().is_some_and(|p| p.band.is_some())
            && matches!(stop, Stop::Tolerance | Stop::Rounding)
            && realigned < BANDED_REALIGNMENTS
        {
            let tol = descent.options.tol;
            let (aligned, a) = align(descent.schur, last, tol);
            realigned += 1;
            last = aligned;
            // logged whether or not the descent goes on from it: it is the state returned
            descent.log_state(&last);
            if !(a.energy_before - a.energy_after > tol * a.energy_after.abs()) {
                break;
            }
            descent.bfgs.reset();
            let (next, s) = descent.minimize(last);
            last = next;
            stop = s;
        }
        if realigned > 0 {
            notes.push(format!(
                "{realigned} Möbius re-alignments at the stops of the banded preconditioner"
            ));
        }
        cur = last;
        let t = Instant::now();
        let map = problem.harmonic_extension(&cur.f);
        let (flips, face) = count_flipped(problem.mesh(), &map);
        let face = face.unwrap_or(usize::MAX);
        finish_ms += t.elapsed().as_secs_f64() * 1e3;
        if flips == 0 {
            return Ok((cur, stop, map, 0, finish_ms));
        }
        let next = descent.floor * GAP_FLOOR_STEP;
        let crowded = descent.held > 0 || min_gap(&cur.theta).0 < next;
        let folded = DiskError::Folded {
            flipped_faces: flips,
            face,
            held_gaps: descent.held,
            floor: descent.floor,
        };
        if !crowded || next > floor_max {
            return Err(folded);
        }
        let Some(theta) = project_to_floor(&cur.theta, next, largest_gap(&cur.theta)) else {
            return Err(folded);
        };
        notes.push(format!(
            "{flips} faces folded with boundary gaps at {:.0e} rad (below what f64 resolves \
             on this mesh): floor raised to {next:.0e}",
            descent.floor
        ));
        descent.floor = next;
        descent.bfgs.reset();
        cur = evaluate(descent.schur, theta);
        descent.log_state(&cur);
        // the states before this one were at a floor whose minimum folds faces
        descent.best_from = descent.history.len() - 1;
    }
}
