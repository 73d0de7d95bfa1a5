//! CEM: conformal energy minimization (Yueh, Lin, Wu, Yau 2017, Algorithm 1).

use std::time::Instant;

use num_complex::Complex64;

use crate::initial::{angenent_boundary, centralize_normalize};
use crate::options::with_setters;
use crate::problem::DiskProblem;
use crate::report::{DiskMap, SolverReport};
use crate::DiskError;

/// Options of [`cem`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct CemOptions {
    /// Iteration cap. Default: 20, as in both papers (CEM §5, CCEM §5 use CEM with 20
    /// iterations); CEM gains little after that.
    pub max_iter: usize,
    /// Relative energy-drop tolerance: stop when `|E_C^(k−1) − E_C^(k)| ≤ tol · |E_C^(k)|`.
    /// Default: `1e-6` relative, as in both papers (relative, not absolute: `E_C` can be
    /// ~3e-3).
    pub tol: f64,
    /// Use Remark 3's reflected interior values `f_i / |f_i|²` in the boundary update
    /// (Algorithm 1, step 7). Default: `true`; `false` gives the plain Eq. 23.
    pub reflect_interior: bool,
}

impl CemOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        max_iter: 20,
        tol: 1e-6,
        reflect_interior: true,
    };

    with_setters! {
        with_max_iter(max_iter: usize);
        with_tol(tol: f64);
        with_reflect_interior(reflect_interior: bool);
    }
}

impl Default for CemOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The CEM disk map (Algorithm 1): Angenent's initial map, then the boundary iteration
/// `L_BB f_B = −L_BI (diag|f_I|)^{-2} f_I` (Eq. 30), centralization (Eq. 24),
/// normalization (Eq. 25) and the interior solve (Eq. 22), until the relative energy drop
/// is below `tol` or `max_iter` iterations ran.
///
/// CEM's energy is not monotone on every mesh (it rises on alligator after the first step),
/// so the iterate of least `E_C` is returned and the whole history is reported. An update
/// that puts a boundary value at the centre (a regular polygon around a vertex at the
/// origin: the reflected interior value of Remark 3 is at infinity) ends the iteration with
/// a note; the best iterate so far is returned.
///
/// # Errors
/// See [`DiskError`].
///
/// # Examples
/// ```
/// use conformap_disk::{cem, CemOptions, DiskProblem};
/// use conformap_mesh::TriMesh;
/// // a hexagon fan around an off-centre vertex, slightly bent
/// let mut pos = vec![[0.2, 0.1, 0.3]];
/// for k in 0..6 {
///     let t = k as f64 * std::f64::consts::PI / 3.0;
///     pos.push([t.cos(), t.sin(), 0.0]);
/// }
/// let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
/// let mesh = TriMesh::try_new(pos, faces).unwrap();
/// let mut problem = DiskProblem::new(&mesh).unwrap();
/// let out = cem(&mut problem, &CemOptions::DEFAULT).unwrap();
/// assert!(out.map.iter().all(|z| z.norm() <= 1.0 + 1e-12));
/// let h = &out.report.energy_history;
/// assert!(h[out.report.best_iteration] <= h[0]);
/// ```
pub fn cem(problem: &mut DiskProblem<'_>, options: &CemOptions) -> Result<DiskMap, DiskError> {
    let t0 = Instant::now();
    let init = angenent_boundary(problem)?;
    let mut notes = vec![format!("Angenent source face {}", init.face)];
    if init.conjugated {
        notes.push("initial map conjugated to preserve orientation".to_string());
    }
    let boundary_ids = problem.partition().boundary.clone();
    let mut fb = init.boundary;
    let mut fi = problem.interior_solution(&fb);
    let mut f = problem.partition().assemble(&fi, &fb);
    let e0 = problem.conformal_energy(&f);
    let mut history = vec![e0];
    let mut best = (e0, 0usize, f.clone());
    let mut converged = false;
    let mut iterations = 0;
    for k in 1..=options.max_iter {
        let g: Vec<Complex64> = if options.reflect_interior {
            fi.iter()
                .map(|&z| {
                    let r2 = z.norm_sqr();
                    if r2 > f64::MIN_POSITIVE {
                        z / r2
                    } else {
                        z
                    }
                })
                .collect()
        } else {
            fi.clone()
        };
        let mut rhs = problem.blocks().bi_mul(&g);
        for z in &mut rhs {
            *z = -*z;
        }
        fb = problem.solve_boundary_block(&rhs)?;
        // a boundary value at the centre (e.g. an interior vertex exactly at 0, whose
        // reflection of Remark 3 is at infinity) ends the iteration: the best iterate so
        // far is still a valid map
        if let Err(e) = centralize_normalize(&mut fb, &boundary_ids, "CEM boundary update") {
            notes.push(format!(
                "iteration {k} stopped: {e}; the best iterate is returned"
            ));
            break;
        }
        fi = problem.interior_solution(&fb);
        f = problem.partition().assemble(&fi, &fb);
        let e = problem.conformal_energy(&f);
        if !e.is_finite() {
            let v = f
                .iter()
                .position(|z| !z.re.is_finite() || !z.im.is_finite())
                .unwrap_or(0);
            return Err(DiskError::NonFinite {
                vertex: v,
                stage: "CEM interior solve",
            });
        }
        iterations = k;
        let prev = *history.last().unwrap_or(&e);
        history.push(e);
        if e < best.0 {
            best = (e, k, f.clone());
        }
        if (prev - e).abs() <= options.tol * e.abs() {
            converged = true;
            break;
        }
    }
    let residual = interior_residual(problem, &best.2);
    let total = t0.elapsed().as_secs_f64() * 1e3;
    let report = SolverReport {
        method: "cem".to_string(),
        iterations,
        converged,
        energy_history: history,
        best_iteration: best.1,
        residual,
        factorizations: 2,
        notes,
        fallback_from: None,
        timings_ms: crate::report::Timings {
            assemble: problem.assemble_ms,
            factor: problem.factor_ms + init.factor_ms,
            solve: total - init.factor_ms,
            total: total + problem.setup_ms,
        },
        ..SolverReport::default()
    };
    Ok(DiskMap {
        map: best.2,
        report,
    })
}

/// Relative residual of the interior equations `L_II f_I + L_IB f_B = 0` of a full map.
pub fn interior_residual(problem: &DiskProblem<'_>, f: &[Complex64]) -> f64 {
    let part = problem.partition();
    let fi = part.interior_values(f);
    let fb = part.boundary_values(f);
    let lib = problem.blocks().ib_mul(&fb);
    let lii = conformap_operators::mul_complex(&problem.blocks().ii, &fi);
    let num = lii
        .iter()
        .zip(&lib)
        .map(|(a, b)| (a + b).norm())
        .fold(0.0, f64::max);
    let den = lib
        .iter()
        .map(|b| b.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    num / den
}
