//! The starting boundary of a CCEM run: the harmonic measure seen from a central vertex
//! (the default), Angenent's map, CEM, or the arc-length boundary, each with the note that
//! says which it was and why.

use num_complex::Complex64;

use crate::ccem::options::{CcemOptions, CcemStart};
use crate::ccem::schur::Schur;
use crate::cem::{cem, CemOptions};
use crate::initial::{angenent_boundary, angenent_from_schur, angenent_rhs, arc_length_boundary};
use crate::problem::DiskProblem;
use crate::DiskError;

/// What the start produced.
pub(super) struct Start {
    /// The starting boundary values (on the unit circle, in boundary-loop order).
    pub(super) boundary: Vec<Complex64>,
    /// Milliseconds of factorizations beyond the problem's own.
    pub(super) extra_factor_ms: f64,
    /// Factorizations beyond the problem's own.
    pub(super) extra_factorizations: usize,
    /// What the start was, for the notes.
    pub(super) note: String,
}

/// The arc-length start, with a note saying why it was used.
pub(super) fn arc_start(problem: &DiskProblem<'_>, why: Option<String>) -> Start {
    Start {
        boundary: arc_length_boundary(problem.mesh(), &problem.partition().boundary),
        extra_factor_ms: 0.0,
        extra_factorizations: 0,
        note: why.unwrap_or_else(|| "started from the arc-length boundary".to_string()),
    }
}

/// The CEM start (`CcemStart::Cem`): runs CEM with its own second factorization.
pub(super) fn cem_start(problem: &mut DiskProblem<'_>, o: &CemOptions) -> Result<Start, DiskError> {
    match cem(problem, o) {
        Ok(out) => {
            let boundary = problem.partition().boundary_values(&out.map);
            let extra = out.report.timings_ms.factor - problem.factor_ms;
            let r = &out.report;
            let note = format!(
                "started from CEM ({} iterations, E_C = {:.6e})",
                r.iterations,
                r.energy_history
                    .get(r.best_iteration)
                    .copied()
                    .unwrap_or(f64::NAN)
            );
            Ok(Start {
                boundary,
                extra_factorizations: out.report.factorizations.saturating_sub(1),
                extra_factor_ms: extra.max(0.0),
                note,
            })
        }
        // CEM's own numerical failures (a boundary vertex collapsing to the centre on
        // a tiny mesh) are no reason to give up: any ordered boundary is a start
        Err(e @ (DiskError::BoundaryCollapsed { .. } | DiskError::NonFinite { .. })) => {
            Ok(arc_start(
                problem,
                Some(format!(
                    "CEM failed ({e}); started from the arc-length boundary"
                )),
            ))
        }
        Err(e) => Err(e),
    }
}

/// The interior vertex the harmonic-measure start looks from: a vertex of the centre face
/// ([`centre_face`], which prefers faces off the boundary), else the first interior vertex.
pub(super) fn harmonic_measure_source(problem: &DiskProblem<'_>, face: usize) -> Option<u32> {
    let mesh = problem.mesh();
    let part = problem.partition();
    let interior = |v: u32| part.is_interior.get(v as usize).copied().unwrap_or(false);
    mesh.faces()
        .get(face)
        .and_then(|t| t.iter().copied().find(|&v| interior(v)))
        .or_else(|| part.interior.first().copied())
}

