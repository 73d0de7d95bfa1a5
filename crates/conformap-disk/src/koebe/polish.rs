//! The last stage of [`crate::koebe`]: from a normalized circle-domain map (or a rough one),
//! the map of least conformal energy on the surface among all circle-domain maps
//! ([`crate::koebe::polish_newton`]), with its interior.

use std::f64::consts::TAU;
use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_operators::{cotan_laplacian, Cholesky, LaplacianBlocks, Partition};
use num_complex::Complex64;

use crate::error::DiskError;
use crate::koebe::circle_fit::fit_circle;
use crate::koebe::options::KoebeOptions;
use crate::koebe::polish_newton::{minimize_circles, CircleProblem, CircleState, LoopSpec};
use crate::koebe::report::PolishReport;
use crate::koebe::step::dense_schur;

/// Newton iterations of the polish at most: `100`. From a converged Koebe map it needs
/// 3–6; from a rough start (a first map whose holes are far from round) a few dozen.
pub(crate) const POLISH_MAX_ITER: usize = 100;

/// Polishes `z` (outer loop on the unit circle, its first vertex at angle 0, the reference
/// hole centred at 0): minimizes the surface's conformal energy over circle-domain maps and
/// returns the map (the normalization kept) and the account.
pub(crate) fn polish(
    mesh: &TriMesh,
    z: &[Complex64],
    outer: usize,
    reference: Option<usize>,
    options: &KoebeOptions,
) -> Result<(Vec<Complex64>, PolishReport), DiskError> {
    let t0 = Instant::now();
    let loops = mesh.boundary_loops();
    // the mesh's own weights: the energy minimized is the one the metrics judge
    let laplacian = cotan_laplacian(mesh);
    // every loop is boundary: outer first, then the holes, in loop order
    let order: Vec<usize> = std::iter::once(outer)
        .chain((0..loops.len()).filter(|&l| l != outer))
        .collect();
    let mut boundary = Vec::new();
    let mut specs = Vec::new();
    for &l in &order {
        specs.push(LoopSpec {
            start: boundary.len(),
            len: loops[l].len(),
            sign: if l == outer { 1.0 } else { -1.0 },
            free_circle: l != outer,
            pinned_centre: Some(l) == reference,
        });
        boundary.extend_from_slice(&loops[l]);
    }
    let partition = Partition::new(mesh.num_vertices(), &boundary);
    let blocks = LaplacianBlocks::new(&laplacian, &partition);
    let factor = Cholesky::factor(&blocks.ii)?;
    let s = dense_schur(&blocks, &factor);
    let problem = CircleProblem::new(&s, specs.clone());
    let start = start_state(z, &boundary, &specs, &order, outer, reference);
    let result = minimize_circles(&problem, start, POLISH_MAX_ITER, options.newton_step_tol);
    let fb = problem.positions(&result.state);
    let mut rhs = blocks.ib_mul(&fb);
    for v in &mut rhs {
        *v = -*v;
    }
    let fi = factor.solve_complex(&rhs);
    let map = partition.assemble(&fi, &fb);
    let flipped = crate::laplacian_choice::count_flipped(mesh, &map).0;
    if let Some(v) = map.iter().position(|z| !z.is_finite()) {
        return Err(DiskError::NonFinite {
            vertex: v,
            stage: "interior of the circle-domain polish",
        });
    }
    let report = PolishReport {
        iterations: result.iterations,
        converged: result.converged,
        energy_history: result.energy_history,
        flipped_faces: flipped,
        held_vertices: result.held_vertices,
        boundary_vertices: boundary.len(),
        time_ms: t0.elapsed().as_secs_f64() * 1e3,
    };
    Ok((map, report))
}

/// The circle-domain parameters closest to `z`: each hole's best-fit circle (the reference
/// hole's centre set to 0), the outer loop on the unit circle, and the angles of the
/// vertices about their circle's centre, unwrapped along the loop (increasing on the outer
/// loop, decreasing on holes). A loop whose angles do not run monotonically (a rough
/// start) gets angles proportional to arc length. Hole circles that overlap are shrunk
/// about their centres until they are disjoint inside the unit circle.
fn start_state(
    z: &[Complex64],
    boundary: &[u32],
    specs: &[LoopSpec],
    order: &[usize],
    outer: usize,
    reference: Option<usize>,
) -> CircleState {
    let mut theta = vec![0.0; boundary.len()];
    let mut centre = vec![Complex64::new(0.0, 0.0); specs.len()];
    let mut log_radius = vec![0.0; specs.len()];
    for (li, (spec, &l)) in specs.iter().zip(order).enumerate() {
        let pts: Vec<Complex64> = boundary[spec.start..spec.start + spec.len]
            .iter()
            .map(|&v| z[v as usize])
            .collect();
        let (c, r) = if l == outer {
            (Complex64::new(0.0, 0.0), 1.0)
        } else {
            let fit = fit_circle(&pts);
            let c = if Some(l) == reference {
                Complex64::new(0.0, 0.0)
            } else {
                fit.center
            };
            (c, fit.radius.max(1e-6))
        };
        centre[li] = c;
        log_radius[li] = r.ln();
        let angles = loop_angles(&pts, c, spec.sign);
        theta[spec.start..spec.start + spec.len].copy_from_slice(&angles);
    }
    // keep the outer loop's first vertex at angle 0 (the rotation of the normalization)
    let shift = theta[0];
    for t in &mut theta[..specs[0].len] {
        *t -= shift;
    }
    // disjoint circles inside the unit circle
    for _ in 0..30 {
        let mut ok = true;
        for a in 1..specs.len() {
            let ra = log_radius[a].exp();
            if centre[a].norm() + ra >= 1.0 {
                ok = false;
            }
            for b in a + 1..specs.len() {
                if (centre[a] - centre[b]).norm() <= ra + log_radius[b].exp() {
                    ok = false;
                }
            }
        }
        if ok {
            break;
        }
        for r in log_radius.iter_mut().skip(1) {
            *r += (0.8f64).ln();
        }
    }
    CircleState {
        theta,
        centre,
        log_radius,
    }
}

/// Angles of `pts` about `c`, unwrapped so that `sign · θ` increases along the loop with one
/// full turn; arc-length angles if they do not.
fn loop_angles(pts: &[Complex64], c: Complex64, sign: f64) -> Vec<f64> {
    let m = pts.len();
    let mut theta = Vec::with_capacity(m);
    let mut t = (pts[0] - c).arg();
    theta.push(t);
    let mut monotone = true;
    let mut turn = 0.0;
    for k in 0..m {
        let d = ((pts[(k + 1) % m] - c) * (pts[k] - c).conj()).arg();
        if !(sign * d > 0.0) {
            monotone = false;
        }
        turn += d;
        if k + 1 < m {
            t += d;
            theta.push(t);
        }
    }
    if monotone && (turn - sign * TAU).abs() < 1e-6 {
        return theta;
    }
    let lens: Vec<f64> = (0..m)
        .map(|k| (pts[(k + 1) % m] - pts[k]).norm().max(f64::MIN_POSITIVE))
        .collect();
    let total: f64 = lens.iter().sum();
    let mut t = (pts[0] - c).arg();
    lens.iter()
        .map(|len| {
            let here = t;
            t += sign * TAU * len / total;
            here
        })
        .collect()
}
