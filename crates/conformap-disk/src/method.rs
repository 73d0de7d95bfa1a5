//! One entry point for every disk method: [`compute_disk_map`] with a [`DiskMethod`] and
//! the `--max-iter` / `--tol` overrides a command line offers.

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use conformap_mesh::TriMesh;

use crate::ccem::{CcemOptions, CcemStart, CcemVariant};
use crate::cem::interior_residual;
use crate::options::{finite_non_negative, with_setters};
use crate::{
    ccem, cem, harmonic_arc_length, unfold_disk_map, CemOptions, DiskError, DiskMap, DiskProblem,
};

/// A disk parameterization method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[non_exhaustive]
pub enum DiskMethod {
    /// Harmonic map to the arc-length circle (baseline, one solve).
    Harmonic,
    /// CEM, Yueh et al. 2017, Algorithm 1 (best iterate of 20).
    Cem,
    /// CCEM, Kuo et al. 2021, Algorithm 4.1: steepest descent with the quadratic step.
    Ccem,
    /// CCEM with BFGS, Algorithm 4.2 (default: the lowest energy, in the fewest
    /// iterations, on every class-a test mesh).
    #[default]
    CcemQn,
}

impl DiskMethod {
    /// Every method, in the order of the CLI's help.
    pub const ALL: [Self; 4] = [Self::CcemQn, Self::Ccem, Self::Cem, Self::Harmonic];

    /// The name used on the command line and in reports: `harmonic`, `cem`, `ccem`,
    /// `ccem-qn`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Harmonic => "harmonic",
            Self::Cem => "cem",
            Self::Ccem => "ccem",
            Self::CcemQn => "ccem-qn",
        }
    }
}

impl fmt::Display for DiskMethod {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DiskMethod {
    type Err = DiskError;

    /// Parses a method name ([`DiskMethod::name`]).
    fn from_str(s: &str) -> Result<Self, DiskError> {
        Self::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or(DiskError::InvalidOption {
                name: "method",
                reason: "expected one of ccem-qn, ccem, cem, harmonic",
            })
    }
}

/// Options of [`compute_disk_map`]: each method's own options, and the overrides of its
/// iteration cap and tolerance that a command line's `--max-iter` / `--tol` give.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct DiskOptions {
    /// Overrides the method's iteration cap. Default: `None` (CEM 20, CCEM 1000).
    pub max_iter: Option<usize>,
    /// Overrides the method's relative energy tolerance. Default: `None` (CEM 1e-6,
    /// CCEM 1e-9).
    pub tol: Option<f64>,
    /// Options of CEM. Default: [`CemOptions::DEFAULT`].
    pub cem: CemOptions,
    /// Options of CCEM (both variants; the variant is set by the method). Default:
    /// [`CcemOptions::DEFAULT`].
    pub ccem: CcemOptions,
    /// Return the harmonic and CEM maps as computed even when they fold, instead of
    /// passing them through [`unfold_disk_map`]. Default: `false` (every method returns a
    /// flip-free map or an error; CCEM guards its boundary order itself and ignores this).
    pub keep_folds: bool,
}

impl DiskOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        max_iter: None,
        tol: None,
        cem: CemOptions::DEFAULT,
        ccem: CcemOptions::DEFAULT,
        keep_folds: false,
    };

    with_setters! {
        with_max_iter(max_iter: Option<usize>);
        with_tol(tol: Option<f64>);
        with_cem(cem: CemOptions);
        with_keep_folds(keep_folds: bool);
        with_ccem(ccem: CcemOptions);
    }
}

/// Runs `method` on a problem already prepared (the factorization is reused). Harmonic
/// and CEM maps that fold are made flip-free by [`unfold_disk_map`] unless
/// [`DiskOptions::keep_folds`] is set.
///
/// # Errors
/// The method's errors (see [`cem`], [`ccem`]); [`DiskError::InvalidOption`] for a
/// negative or non-finite tolerance; [`DiskError::Folded`] when a folded harmonic or CEM
/// map cannot be repaired (boundary crowded below what f64 resolves).
pub fn run_disk_method(
    problem: &mut DiskProblem<'_>,
    method: DiskMethod,
    options: &DiskOptions,
) -> Result<DiskMap, DiskError> {
    if let Some(tol) = options.tol {
        finite_non_negative("tol", tol)?;
    }
    match method {
        DiskMethod::Harmonic => unfolded(problem, harmonic_arc_length(problem), options),
        DiskMethod::Cem => {
            let mut o = options.cem;
            o.max_iter = options.max_iter.unwrap_or(o.max_iter);
            o.tol = options.tol.unwrap_or(o.tol);
            let out = cem(problem, &o)?;
            unfolded(problem, out, options)
        }
        DiskMethod::Ccem | DiskMethod::CcemQn => {
            let variant = if method == DiskMethod::Ccem {
                CcemVariant::Gradient
            } else {
                CcemVariant::QuasiNewton
            };
            let mut o = options.ccem.with_variant(variant);
            o.max_iter = options.max_iter.unwrap_or(o.max_iter);
            o.tol = options.tol.unwrap_or(o.tol);
            if method == DiskMethod::Ccem && o.start == CcemOptions::DEFAULT.start {
                // Algorithm 4.1 as Kuo et al. §6 run it: from the CEM map (steepest descent
                // from the harmonic measure zigzags to the iteration cap on camelhead and
                // human_face, above CEM's energy)
                o.start = CcemStart::Cem(options.cem);
            }
            match ccem(problem, &o) {
                Err(e @ DiskError::Folded { .. }) if !options.keep_folds => {
                    fall_back(problem, method, options, &e).ok_or(e)
                }
                other => other,
            }
        }
    }
}

