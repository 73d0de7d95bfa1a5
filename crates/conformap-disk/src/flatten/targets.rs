//! The boundary data of each target: boundary scale factors `u_B` and target curvature `κ̃`
//! for the free boundary, given scale factors, given angles, BFF's circle, rectangles and
//! polygons, and the automatic choice of a rectangle's corners.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::time::Instant;

use super::boundary::{dirichlet_to_neumann, neumann_to_dirichlet, Curvatures, PinnedLaplacian};
use super::curve::{edge_lengths, scaled_lengths};
use super::target::FlattenBoundary;
use crate::{DiskError, DiskProblem};

/// How far the exterior angles of a target may sum from `2π` (radians) before the target
/// is rejected; a smaller mismatch (rounding in a file of degrees) is spread evenly over
/// the corners.
pub const TURNING_SUM_TOL: f64 = 1e-6;

/// The automatic corners of a rectangle: the sharpest boundary vertex (largest geodesic
/// curvature `κ = π − Σθ`, the first in loop order on ties) is the first corner; then, three
/// times, the sharpest vertex at least [`CORNER_SEPARATION`] of the perimeter (by 3D arc
/// length) from every corner chosen so far, as long as it turns by at least this much
/// (radians). Below it the boundary has no four clear corners, and the corners are instead
/// the vertices nearest to a quarter, a half and three quarters of the perimeter after the
/// sharpest vertex. The corners are then taken in boundary order from the first.
pub const CLEAR_CORNER_RAD: f64 = std::f64::consts::PI / 8.0;

/// The least arc-length distance between two automatic corners, as a share of the
/// perimeter (sides of a rectangle up to about 15 : 1 are told apart).
pub const CORNER_SEPARATION: f64 = 1.0 / 32.0;

/// Boundary data of one target, in the problem's boundary order.
#[derive(Debug)]
pub(crate) struct BoundaryData {
    /// Boundary scale factors `u_B`.
    pub u_b: Vec<f64>,
    /// Target curvature `κ̃` (exterior turning angles).
    pub kappa: Vec<f64>,
    /// Loop positions of the corners (rectangle, polygon), in boundary order.
    pub corners: Vec<usize>,
    /// Loop position the curve starts at (edge `start` points along `+x`).
    pub start: usize,
    /// The factor of the pinned Laplacian, if a Neumann problem was solved.
    pub pinned: Option<PinnedLaplacian>,
    /// Milliseconds of the factorization of the pinned Laplacian (0 without one).
    pub pinned_factor_ms: f64,
}

/// Computes the boundary data of `target`.
pub(crate) fn boundary_data(
    problem: &DiskProblem<'_>,
    curv: &Curvatures,
    target: &FlattenBoundary,
    circle_iterations: usize,
) -> Result<BoundaryData, DiskError> {
    let lp = &problem.partition().boundary;
    let m = lp.len();
    let mut data = BoundaryData {
        u_b: vec![0.0; m],
        kappa: Vec::new(),
        corners: Vec::new(),
        start: 0,
        pinned: None,
        pinned_factor_ms: 0.0,
    };
    let kappa = match target {
        FlattenBoundary::Free => dirichlet_to_neumann(problem, curv, &data.u_b).1,
        FlattenBoundary::Scale(values) => {
            data.u_b = every_boundary_value(problem, values)?;
            dirichlet_to_neumann(problem, curv, &data.u_b).1
        }
        FlattenBoundary::Angles(values) => {
            let mut k = every_boundary_value(problem, values)?;
            fix_turning_sum(&mut k, &(0..m).collect::<Vec<_>>())?;
            k
        }
        FlattenBoundary::Circle => Vec::new(),
        FlattenBoundary::Rectangle { corners, .. } => {
            let pos = match corners {
                Some(c) => corner_positions(problem, c)?,
                None => auto_corners(problem, curv),
            };
            if pos.len() != 4 {
                return Err(DiskError::BadCorners {
                    reason: format!("a rectangle needs 4 corners, got {}", pos.len()),
                });
            }
            data.start = pos[0];
            let mut k = vec![0.0; m];
            for &p in &pos {
                k[p] = FRAC_PI_2;
            }
            data.corners = pos;
            k
        }
        FlattenBoundary::Polygon(list) => {
            let vertices: Vec<u32> = list.iter().map(|c| c.0).collect();
            let pos = corner_positions(problem, &vertices)?;
            if pos.len() < 3 {
                return Err(DiskError::BadCorners {
                    reason: format!("a polygon needs at least 3 corners, got {}", pos.len()),
                });
            }
            let mut k = vec![0.0; m];
            for (&p, c) in pos.iter().zip(list) {
                k[p] = c.1;
            }
            fix_turning_sum(&mut k, &pos)?;
            data.start = pos[0];
            data.corners = pos;
            k
        }
    };
    let needs_neumann = !matches!(target, FlattenBoundary::Free | FlattenBoundary::Scale(_));
    if !needs_neumann {
        data.kappa = kappa;
        return Ok(data);
    }
    let t = Instant::now();
    let pinned = PinnedLaplacian::new(problem, lp[0])?;
    data.pinned_factor_ms = t.elapsed().as_secs_f64() * 1e3;
    let lengths = edge_lengths(problem.mesh(), lp);
    data.kappa = if matches!(target, FlattenBoundary::Circle) {
        circle_curvature(problem, curv, &pinned, &lengths, circle_iterations)
    } else {
        kappa
    };
    let u = neumann_to_dirichlet(problem, &pinned, curv, &data.kappa);
    data.u_b = perimeter_preserving(&lengths, lp.iter().map(|&v| u[v as usize]).collect());
    data.pinned = Some(pinned);
    Ok(data)
}

