//! Generalized CEM for multiply-connected surfaces (Yueh, Lin, Wu, Yau 2017, §3.3,
//! Algorithm 2): Koebe's iteration onto the unit disk with circular holes.

mod circle_fit;
mod options;
mod polish;
mod polish_newton;
mod report;
mod step;
mod step_newton;

pub use options::KoebeOptions;
pub use report::{CircleDomainMap, KoebeReport, KoebeStepRecord, KoebeTimings, PolishReport};

use std::time::Instant;

use conformap_mesh::{fill_all_holes_except, Topology, TriMesh};
use conformap_operators::LoopCircle;
use num_complex::Complex64;

use crate::koebe::circle_fit::{
    arc_length_angles, circle_residual, concentric_point, disk_automorphism, fit_circle,
    inner_point, unwrapped_angles, Circle,
};
use crate::koebe::polish::polish;
use crate::koebe::step::{LoopSystem, StepSolve};
use crate::koebe::step_newton::NewtonOptions;
use crate::{cem, DiskError, DiskProblem};

/// The conformal map of a genus-0 mesh with several boundary loops onto the unit disk with
/// circular holes: Koebe's iteration (CEM §3.3, Algorithm 2), then the circle-domain map of
/// least conformal energy.
///
/// 1. **First map** (Algorithm 2, steps 1–4): fill every hole (every loop but the outer
///    one) with its centroid fan and map the filled surface onto the unit disk by CEM
///    ([`crate::cem`], Algorithm 1, with [`KoebeOptions::initial`]); open the holes.
/// 2. **Koebe sweeps** (steps 5–11, repeated): for each hole in loop order, then the outer
///    loop, invert the current image about a point deep inside that loop
///    (`z ↦ 1/(z − c)`; the loop's vertex centroid, step 6, when it is well inside) so the
///    loop becomes the outer boundary, fill every other loop with its centroid fan *in the
///    plane* (step 8), and map this planar disk onto the unit disk (step 9) with the
///    planar image's own cotangent weights. The planar map minimizes the conformal energy on
///    the boundary angles with the interior harmonic (CCEM's energy, Eq. 3.17, by Newton's
///    method on the dense Schur complement, the boundary's vertex mean held where the start
///    has it) rather than running 20 CEM iterations: a domain whose holes are already
///    circles is then mapped to itself by a Möbius map exactly, so circles converge to
///    rounding, not to CEM's stopping error. Each open loop keeps its filled mesh, Laplacian
///    pattern and symbolic factorization across sweeps (`Cholesky::refactor` only).
///    Sweeps stop once the worst circle residual `max ||f − c| − r| / r` over the loops is
///    at most [`KoebeOptions::tol`], or at [`KoebeOptions::max_sweeps`]; with the polish
///    on, also when a sweep raises that residual or a step breaks down (small holes with
///    staircase boundaries, where an inverted step is dominated by one ring of coarse
///    triangles), keeping the best iterate.
/// 3. **Normalization** (a Möbius map, so circles stay circles): the outer loop on the unit
///    circle around the domain; the *reference hole* (the hole loop of smallest index)
///    centred at 0 by a disk automorphism; then a rotation putting the outer loop's first
///    vertex (`boundary_loops()[outer][0]`, its smallest vertex index) at angle 0. For two
///    loops this is the concentric annulus `r ≤ |f| ≤ 1`, whose modulus `ln(1/r)` is
///    reported.
/// 4. **Polish** ([`KoebeOptions::polish`], on by default): the iteration reaches *a*
///    circle domain, which one depending on its path (every planar step is exact for its
///    own image, so the first map's discretization error stays). The polish minimizes the
///    conformal energy of CEM Eq. 7, measured on the surface with its own cotangent weights,
///    over all circle-domain maps in the normalization of step 3 (every loop's vertices on
///    a circle, each hole's centre and radius free; Newton on the dense Schur complement of
///    all boundary vertices), so every loop lies on its circle to rounding and the map is
///    the most conformal one in that normalization.
///
/// A mesh with one boundary loop is a disk: the first map alone.
///
/// # Errors
/// [`DiskError::NotGenusZero`] unless the mesh is connected, genus 0, with boundary;
/// [`DiskError::OuterLoopOutOfRange`]; [`DiskError::InvalidOption`];
/// [`DiskError::Fill`]; the first map's own [`DiskError`]s;
/// [`DiskError::Operator`], [`DiskError::LoopNotSimple`], [`DiskError::NonFinite`]
/// when a planar step breaks down with the polish off, or the polish's factorization fails.
///
/// # Examples
/// ```
/// use conformap_disk::{koebe, KoebeOptions};
/// use conformap_mesh::TriMesh;
/// // a flat annulus 1 ≤ |z| ≤ 2: 5 circles of 24 vertices, uniform in log r
/// # let (rings, sectors) = (4usize, 24usize);
/// # let mut pos = Vec::new();
/// # for k in 0..=rings {
/// #     let r = 2f64.powf(k as f64 / rings as f64);
/// #     let shift = if k % 2 == 1 { 0.5 } else { 0.0 };
/// #     for j in 0..sectors {
/// #         let t = (j as f64 + shift) * std::f64::consts::TAU / sectors as f64;
/// #         pos.push([r * t.cos(), r * t.sin(), 0.0]);
/// #     }
/// # }
/// # let mut faces = Vec::new();
/// # for k in 0..rings {
/// #     let (a, b) = ((k * sectors) as u32, ((k + 1) * sectors) as u32);
/// #     let s = sectors as u32;
/// #     for j in 0..s {
/// #         let (j1) = (j + 1) % s;
/// #         if k % 2 == 0 {
/// #             faces.push([a + j, a + j1, b + j]);
/// #             faces.push([a + j1, b + j1, b + j]);
/// #         } else {
/// #             faces.push([a + j, b + j1, b + j]);
/// #             faces.push([a + j, a + j1, b + j1]);
/// #         }
/// #     }
/// # }
/// let mesh = TriMesh::try_new(pos, faces)?;
/// // both loops have 24 vertices: name the outer one (loop 1, the circle |z| = 2)
/// let out = koebe(&mesh, &KoebeOptions::DEFAULT.with_outer(Some(1)))?;
/// assert!(out.report.converged);
/// // every loop on a circle, the outer one the unit circle
/// assert!(out.circles.iter().all(|c| c.residual_max < 1e-12));
/// assert!(mesh.boundary_loops()[1].iter().all(|&v| (out.map[v as usize].norm() - 1.0).abs() < 1e-12));
/// // a flat annulus is its own circle domain: the map is z/2, the modulus ln 2
/// let modulus = out.modulus.unwrap_or(f64::NAN);
/// assert!((modulus - 2f64.ln()).abs() < 1e-9, "{modulus}");
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn koebe(mesh: &TriMesh, options: &KoebeOptions) -> Result<CircleDomainMap, DiskError> {
    options.validate()?;
    let t_all = Instant::now();
    let found = mesh.topology();
    if !matches!(found, Topology::Disk | Topology::MultiplyConnected { .. }) {
        return Err(DiskError::NotGenusZero { found });
    }
    let loops = mesh.boundary_loops();
    let outer = match options.outer {
        Some(index) if index >= loops.len() => {
            return Err(DiskError::OuterLoopOutOfRange {
                index,
                loops: loops.len(),
            })
        }
        Some(index) => index,
        None => mesh.longest_boundary_loop().unwrap_or(0),
    };
    let holes: Vec<usize> = (0..loops.len()).filter(|&l| l != outer).collect();
    let n = mesh.num_vertices();

    // steps 1-4: CEM on the surface with every hole filled
    let t = Instant::now();
    let filled = fill_all_holes_except(mesh, outer)?;
    let mut problem = DiskProblem::new(&filled.mesh)?;
    let first = cem(&mut problem, &options.initial)?;
    let newton = NewtonOptions {
        max_iter: options.newton_max_iter,
        step_tol: options.newton_step_tol,
    };
    let mut z = first.map[..n].to_vec();
    let mut report = KoebeReport {
        method: "koebe".to_string(),
        outer_loop: outer,
        tol: options.tol,
        residual_history: vec![worst_residual(mesh, &z)],
        notes: vec![format!(
            "first map: CEM on the surface with {} holes filled by centroid fans",
            holes.len()
        )],
        initial: first.report,
        ..KoebeReport::default()
    };
    report.timings_ms.first_map = ms(t);

    // steps 5-11, repeated: planar sweeps
    let (koebe_converged, best) =
        sweeps(mesh, &mut z, &holes, outer, options, &newton, &mut report)?;
    report.koebe_converged = koebe_converged;
    report.converged = koebe_converged;
    if options.polish && !koebe_converged {
        if let Some(best) = best {
            z = best;
        }
    }

    let t = Instant::now();
    let reference_hole = holes.first().copied();
    normalize(mesh, &mut z, outer, reference_hole);
    report.timings_ms.solve += ms(t);
    if options.polish && !holes.is_empty() {
        let t = Instant::now();
        let (polished, polish_report) = polish(mesh, &z, outer, reference_hole, options)?;
        z = polished;
        report.converged = polish_report.converged;
        report.polish = Some(polish_report);
        report.timings_ms.polish = ms(t);
    }
    let circles = loop_circles(mesh, &z, outer);
    let modulus = match (loops.len(), reference_hole) {
        (2, Some(h)) => Some(-circles[h].radius.ln()),
        _ => None,
    };
    report.timings_ms.total = ms(t_all);
    Ok(CircleDomainMap {
        map: z,
        circles,
        reference_hole,
        modulus,
        report,
    })
}

