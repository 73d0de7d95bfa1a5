//! Where Eq. 34 folds: the search for the largest λ without a fold (back-off, then
//! geometric bisection, then the full solve at the λ found) and the fold-free landmark
//! warp from there onto the goals.

use num_complex::Complex64;

use super::solve::{Attempt, Solver};
use super::warp::{warp_landmarks, WarpReport};
use super::{
    RegisterOptions, DEFAULT_LAMBDA, LAMBDA_BACKOFF, LAMBDA_BISECTIONS, MAX_LAMBDA_BACKOFFS,
};
use crate::MorphError;

/// The map, the sweep outcome and λ of the base solve, the warp's report, and what the
/// search and warp note.
pub(super) struct Unfolded {
    pub map: Vec<Complex64>,
    pub outcome: super::boundary::SweepOutcome,
    /// The largest λ without a fold (`None` when every λ tried folds).
    pub lambda: Option<f64>,
    pub warp: WarpReport,
    pub notes: Vec<String>,
    /// Solves performed.
    pub attempts: usize,
}

/// Starting from `first`, the solve at the requested λ (`requested`; `None`: hard) that
/// folded: the largest λ without a fold, its full solve, and the landmark warp of that
/// map onto the goals (where `first` put the landmarks; hard: the targets). `g` is the
/// normalized disk map, the warp's start when every λ folds; `search` caps the sweeps of
/// the searching solves.
pub(super) fn unfold(
    solver: &Solver<'_, '_, '_>,
    g: &[Complex64],
    vertices: &[u32],
    first: Attempt,
    requested: Option<f64>,
    options: &RegisterOptions,
    search: usize,
) -> Result<Unfolded, MorphError> {
    let hard = requested.is_none();
    let goals: Vec<Complex64> = if hard {
        solver.targets.to_vec()
    } else {
        vertices.iter().map(|&v| first.h[v as usize]).collect()
    };
    let mut notes = vec![format!(
        "{} folds {} face(s): the landmarks are brought to where it puts them by the \
         largest λ without a fold and a fold-free landmark warp",
        match requested {
            Some(l) => format!("λ = {l:e}"),
            None => "the hard constraint".to_string(),
        },
        first.folds
    )];
    let mut attempts = 0;
    let start_lambda = requested.unwrap_or(DEFAULT_LAMBDA);
    let (found, lowest) = back_off(solver, hard, first.hb, start_lambda, search, &mut attempts)?;
    let found = match found {
        Some(b) => Some(bisect(solver, hard, b, search, &mut attempts)?),
        None => None,
    };
    let base = match found {
        Some((from, lo)) => full_solve(solver, hard, &from, lo, options, &mut attempts)?,
        None => None,
    };
    // no λ without a fold: the normalized disk map itself
    let (mut map, outcome, lambda) = match base {
        Some((a, lo)) => (a.h, a.outcome, Some(lo)),
        None => {
            notes.push(format!(
                "every λ down to {lowest:e} folds: the warp starts from the unregistered disk"
            ));
            (g.to_vec(), first.outcome, None)
        }
    };
    if let Some(lo) = lambda {
        notes.push(format!("largest λ without a fold: {lo:e}"));
    }
    let warp = warp_onto_goals(solver, &mut map, vertices, &goals, options)?;
    if !warp.reached {
        notes.push(format!(
            "the landmark warp stopped at its cap of {} steps, short of the goals",
            options.warp.max_steps
        ));
    }
    Ok(Unfolded {
        map,
        outcome,
        lambda,
        warp,
        notes,
        attempts,
    })
}

/// A λ without a fold (`lo`, its boundary `hb`) and the last λ above it that folded (`hi`).
struct Bracket {
    hb: Vec<Complex64>,
    lo: f64,
    hi: f64,
}

/// Phase 1: λ divided by [`LAMBDA_BACKOFF`] until nothing folds (each solve's sweeps
/// start from the boundary of the last). Returns the bracket, if found, and the lowest λ
/// that folded.
fn back_off(
    solver: &Solver<'_, '_, '_>,
    hard: bool,
    mut start: Vec<Complex64>,
    mut lambda: f64,
    search: usize,
    attempts: &mut usize,
) -> Result<(Option<Bracket>, f64), MorphError> {
    let mut folded_at = lambda;
    for _ in 0..MAX_LAMBDA_BACKOFFS {
        let lower = lambda / LAMBDA_BACKOFF;
        *attempts += 1;
        let a = solver.attempt(Some(lower), hard, &start, search)?;
        start = a.hb;
        if a.folds == 0 {
            let bracket = Bracket {
                hb: start,
                lo: lower,
                hi: folded_at,
            };
            return Ok((Some(bracket), lambda));
        }
        folded_at = lower;
        lambda = lower;
    }
    Ok((None, lambda))
}

/// Phase 2: [`LAMBDA_BISECTIONS`] geometric bisections of the bracket; returns the
/// largest λ without a fold and its boundary.
fn bisect(
    solver: &Solver<'_, '_, '_>,
    hard: bool,
    bracket: Bracket,
    search: usize,
    attempts: &mut usize,
) -> Result<(Vec<Complex64>, f64), MorphError> {
    let Bracket {
        hb: mut from,
        mut lo,
        mut hi,
    } = bracket;
    for _ in 0..LAMBDA_BISECTIONS {
        let mid = (hi * lo).sqrt();
        *attempts += 1;
        let a = solver.attempt(Some(mid), hard, &from, search)?;
        if a.folds == 0 {
            lo = mid;
            from = a.hb;
        } else {
            hi = mid;
        }
    }
    Ok((from, lo))
}

/// Phase 3: the full solve at the λ found (lowered again should the converged boundary
/// fold).
fn full_solve(
    solver: &Solver<'_, '_, '_>,
    hard: bool,
    from: &[Complex64],
    mut lo: f64,
    options: &RegisterOptions,
    attempts: &mut usize,
) -> Result<Option<(Attempt, f64)>, MorphError> {
    for _ in 0..MAX_LAMBDA_BACKOFFS {
        *attempts += 1;
        let a = solver.attempt(Some(lo), hard, from, options.max_sweeps)?;
        if a.folds == 0 {
            return Ok(Some((a, lo)));
        }
        lo /= LAMBDA_BACKOFF;
    }
    Ok(None)
}

/// The fold-free landmark warp of `map` bringing the interior landmarks onto `goals`.
fn warp_onto_goals(
    solver: &Solver<'_, '_, '_>,
    map: &mut [Complex64],
    vertices: &[u32],
    goals: &[Complex64],
    options: &RegisterOptions,
) -> Result<WarpReport, MorphError> {
    let part = solver.problem.partition();
    let active: Vec<bool> = vertices
        .iter()
        .map(|&v| part.is_interior[v as usize])
        .collect();
    warp_landmarks(
        map,
        solver.problem.mesh().faces(),
        vertices,
        goals,
        &active,
        solver.sigma,
        &options.warp,
    )
    .map_err(|source| MorphError::Operator {
        surface: solver.surface,
        source,
    })
}