/// BFF's disk: the curvature of a circle through the boundary, `κ̃_k` proportional to the
/// dual length `(l̃_{k−1} + l̃_k)/2` of the current lengths, which the Neumann solve then
/// changes; repeated `iterations` times from the free boundary's lengths (`u = 0`).
fn circle_curvature(
    problem: &DiskProblem<'_>,
    curv: &Curvatures,
    pinned: &PinnedLaplacian,
    lengths: &[f64],
    iterations: usize,
) -> Vec<f64> {
    let lp = &problem.partition().boundary;
    let m = lp.len();
    let mut scaled = lengths.to_vec();
    let mut kappa = vec![0.0; m];
    for it in 0..iterations.max(1) {
        let total: f64 = scaled.iter().sum();
        for k in 0..m {
            kappa[k] = TAU * 0.5 * (scaled[(k + m - 1) % m] + scaled[k]) / total;
        }
        if it + 1 < iterations {
            let u = neumann_to_dirichlet(problem, pinned, curv, &kappa);
            let u_b: Vec<f64> = lp.iter().map(|&v| u[v as usize]).collect();
            scaled = scaled_lengths(lengths, &u_b);
        }
    }
    kappa
}

/// `u_B` shifted by the constant that keeps the perimeter (a Neumann solution is determined
/// up to a constant, a uniform scale of the map).
fn perimeter_preserving(lengths: &[f64], mut u_b: Vec<f64>) -> Vec<f64> {
    let scaled: f64 = scaled_lengths(lengths, &u_b).iter().sum();
    let total: f64 = lengths.iter().sum();
    let c = (total / scaled).ln();
    if c.is_finite() {
        for u in &mut u_b {
            *u += c;
        }
    }
    u_b
}

/// One value per boundary vertex (boundary order) from `(vertex, value)` pairs, which must
/// name every boundary vertex exactly once.
fn every_boundary_value(
    problem: &DiskProblem<'_>,
    values: &[(u32, f64)],
) -> Result<Vec<f64>, DiskError> {
    let partition = problem.partition();
    let m = partition.boundary.len();
    let mut out = vec![f64::NAN; m];
    for &(v, x) in values {
        let k = boundary_position(problem, v)?;
        if !x.is_finite() {
            return Err(DiskError::NonFiniteBoundaryValue { vertex: v });
        }
        if !out[k].is_nan() {
            return Err(DiskError::BadCorners {
                reason: format!("vertex {v} is given twice"),
            });
        }
        out[k] = x;
    }
    match out.iter().position(|x| x.is_nan()) {
        Some(k) => Err(DiskError::MissingBoundaryValue {
            vertex: partition.boundary[k],
        }),
        None => Ok(out),
    }
}

/// The position of vertex `v` along the boundary loop.
fn boundary_position(problem: &DiskProblem<'_>, v: u32) -> Result<usize, DiskError> {
    let partition = problem.partition();
    let n = partition.is_interior.len();
    if v as usize >= n {
        return Err(DiskError::VertexOutOfRange {
            vertex: v,
            vertices: n,
        });
    }
    if partition.is_interior[v as usize] {
        return Err(DiskError::NotOnBoundary { vertex: v });
    }
    Ok(partition.local[v as usize] as usize)
}