/// The Koebe sweeps (steps 5–11, repeated) on the image `z`, recorded in `report`: until
/// the worst circle residual after a sweep is at most the tolerance, or the sweep cap.
/// With the polish on, a sweep that raises the residual above the best so far, or a step
/// that breaks down (a folded image), ends the sweeps instead of the run: the polish then
/// starts from the best iterate, which is returned (`None` if the last one is the best).
/// Returns whether the tolerance was met.
fn sweeps(
    mesh: &TriMesh,
    z: &mut [Complex64],
    holes: &[usize],
    outer: usize,
    options: &KoebeOptions,
    newton: &NewtonOptions,
    report: &mut KoebeReport,
) -> Result<(bool, Option<Vec<Complex64>>), DiskError> {
    let n = mesh.num_vertices();
    let loops = mesh.boundary_loops();
    let mut systems: Vec<Option<LoopSystem>> = (0..loops.len()).map(|_| None).collect();
    let order: Vec<usize> = holes.iter().copied().chain([outer]).collect();
    let mut best_residual = report
        .residual_history
        .first()
        .copied()
        .unwrap_or(f64::INFINITY);
    let mut best: Option<Vec<Complex64>> = None;
    let mut converged = holes.is_empty() || best_residual <= options.tol;
    let mut sweep = 0;
    'sweeps: while !converged && sweep < options.max_sweeps {
        sweep += 1;
        let before = z.to_vec();
        for &k in &order {
            let system = systems[k].get_or_insert_with(|| LoopSystem::new(mesh, k));
            match planar_step(mesh, system, z, newton, sweep) {
                Ok(solved) => {
                    z.copy_from_slice(&solved.map[..n]);
                    record_step(report, &solved, sweep, k, worst_residual(mesh, z));
                }
                Err(e) if options.polish => {
                    report.notes.push(format!(
                        "Koebe sweep {sweep} broke down ({e}); the polish starts from the best \
                         iterate"
                    ));
                    best = Some(before);
                    break 'sweeps;
                }
                Err(e) => return Err(e),
            }
        }
        let residual = worst_residual(mesh, z);
        report.residual_history.push(residual);
        converged = residual <= options.tol;
        if residual < best_residual {
            best_residual = residual;
        } else if options.polish {
            report.notes.push(format!(
                "Koebe sweep {sweep} raised the worst circle residual to {residual:.2e} (best \
                 {best_residual:.2e}); the polish starts from the best iterate"
            ));
            best = Some(before);
            break;
        }
    }
    report.sweeps = sweep;
    report.symbolic_factorizations = systems.iter().filter(|s| s.is_some()).count();
    report.numeric_factorizations = report.steps;
    if !converged && sweep == options.max_sweeps {
        report.notes.push(format!(
            "Koebe stopped at the sweep cap ({}) with circle residual {:.2e} above the \
             tolerance {:.0e}",
            options.max_sweeps,
            report.residual_history.last().copied().unwrap_or(f64::NAN),
            options.tol
        ));
    }
    Ok((converged, best))
}

