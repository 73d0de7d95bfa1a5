//! CCEM: convergent conformal energy minimization on the boundary angles (Kuo, Lin, Yueh,
//! Yau 2021, Algorithms 4.1 and 4.2), with a guard that keeps the boundary bijective.

mod descent;
mod energy;
mod hessian;
mod line_search;
mod minimize;
mod mobius_align;
mod options;
mod qn;
mod schur;
#[cfg(test)]
mod speed_tests;
mod start;
#[cfg(test)]
pub(crate) mod tests;

pub use options::{CcemOptions, CcemStart, CcemVariant};
pub use schur::SchurMode;

use std::time::Instant;

use crate::angles::{min_gap, unwrap_boundary, GAP_FLOOR_MAX};
use crate::ccem::descent::{Descent, Stop};
use crate::ccem::energy::{evaluate, Eval};
use crate::ccem::minimize::{minimize_valid, precondition};
use crate::ccem::mobius_align::align;
use crate::ccem::schur::Schur;
use crate::ccem::start::{cem_start, harmonic_measure_source, schur_for_start, schur_start, Start};
use crate::cem::interior_residual;
use crate::initial::centre_face;
use crate::problem::DiskProblem;
use crate::report::{
    BoundaryReport, CcemReport, CcemStages, DiskMap, SchurReport, SolverReport, Timings,
};
use crate::DiskError;