/// Loop positions of the corner vertices, checked: on the boundary, distinct, and in
/// boundary order (cyclically increasing from the first).
fn corner_positions(problem: &DiskProblem<'_>, vertices: &[u32]) -> Result<Vec<usize>, DiskError> {
    let pos = vertices
        .iter()
        .map(|&v| boundary_position(problem, v))
        .collect::<Result<Vec<_>, _>>()?;
    let m = problem.num_boundary();
    let mut last = 0;
    for (i, &p) in pos.iter().enumerate() {
        let offset = (p + m - pos[0]) % m;
        if i > 0 && offset <= last {
            return Err(DiskError::BadCorners {
                reason: format!(
                    "corner vertex {} repeats or is out of boundary order",
                    vertices[i]
                ),
            });
        }
        last = offset;
    }
    Ok(pos)
}

/// Spreads the mismatch of `Σ κ̃` from `2π` evenly over `corners`, or rejects it above
/// [`TURNING_SUM_TOL`].
fn fix_turning_sum(kappa: &mut [f64], corners: &[usize]) -> Result<(), DiskError> {
    let sum: f64 = kappa.iter().sum();
    let miss = sum - TAU;
    if !(miss.abs() <= TURNING_SUM_TOL) {
        return Err(DiskError::TurningSum {
            sum_deg: sum.to_degrees(),
        });
    }
    for &c in corners {
        kappa[c] -= miss / corners.len() as f64;
    }
    Ok(())
}

/// The automatic corners of a rectangle (loop positions, in boundary order): the sharpest
/// boundary vertex (largest geodesic curvature `κ`, first in loop order on ties) is the
/// first corner; then, three times, the sharpest vertex at least [`CORNER_SEPARATION`] of the
/// perimeter (by 3D arc length) from every corner chosen so far. If the fourth turns by less than
/// [`CLEAR_CORNER_RAD`] the boundary has no four clear corners, and the corners are instead
/// the vertices nearest to a quarter, a half and three quarters of the perimeter after the
/// sharpest vertex. Fewer than four distinct corners only on a boundary of fewer than four
/// vertices.
pub(crate) fn auto_corners(problem: &DiskProblem<'_>, curv: &Curvatures) -> Vec<usize> {
    let lp = &problem.partition().boundary;
    let lengths = edge_lengths(problem.mesh(), lp);
    let m = lp.len();
    let mut arc = vec![0.0; m];
    for k in 1..m {
        arc[k] = arc[k - 1] + lengths[k - 1];
    }
    let perimeter = arc[m - 1] + lengths[m - 1];
    let dist = |a: usize, b: usize| {
        let d = (arc[a] - arc[b]).abs();
        d.min(perimeter - d)
    };
    let kappa = &curv.boundary;
    let sharpest = |ok: &dyn Fn(usize) -> bool| {
        (0..m)
            .filter(|&k| ok(k))
            .fold(None, |best: Option<usize>, k| match best {
                Some(b) if kappa[b] >= kappa[k] => Some(b),
                _ => Some(k),
            })
    };
    let first = sharpest(&|_| true).unwrap_or(0);
    let mut chosen = vec![first];
    while chosen.len() < 4 {
        let far = |k: usize| {
            chosen
                .iter()
                .all(|&c| dist(c, k) >= perimeter * CORNER_SEPARATION)
        };
        match sharpest(&far) {
            Some(k) if kappa[k] >= CLEAR_CORNER_RAD => chosen.push(k),
            _ => break,
        }
    }
    if chosen.len() < 4 {
        chosen = (0..4)
            .map(|q| {
                let s = (arc[first] + q as f64 * perimeter / 4.0) % perimeter;
                (0..m)
                    .min_by(|&a, &b| {
                        let da = (arc[a] - s).abs().min(perimeter - (arc[a] - s).abs());
                        let db = (arc[b] - s).abs().min(perimeter - (arc[b] - s).abs());
                        da.total_cmp(&db)
                    })
                    .unwrap_or(first)
            })
            .collect();
    }
    chosen.sort_by_key(|&k| (k + m - first) % m);
    chosen.dedup();
    chosen
}