/// Steps 6–10 for the open loop of `system`: invert the image `z` about a point inside the
/// loop, scale the loop to about the unit circle, fill the other loops with planar fans,
/// and map onto the unit disk.
fn planar_step(
    mesh: &TriMesh,
    system: &mut LoopSystem,
    z: &[Complex64],
    newton: &NewtonOptions,
    sweep: usize,
) -> Result<StepSolve, DiskError> {
    let loops = mesh.boundary_loops();
    let k = system.open;
    let at = |values: &[Complex64], l: usize| -> Vec<Complex64> {
        loops[l].iter().map(|&v| values[v as usize]).collect()
    };
    let not_simple = |loop_index| DiskError::LoopNotSimple { loop_index, sweep };
    let c = inner_point(&at(z, k), -1).ok_or_else(|| not_simple(k))?;
    let mut w: Vec<Complex64> = z.iter().map(|&x| 1.0 / (x - c)).collect();
    // the loop's own best-fit circle becomes (about) the unit circle: when the loop is a
    // circle already, its vertices keep their exact angles
    let fit = fit_circle(&at(&w, k));
    if !(fit.radius > 0.0 && fit.radius.is_finite()) {
        return Err(not_simple(k));
    }
    for x in &mut w {
        *x = (*x - fit.center) / fit.radius;
    }
    for &l in &system.filled {
        let p = inner_point(&at(&w, l), -1).ok_or_else(|| not_simple(l))?;
        w.push(p);
    }
    let boundary = at(&w, k);
    let theta0 = unwrapped_angles(&boundary).unwrap_or_else(|| arc_length_angles(&boundary));
    system.solve(&w, theta0, newton)
}