/// The CCEM disk map (Kuo, Lin, Yueh, Yau 2021): minimizes the conformal energy over the
/// boundary angles, `E_C(θ) = ½ pᵀAp + ½ qᵀAq − ½ pᵀCq` (Eq. 3.17) with the Schur
/// complement `A` of Eq. 3.15, by steepest descent with the quadratic step (Eq. 4.1,
/// 4.5–4.6, Algorithm 4.1) or BFGS (Algorithm 4.2), both under a line search enforcing
/// the Wolfe conditions, then maps the interior by one harmonic solve.
///
/// - Starts by default from the harmonic measure of the boundary seen from a central
///   interior vertex, Möbius-aligned ([`CcemStart::HarmonicMeasure`]; its solve rides
///   along in the pass that forms the dense Schur complement with the factor of `L_II`
///   that [`DiskProblem::new`] made: no further factorization). The quasi-Newton variant is preconditioned by the exact Hessian at the
///   start and restarts its model before a tolerance stop
///   ([`CcemOptions::hessian_preconditioner`], [`CcemOptions::tol`]).
/// - Keeps the boundary bijective: the angles stay strictly increasing. A step may go at
///   most `ρ` of the way to the nearest collision of neighbours and never below
///   `min_gap`; gaps that the minimization drives to the floor are held there (their
///   vertices move together), which happens where the conformal map crowds the boundary
///   (thin limbs, long corridors). The report's [`BoundaryReport`] says how many.
/// - Never returns a folded map: if faces of the final map fold while gaps sit at the
///   floor (the crowding is below what f64 resolves on this mesh), the floor is raised
///   ×1000 and the minimization continues; if it still folds at
///   `1e-4` rad (or a tenth of the mean gap), or folds without crowding, CCEM refuses with
///   [`DiskError::Folded`].
/// - Energy never rises on an accepted step; the returned map is the last iterate, which
///   is the best since the last raise of the gap floor (`SolverReport::best_from`).
///
/// # Errors
/// [`DiskError::InvalidOption`] for out-of-range options; errors of the CEM start;
/// [`DiskError::InvalidStart`] when the starting boundary cannot be made to wind once
/// around the circle; [`DiskError::NonFinite`] if the energy is not finite (cotangent
/// weights too badly conditioned); [`DiskError::Folded`] when no floor up to
/// `1e-4` rad gives a map without folded faces.
///
/// # Examples
/// ```
/// use conformap_disk::{ccem, cem, CcemOptions, CemOptions, DiskProblem};
/// use conformap_mesh::TriMesh;
/// // a bumpy hexagonal patch: a centre vertex and two rings
/// let mut pos = vec![[0.0, 0.0, 0.3]];
/// for r in 1..=2 {
///     for k in 0..6 * r {
///         let t = k as f64 * std::f64::consts::TAU / (6 * r) as f64;
///         pos.push([r as f64 * t.cos(), r as f64 * t.sin(), 0.1 * (3.0 * t).sin()]);
///     }
/// }
/// # let faces = conformap_disk::doc_support::two_ring_faces();
/// let mesh = TriMesh::try_new(pos, faces)?;
/// let mut problem = DiskProblem::new(&mesh)?;
/// let c = cem(&mut problem, &CemOptions::DEFAULT)?;
/// let out = ccem(&mut problem, &CcemOptions::DEFAULT)?;
/// let e = |m: &[num_complex::Complex64]| problem.conformal_energy(m);
/// assert!(e(&out.map) <= e(&c.map));
/// for &v in &mesh.boundary_loops()[0] {
///     assert!((out.map[v as usize].norm() - 1.0).abs() < 1e-12);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn ccem(problem: &mut DiskProblem<'_>, options: &CcemOptions) -> Result<DiskMap, DiskError> {
    options.validate()?;
    let t0 = Instant::now();
    // the CEM start needs the problem mutably (its L_BB solver), so it runs first
    let cem_first = match &options.start {
        CcemStart::Cem(o) => Some(cem_start(problem, o)?),
        _ => None,
    };
    let cem_ms = ms_since(t0);
    let problem: &DiskProblem<'_> = problem;
    let face = centre_face(problem.mesh());
    let source = harmonic_measure_source(problem, face);
    let schur = schur_for_start(problem, options, face, source);
    let t_start = Instant::now();
    let start = match cem_first {
        Some(s) => s,
        None => schur_start(problem, options, &schur, face, source)?,
    };
    let start_ms = cem_ms + ms_since(t_start);
    let mut notes = vec![start.note.clone()];
    let (cur, repaired, align_ms) = starting_iterate(problem, &schur, &start, options, &mut notes)?;
    let mut descent = Descent::new(&schur, options);
    let t_pre = Instant::now();
    precondition_at_start(&mut descent, &cur, &mut notes);
    let precond_ms = ms_since(t_pre);
    descent.log_state(&cur);
    let floor_max = GAP_FLOOR_MAX.min(0.1 * std::f64::consts::TAU / problem.num_boundary() as f64);
    let t_iter = Instant::now();
    let (cur, stop, map, flips, finish_ms) =
        minimize_valid(problem, &mut descent, cur, floor_max, &mut notes)?;
    let iterations_ms = ms_since(t_iter) - finish_ms;
    stop_notes(problem, &descent, stop, &mut notes);
    let finished_at = ms_since(t0);
    let residual = interior_residual(problem, &map);
    let elapsed = ms_since(t0);
    let mut stages = CcemStages {
        start: start_ms + align_ms + precond_ms,
        schur: schur.form_ms,
        iterations: iterations_ms,
        finish: finish_ms,
    };
    let boundary = boundary_report(&cur, &descent, repaired, flips);
    let mut ls = descent.ls;
    ls.qn_pairs_skipped = descent.bfgs.skipped;
    stages.finish += ms_since(t0) - finished_at;
    let report = SolverReport {
        method: if options.variant == CcemVariant::QuasiNewton {
            "ccem-qn"
        } else {
            "ccem"
        }
        .to_string(),
        // every logged state after the start: the steps, the re-alignments and the
        // projections onto a raised floor (so that `best_iteration ≤ iterations`)
        iterations: descent.history.len() - 1,
        converged: matches!(stop, Stop::Tolerance | Stop::Rounding),
        best_iteration: descent.history.len() - 1,
        best_from: descent.best_from,
        energy_history: descent.history,
        residual,
        factorizations: 1 + start.extra_factorizations,
        notes,
        fallback_from: None,
        timings_ms: Timings {
            assemble: problem.assemble_ms,
            factor: problem.factor_ms + start.extra_factor_ms,
            solve: elapsed - start.extra_factor_ms,
            total: problem.setup_ms + elapsed,
        },
        ccem: Some(CcemReport {
            gradient_norm_history: descent.gnorm,
            line_search: ls,
            schur: schur_report(&schur),
            stages_ms: stages,
            boundary,
        }),
    };
    Ok(DiskMap { map, report })
}