/// When CCEM would fold (negative cotangent weights fold its harmonic interior, or its
/// boundary crowds below what f64 resolves), the flip-free CEM and harmonic maps (each
/// through [`unfold_disk_map`]) of lower conformal energy, with a note and
/// [`SolverReport::fallback_from`] saying so; `None` when neither maps the mesh either.
/// The default method never refuses a disk a simpler method maps.
fn fall_back(
    problem: &mut DiskProblem<'_>,
    method: DiskMethod,
    options: &DiskOptions,
    why: &DiskError,
) -> Option<DiskMap> {
    let simpler = [DiskMethod::Cem, DiskMethod::Harmonic]
        .into_iter()
        .filter_map(|m| run_disk_method(problem, m, options).ok());
    let mut best = simpler.min_by(|a, b| {
        let (ea, eb) = (
            a.report.energy_history[a.report.best_iteration],
            b.report.energy_history[b.report.best_iteration],
        );
        ea.total_cmp(&eb)
    })?;
    let r = &mut best.report;
    r.notes.push(format!(
        "{} refused ({why}); returned the {} map, the flip-free one of lower E_C of cem and \
         harmonic",
        method.name(),
        r.method
    ));
    r.fallback_from = Some(method.name().to_string());
    Some(best)
}

/// `out` passed through [`unfold_disk_map`] unless [`DiskOptions::keep_folds`]: a map that
/// folds is replaced by its flip-free repair, whose energy is appended to the history (one
/// more iteration, made the returned iterate and [`SolverReport::best_from`]), with a note
/// saying what was done.
fn unfolded(
    problem: &DiskProblem<'_>,
    mut out: DiskMap,
    options: &DiskOptions,
) -> Result<DiskMap, DiskError> {
    if options.keep_folds {
        return Ok(out);
    }
    let t0 = Instant::now();
    let u = unfold_disk_map(problem, &out.map)?;
    let Some(note) = u.note() else {
        return Ok(out);
    };
    let r = &mut out.report;
    r.energy_history.push(problem.conformal_energy(&u.map));
    r.iterations += 1;
    r.best_iteration = r.energy_history.len() - 1;
    r.best_from = r.best_iteration;
    r.notes.push(note);
    out.map = u.map;
    r.residual = interior_residual(problem, &out.map);
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    r.timings_ms.solve += ms;
    r.timings_ms.total += ms;
    Ok(out)
}

/// The disk map of `mesh` by `method`: prepares the problem ([`DiskProblem::new`]:
/// topology check, Laplacian, one factorization) and runs the method.
///
/// # Errors
/// [`DiskProblem::new`]'s errors and the method's.
///
/// # Examples
/// ```
/// use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
/// use conformap_mesh::TriMesh;
/// let mut pos = vec![[0.0, 0.0, 0.3]];
/// for r in 1..=2 {
///     for k in 0..6 * r {
///         let t = k as f64 * std::f64::consts::TAU / (6 * r) as f64;
///         pos.push([r as f64 * t.cos(), r as f64 * t.sin(), 0.1 * (3.0 * t).sin()]);
///     }
/// }
/// # let faces = conformap_disk::doc_support::two_ring_faces();
/// let mesh = TriMesh::try_new(pos, faces)?;
/// let method: DiskMethod = "ccem-qn".parse()?;
/// let out = compute_disk_map(&mesh, method, &DiskOptions::DEFAULT.with_tol(Some(1e-10)))?;
/// assert_eq!(out.report.method, "ccem-qn");
/// assert!(out.report.converged);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn compute_disk_map(
    mesh: &TriMesh,
    method: DiskMethod,
    options: &DiskOptions,
) -> Result<DiskMap, DiskError> {
    let mut problem = DiskProblem::new(mesh)?;
    run_disk_method(&mut problem, method, options)
}