fn record_step(report: &mut KoebeReport, s: &StepSolve, sweep: usize, open: usize, residual: f64) {
    report.steps += 1;
    report.step_history.push(KoebeStepRecord {
        sweep,
        open_loop: open,
        newton_iterations: s.newton.iterations,
        newton_converged: s.newton.converged,
        energy: s.newton.energy,
        residual_max: residual,
        refactored: s.refactored,
    });
    let t: &mut KoebeTimings = &mut report.timings_ms;
    t.assemble += s.assemble_ms;
    t.factor += s.factor_ms;
    t.schur += s.schur_ms;
    t.solve += s.solve_ms;
}

/// Best-fit circle of every loop of `z`.
fn fits(mesh: &TriMesh, z: &[Complex64]) -> Vec<(Circle, f64)> {
    mesh.boundary_loops()
        .iter()
        .map(|lp| {
            let pts: Vec<Complex64> = lp.iter().map(|&v| z[v as usize]).collect();
            let fit = fit_circle(&pts);
            (fit, circle_residual(&pts, fit))
        })
        .collect()
}

/// Worst relative circle residual over every loop.
fn worst_residual(mesh: &TriMesh, z: &[Complex64]) -> f64 {
    fits(mesh, z).iter().fold(0.0, |a, f| a.max(f.1))
}

/// The Möbius normalization of [`koebe`], step 4.
fn normalize(mesh: &TriMesh, z: &mut [Complex64], outer: usize, reference: Option<usize>) {
    let loops = mesh.boundary_loops();
    let outer_pts: Vec<Complex64> = loops[outer].iter().map(|&v| z[v as usize]).collect();
    let fit = fit_circle(&outer_pts);
    // the outer loop runs counter-clockwise around the domain when the domain lies inside
    // its circle; otherwise invert about its centre
    let inside = crate::koebe::circle_fit::winding(&outer_pts, fit.center) == 1;
    for x in z.iter_mut() {
        *x = if inside {
            (*x - fit.center) / fit.radius
        } else {
            fit.radius / (*x - fit.center)
        };
    }
    if let Some(h) = reference {
        let pts: Vec<Complex64> = loops[h].iter().map(|&v| z[v as usize]).collect();
        let p = concentric_point(fit_circle(&pts));
        for x in z.iter_mut() {
            *x = disk_automorphism(*x, p);
        }
    }
    let first = z[loops[outer][0] as usize];
    if first.norm() > 0.0 {
        let turn = first.conj() / first.norm();
        for x in z.iter_mut() {
            *x *= turn;
        }
    }
}

/// The report's circle of every loop in the normalized map.
fn loop_circles(mesh: &TriMesh, z: &[Complex64], outer: usize) -> Vec<LoopCircle> {
    let loops = mesh.boundary_loops();
    fits(mesh, z)
        .into_iter()
        .enumerate()
        .map(|(l, (fit, residual))| {
            if l == outer {
                let residual_max = loops[l]
                    .iter()
                    .map(|&v| (z[v as usize].norm() - 1.0).abs())
                    .fold(0.0, f64::max);
                LoopCircle::new(l, loops[l].len(), true, Circle::UNIT, residual_max)
            } else {
                LoopCircle::new(l, loops[l].len(), false, fit, residual)
            }
        })
        .collect()
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