/// Milliseconds since `t`.
fn ms_since(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The first iterate: the start's angles unwrapped (gaps below `min_gap` repaired) and,
/// for the harmonic-measure start, Möbius-aligned. Returns it, the number of repaired gaps
/// and the milliseconds of the alignment.
///
/// # Errors
/// [`DiskError::InvalidStart`] when the start does not wind once around the circle;
/// [`DiskError::NonFinite`] when its energy is not finite.
fn starting_iterate(
    problem: &DiskProblem<'_>,
    schur: &Schur<'_, '_>,
    start: &Start,
    options: &CcemOptions,
    notes: &mut Vec<String>,
) -> Result<(Eval, usize, f64), DiskError> {
    let unwrapped =
        unwrap_boundary(&start.boundary, options.min_gap).ok_or(DiskError::InvalidStart)?;
    if unwrapped.repaired > 0 {
        notes.push(format!(
            "the starting boundary was out of order or crowded below min_gap: {} gaps \
             repaired",
            unwrapped.repaired
        ));
    }
    let repaired = unwrapped.repaired;
    let mut cur = evaluate(schur, unwrapped.theta);
    if !cur.energy.is_finite() {
        return Err(DiskError::NonFinite {
            vertex: problem.partition().boundary[0] as usize,
            stage: "CCEM energy of the start",
        });
    }
    let mut align_ms = 0.0;
    if options.start == CcemStart::HarmonicMeasure {
        let t_align = Instant::now();
        let (aligned, a) = align(schur, cur, options.tol);
        cur = aligned;
        notes.push(format!(
            "Möbius-aligned: {} rounds, |b| {:.3e} in all, E_C {:.9e} → {:.9e}, {} products",
            a.rounds, a.moved, a.energy_before, a.energy_after, a.products,
        ));
        align_ms = ms_since(t_align);
    }
    Ok((cur, repaired, align_ms))
}

/// Sets the quasi-Newton variant's preconditioner: the Hessian (or its band) at the start,
/// when `A` is dense and [`CcemOptions::hessian_preconditioner`] asks for it; the note
/// says which.
///
/// Also at a repaired start (gaps set to the floor where the start stepped backwards): its
/// Hessian describes some artificial crowding, but together with the quasi-Newton restarts
/// of `Descent::minimize` it still cuts the iterations (alligator.obj 151 → 50,
/// igea_open.obj 125 → 40 to a lower minimum, a hemisphere 182 → 5).
fn precondition_at_start(descent: &mut Descent<'_, '_, '_>, cur: &Eval, notes: &mut Vec<String>) {
    let options = descent.options;
    if options.variant != CcemVariant::QuasiNewton || !options.hessian_preconditioner {
        return;
    }
    let Some(a) = descent.schur.dense() else {
        return;
    };
    descent.precond = precondition(a, cur, options.banded_hessian_min_nb);
    notes.push(match &descent.precond {
        Some(p) if p.band.is_some() => format!(
            "BFGS preconditioned by the band (half-width {}) of the Hessian at the start{}",
            p.band.unwrap_or(0),
            if p.modified > 0 {
                format!("; shifted {} times to be positive definite", p.modified)
            } else {
                String::new()
            }
        ),
        Some(p) => format!(
            "BFGS preconditioned by the exact Hessian at the start{}",
            if p.modified > 0 {
                format!("; {} negative curvatures flipped", p.modified)
            } else {
                String::new()
            }
        ),
        None => "the Hessian at the start could not be formed: plain BFGS".into(),
    });
}

/// The notes of the end of a run: why it stopped, the gaps held at the floor, the Schur
/// complement's path, a preconditioner dropped on the way.
fn stop_notes(
    problem: &DiskProblem<'_>,
    descent: &Descent<'_, '_, '_>,
    stop: Stop,
    notes: &mut Vec<String>,
) {
    match stop {
        Stop::Rounding => {
            notes.push("stopped: no decrease left above the rounding level of E_C".into())
        }
        Stop::Stalled => notes.push("stopped: the line search found no decrease".into()),
        Stop::MaxIter => notes.push("stopped at the iteration cap".into()),
        Stop::Tolerance => {}
    }
    if descent.held > 0 {
        notes.push(format!(
            "{} boundary gaps held at the floor {:.1e} rad: the conformal map crowds \
             these boundary vertices closer than that; the map is the energy minimum with \
             the boundary kept in order",
            descent.held, descent.floor
        ));
    }
    let schur = descent.schur;
    notes.push(format!(
        "Schur complement {} (n_B = {}), {} products",
        schur.mode().name(),
        problem.num_boundary(),
        schur.products()
    ));
    if descent.precond_dropped {
        notes.push(
            "a search along the preconditioned direction stalled: continued as plain BFGS".into(),
        );
    }
}

/// The report's account of the final boundary `cur`.
fn boundary_report(
    cur: &Eval,
    descent: &Descent<'_, '_, '_>,
    repaired: usize,
    flips: usize,
) -> BoundaryReport {
    let (gap, after) = min_gap(&cur.theta);
    BoundaryReport {
        min_gap: gap,
        min_gap_after: after,
        gap_floor: descent.floor,
        gaps_at_floor: descent.held,
        start_repaired_gaps: repaired,
        flipped_faces: flips,
    }
}

/// The report's account of how `A` was applied.
fn schur_report(schur: &Schur<'_, '_>) -> SchurReport {
    SchurReport {
        mode: schur.mode().name().to_string(),
        form_ms: schur.form_ms,
        products: schur.products(),
    }
}