/// The harmonic-measure start (`CcemStart::HarmonicMeasure`, see [`crate::ccem::mobius_align`]):
/// the fluxes `−L_BI L_II⁻¹ e_p` from the pass that formed `A` (or one solve when `A` is
/// implicit), accumulated into angles. Negative fluxes (possible where cotangent weights
/// are negative) count as zero; a start that cannot be formed falls back to the
/// arc-length boundary, with a note.
pub(super) fn harmonic_measure_start(
    problem: &DiskProblem<'_>,
    schur: &Schur<'_, '_>,
    source: Option<u32>,
) -> Start {
    let Some(p) = source else {
        return arc_start(
            problem,
            Some(
                "no interior vertex for the harmonic measure: started from the arc-length boundary"
                    .into(),
            ),
        );
    };
    let coupling = match schur.coupling() {
        Some(c) => c.to_vec(),
        None => {
            let part = problem.partition();
            let mut rhs = vec![Complex64::new(0.0, 0.0); part.interior.len()];
            rhs[part.local[p as usize] as usize] = Complex64::new(1.0, 0.0);
            let x = problem.interior_factor().solve_complex(&rhs);
            problem.blocks().bi_mul(&x)
        }
    };
    let flux: Vec<f64> = coupling.iter().map(|z| (-z.re).max(0.0)).collect();
    let total: f64 = flux.iter().sum();
    if !(total.is_finite() && total > 0.0) {
        return arc_start(
            problem,
            Some(format!(
                "the harmonic measure from vertex {p} vanished: started from the arc-length boundary"
            )),
        );
    }
    let mut acc = 0.0;
    let boundary = flux
        .iter()
        .map(|w| {
            let w = w / total;
            let t = std::f64::consts::TAU * (acc + 0.5 * w);
            acc += w;
            Complex64::from_polar(1.0, t)
        })
        .collect();
    Start {
        boundary,
        extra_factor_ms: 0.0,
        extra_factorizations: 0,
        note: format!(
            "started from the harmonic measure seen from vertex {p} (total flux {total:.12})"
        ),
    }
}

/// The Angenent start (`CcemStart::Angenent`): from the dense Schur complement when there
/// is one (no further factorization), else by [`angenent_boundary`] (a second one).
pub(super) fn angenent_start(
    problem: &DiskProblem<'_>,
    schur: &Schur<'_, '_>,
    face: usize,
) -> Result<Start, DiskError> {
    let out = match (schur.dense(), schur.coupling()) {
        (Some(a), Some(c)) => angenent_from_schur(problem, face, a, c).map(|b| (b, 0)),
        _ => angenent_boundary(problem).map(|b| (b, 1)),
    };
    match out {
        Ok((init, extra)) => Ok(Start {
            note: format!(
                "started from Angenent's map (source face {}{}{})",
                init.face,
                if init.conjugated {
                    ", conjugated to preserve orientation"
                } else {
                    ""
                },
                if extra > 0 {
                    ", with a second factorization"
                } else {
                    ", from the Schur complement"
                },
            ),
            boundary: init.boundary,
            extra_factor_ms: if extra > 0 { init.factor_ms } else { 0.0 },
            extra_factorizations: extra,
        }),
        Err(e @ (DiskError::BoundaryCollapsed { .. } | DiskError::NonFinite { .. })) => {
            Ok(arc_start(
                problem,
                Some(format!(
                    "Angenent's map failed ({e}); started from the arc-length boundary"
                )),
            ))
        }
        Err(e) => Err(e),
    }
}

/// The Schur complement `A` of the run, formed in one pass with the right-hand side the
/// start needs (Angenent's source face or the harmonic measure's vertex), so that the start
/// costs no further factorization.
pub(super) fn schur_for_start<'p, 'm>(
    problem: &'p DiskProblem<'m>,
    options: &CcemOptions,
    face: usize,
    source: Option<u32>,
) -> Schur<'p, 'm> {
    match (options.start, source) {
        (CcemStart::Angenent, _) => {
            Schur::with_rhs(problem, options.schur, &angenent_rhs(problem.mesh(), face))
        }
        (CcemStart::HarmonicMeasure, Some(p)) => {
            Schur::with_rhs(problem, options.schur, &[(p, Complex64::new(1.0, 0.0))])
        }
        _ => Schur::new(problem, options.schur),
    }
}

/// The start of `options` other than CEM's (which runs before `A` is formed, see
/// [`cem_start`]).
///
/// # Errors
/// Those of Angenent's map other than a collapse (which falls back to the arc-length
/// boundary).
pub(super) fn schur_start(
    problem: &DiskProblem<'_>,
    options: &CcemOptions,
    schur: &Schur<'_, '_>,
    face: usize,
    source: Option<u32>,
) -> Result<Start, DiskError> {
    Ok(match options.start {
        CcemStart::Angenent => angenent_start(problem, schur, face)?,
        CcemStart::HarmonicMeasure => harmonic_measure_start(problem, schur, source),
        _ => arc_start(problem, None),
    })
}
