//! Boundary first flattening (R. Sawhney, K. Crane, *Boundary First Flattening*, ACM TOG
//! 2017): a conformal flattening chosen by its boundary — the free boundary that keeps the
//! boundary's lengths (`u = 0`, the least area distortion), given scale factors, given
//! exterior angles, BFF's circle, rectangles and polygons with exact corners.
//!
//! One pipeline serves every target: boundary scale factors `u_B` and the target curvature
//! `κ̃` (one converted into the other by a Dirichlet or a Neumann solve, [`boundary`]), the
//! closed boundary curve ([`curve`]), its extension into the interior ([`extend`]). The
//! problem's factor of `L_II` serves the Dirichlet solves and the interior; the Neumann
//! solves (angles, circle, rectangle, polygon, and the conjugate interior) share one
//! factorization of `L` with one vertex pinned.

mod boundary;
mod curve;
mod extend;
mod report;
mod spec;
mod target;
mod targets;

use std::time::Instant;

use conformap_mesh::{fill_all_holes_except, FilledMesh, Topology, TriMesh};
use conformap_metrics::{planar_map_metrics, MapMetrics, MetricsOptions, OuterCircle};
use conformap_operators::memory::FACTOR_BYTES_PER_NLOGN;
use conformap_operators::PeakMemory;
use num_complex::Complex64;

pub use curve::AXIS_SNAP_RAD;
pub use extend::FlattenInterior;
pub use report::{FlattenReport, FlattenTimings, Flattening};
pub use spec::{parse_boundary_values, BoundarySpec};
pub use target::FlattenBoundary;
pub use targets::{CLEAR_CORNER_RAD, CORNER_SEPARATION, TURNING_SUM_TOL};

use crate::laplacian_choice::count_flipped_where;
use crate::{DiskError, DiskProblem, ProblemOptions};

/// Options of [`flatten`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct FlattenOptions {
    /// The target boundary. Default: [`FlattenBoundary::Free`].
    pub boundary: FlattenBoundary,
    /// The interior variant. Default: [`FlattenInterior::Harmonic`].
    pub interior: FlattenInterior,
    /// The Laplacian and factorization options. Default: [`ProblemOptions::DEFAULT`].
    pub problem: ProblemOptions,
    /// Rounds of BFF's circle (curvature from lengths, lengths from curvature). Default: 3.
    pub circle_iterations: usize,
    /// Pairs of boundary edges, each named by its first vertex along the boundary, that
    /// must keep equal lengths: the closing of the boundary curve changes both by the same
    /// factor (the two sides of a seam of a surface cut open, whose target lengths are
    /// equal). Default: none.
    pub equal_lengths: Vec<(u32, u32)>,
    /// Whether a harmonic interior that folds is solved again with the intrinsic Delaunay
    /// Laplacian and then Floater's mean value weights, keeping the one with the fewest
    /// folds. Default: true. A caller with its own local repair of folded faces (the
    /// atlas's `unfold`) turns it off: on a cut closed surface the fold sits beside a
    /// cone, no operator unfolds it, and the mean value factorization (a sparse LU) was
    /// 18 % of spot's whole atlas run.
    pub fold_fallback: bool,
    /// Whether the report measures the map's quality ([`FlattenReport::metrics`]).
    /// Default: true. A caller that measures the result itself (the atlas's chart quality)
    /// turns it off: the metrics are then all zero (the flips, the boundary touches and
    /// `overlap_free` are still counted); on spot's cut surface they were 11.7M of the
    /// flattening's 17M instructions.
    pub measure: bool,
}

impl FlattenOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        boundary: FlattenBoundary::Free,
        interior: FlattenInterior::Harmonic,
        problem: ProblemOptions::DEFAULT,
        circle_iterations: 3,
        equal_lengths: Vec::new(),
        fold_fallback: true,
        measure: true,
    };

    /// Sets [`Self::boundary`].
    #[must_use]
    pub fn with_boundary(mut self, boundary: FlattenBoundary) -> Self {
        self.boundary = boundary;
        self
    }

    /// Sets [`Self::interior`].
    #[must_use]
    pub fn with_interior(mut self, interior: FlattenInterior) -> Self {
        self.interior = interior;
        self
    }

    /// Sets [`Self::equal_lengths`].
    #[must_use]
    pub fn with_equal_lengths(mut self, pairs: Vec<(u32, u32)>) -> Self {
        self.equal_lengths = pairs;
        self
    }

    /// Sets [`Self::circle_iterations`].
    #[must_use]
    pub fn with_circle_iterations(mut self, iterations: usize) -> Self {
        self.circle_iterations = iterations;
        self
    }

    /// Sets [`Self::fold_fallback`].
    #[must_use]
    pub fn with_fold_fallback(mut self, fallback: bool) -> Self {
        self.fold_fallback = fallback;
        self
    }

    /// Sets [`Self::measure`].
    #[must_use]
    pub fn with_measure(mut self, measure: bool) -> Self {
        self.measure = measure;
        self
    }

    /// Sets [`Self::problem`].
    #[must_use]
    pub fn with_problem(mut self, problem: ProblemOptions) -> Self {
        self.problem = problem;
        self
    }
}

impl Default for FlattenOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The closing group of each boundary edge `lp[k] → lp[k + 1]`: its own, unless a pair of
/// `equal` joins it with another (pairs naming a vertex off the loop are ignored).
fn length_groups(lp: &[u32], equal: &[(u32, u32)]) -> Vec<u32> {
    let mut group: Vec<u32> = (0..lp.len() as u32).collect();
    if equal.is_empty() {
        return group;
    }
    let mut at = std::collections::HashMap::with_capacity(lp.len());
    for (k, &v) in lp.iter().enumerate() {
        at.insert(v, k);
    }
    for &(a, b) in equal {
        if let (Some(&i), Some(&j)) = (at.get(&a), at.get(&b)) {
            let g = group[i].min(group[j]);
            group[i] = g;
            group[j] = g;
        }
    }
    group
}

/// Flattens `mesh` conformally onto the plane with the boundary `options` ask for (boundary
/// first flattening, Sawhney & Crane 2017, §4: Eq. 9–10 for the boundary conversions, Eq. 13
/// for the closing, §4.4 for the interior).
///
/// A genus-0 mesh with several boundary loops has its holes filled with centroid fans first
/// (the longest loop stays the boundary); the map is returned for the input's vertices.
///
/// # Errors
/// [`DiskError::NotGenusZero`] unless the mesh is connected, genus 0, with a boundary;
/// [`DiskError::NoInteriorVertex`]; target errors ([`DiskError::NotOnBoundary`],
/// [`DiskError::MissingBoundaryValue`], [`DiskError::BadCorners`],
/// [`DiskError::TurningSum`], [`DiskError::VertexOutOfRange`]); [`DiskError::Operator`] if
/// a factorization fails; [`DiskError::NonFinite`] if the map is not finite.
///
/// # Examples
/// ```
/// use conformap_disk::{flatten, FlattenBoundary, FlattenOptions};
/// # let mesh = conformap_testkit::flat_disk(6, 6);
/// // a flat disk with a free boundary comes back as itself, up to a rigid motion
/// let free = flatten(&mesh, &FlattenOptions::DEFAULT)?;
/// let (p, f) = (mesh.positions(), &free.map);
/// for (a, b) in [(0, 5), (7, 40), (12, 100)] {
///     let d3 = ((p[a][0] - p[b][0]).powi(2) + (p[a][1] - p[b][1]).powi(2)).sqrt();
///     assert!(((f[a] - f[b]).norm() - d3).abs() < 1e-12);
/// }
/// assert_eq!(free.report.metrics.flipped_faces, 0);
/// // the same disk as a rectangle: four right angles
/// let options = FlattenOptions::DEFAULT
///     .with_boundary(FlattenBoundary::Rectangle { corners: None, aspect: None });
/// let rect = flatten(&mesh, &options)?;
/// assert_eq!(rect.corners.len(), 4);
/// assert!(rect.report.closure_residual < 1e-12 && rect.report.overlap_free);
/// # Ok::<(), conformap_disk::DiskError>(())
/// ```
pub fn flatten(mesh: &TriMesh, options: &FlattenOptions) -> Result<Flattening, DiskError> {
    let t0 = Instant::now();
    let filled = fill(mesh)?;
    let work = filled.as_ref().map_or(mesh, |f| &f.mesh);
    // the angle sums need only the geometry: computed beside the assembly and factorization
    let (problem, sums) = rayon::join(
        || DiskProblem::with_options(work, &options.problem),
        || boundary::angle_sums(work),
    );
    let problem = problem?;
    let setup = ms(t0);

    let t = Instant::now();
    let curv = boundary::Curvatures::new(&sums, problem.partition());
    let data = targets::boundary_data(
        &problem,
        &curv,
        &options.boundary,
        options.circle_iterations,
    )?;
    let boundary_ms = ms(t);

    let t = Instant::now();
    let lp = &problem.partition().boundary;
    let lengths = curve::edge_lengths(work, lp);
    let target = curve::scaled_lengths(&lengths, &data.u_b);
    let tangents = curve::tangents(&data.kappa, data.start);
    let groups = length_groups(lp, &options.equal_lengths);
    let closed = curve::close_curve(&target, &target, &tangents, data.start, &groups);
    let points = match options.boundary {
        FlattenBoundary::Circle => on_circle(&closed.lengths, data.start),
        _ => closed.points.clone(),
    };
    let curve_ms = ms(t);

    let t = Instant::now();
    let ears = extend::straight_ears(&problem, &data.kappa);
    let ext = extend::extend(
        &problem,
        &points,
        options.interior,
        data.pinned.as_ref(),
        &ears,
        options.fold_fallback,
    )?;
    let mut map = ext.map;
    map.truncate(mesh.num_vertices());
    if let Some(v) = map
        .iter()
        .position(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        return Err(DiskError::NonFinite {
            vertex: v,
            stage: "flatten",
        });
    }
    let corners: Vec<u32> = data.corners.iter().map(|&k| lp[k]).collect();
    let aspect = match &options.boundary {
        FlattenBoundary::Rectangle { aspect, .. } => {
            Some(stretch_rectangle(&mut map, &corners, *aspect)?)
        }
        _ => None,
    };
    let interior_ms = ms(t);

    let t = Instant::now();
    let metrics = if options.measure {
        planar_map_metrics(
            mesh,
            &map,
            &MetricsOptions::DEFAULT.with_outer_circle(OuterCircle::BestFit),
        )
        .map_err(|_| DiskError::NonFinite {
            vertex: 0,
            stage: "flatten metrics",
        })?
    } else {
        MapMetrics::default()
    };
    let touches = curve::boundary_touches(mesh, &map);
    // the ears are faces of `work`; the input's faces come first in it
    let flipped = count_flipped_where(mesh, &map, |f| !ears[f]);
    let straight_side_ears = ears[..mesh.num_faces()].iter().filter(|&&e| e).count();
    let metrics_ms = ms(t);

    let timings = FlattenTimings {
        setup,
        boundary: boundary_ms,
        curve: curve_ms,
        interior: interior_ms,
        metrics: metrics_ms,
        total: ms(t0),
    };
    let (u_min, u_max) = data
        .u_b
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &u| {
            (a.min(u), b.max(u))
        });
    let report = FlattenReport {
        boundary: options.boundary.name(),
        interior: ext.variant.name(),
        interior_operator: ext.operator.name(),
        flipped_before_fallback: ext.flipped_before,
        corners: corners.clone(),
        closure_gap: closed.gap_before,
        closure_residual: closed.residual,
        closure_max_length_change: closed.max_length_change,
        boundary_u_min: u_min,
        boundary_u_max: u_max,
        conformal_aspect: aspect.map(|a| a.0),
        aspect: aspect.map(|a| a.1),
        aspect_dilatation: aspect.and_then(|a| a.2),
        boundary_touches: touches,
        overlap_free: flipped == 0 && touches == 0,
        straight_side_ears,
        filled_holes: filled.as_ref().map_or(0, |f| f.filled_loops.len()),
        laplacian: problem.laplacian_note(),
        metrics,
        timings_ms: timings,
    };
    Ok(Flattening {
        map,
        boundary_scale: lp.iter().copied().zip(data.u_b.iter().copied()).collect(),
        closure_residual: closed.residual,
        corners,
        timings,
        report,
    })
}

/// Estimated peak resident memory (bytes) of [`flatten`] on `mesh`: the Laplacian and the
/// factor of `L_II`, and for a target with a Neumann solve
/// ([`FlattenBoundary::needs_neumann`], or the conjugate interior) the factor of the pinned
/// `L` beside it.
///
/// # Examples
/// ```
/// use conformap_disk::{flatten_peak_bytes, FlattenBoundary, FlattenOptions};
/// # let mesh = conformap_testkit::flat_disk(10, 40);
/// let free = flatten_peak_bytes(&mesh, &FlattenOptions::DEFAULT);
/// let rect = FlattenOptions::DEFAULT
///     .with_boundary(FlattenBoundary::Rectangle { corners: None, aspect: None });
/// assert!(flatten_peak_bytes(&mesh, &rect) > free && free > 10 << 20);
/// ```
pub fn flatten_peak_bytes(mesh: &TriMesh, options: &FlattenOptions) -> u64 {
    let loops = mesh.boundary_loops();
    let boundary_total: usize = loops.iter().map(Vec::len).sum();
    let outer = loops.iter().map(Vec::len).max().unwrap_or(0);
    // the filled holes add a centre and a fan per inner loop
    let n = mesh.num_vertices() + loops.len().saturating_sub(1);
    let edges = mesh.num_edges() + boundary_total - outer;
    let base = PeakMemory::laplacian(n, edges, n.saturating_sub(outer));
    let neumann =
        options.boundary.needs_neumann() || options.interior == FlattenInterior::Conjugate;
    let pinned = if neumann {
        let m = n.max(2) as f64;
        FACTOR_BYTES_PER_NLOGN * m * m.log2()
    } else {
        0.0
    };
    (base.bytes() as f64 + pinned) as u64
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The disk the pipeline works on: `None` for a disk (work on `mesh` itself), the mesh
/// with every hole but the longest loop filled for a genus-0 mesh with several loops.
fn fill(mesh: &TriMesh) -> Result<Option<FilledMesh>, DiskError> {
    match mesh.topology() {
        Topology::Disk => Ok(None),
        Topology::MultiplyConnected { .. } => {
            let outer = mesh.longest_boundary_loop().unwrap_or(0);
            Ok(Some(fill_all_holes_except(mesh, outer)?))
        }
        found => Err(DiskError::NotGenusZero { found }),
    }
}

/// Boundary points on the circle of the curve's perimeter, spaced by `lengths`.
fn on_circle(lengths: &[f64], start: usize) -> Vec<Complex64> {
    let m = lengths.len();
    let total: f64 = lengths.iter().sum();
    let radius = total / std::f64::consts::TAU;
    let mut out = vec![Complex64::new(0.0, 0.0); m];
    let mut s = 0.0;
    for i in 0..m {
        let k = (start + i) % m;
        out[k] = Complex64::from_polar(radius, std::f64::consts::TAU * s / total);
        s += lengths[k];
    }
    out
}

/// A rectangle's conformal modulus `M` (first corner to second over second to third), the
/// aspect of the returned map, and, for an asked aspect `a`, the dilatation `K` of the
/// affine stretch `x ↦ x √(a/M)`, `y ↦ y √(M/a)` applied to reach it (the map's first side
/// lies along `+x` from the origin).
fn stretch_rectangle(
    map: &mut [Complex64],
    corners: &[u32],
    aspect: Option<f64>,
) -> Result<(f64, f64, Option<f64>), DiskError> {
    let c = |k: usize| map[corners[k] as usize];
    let modulus = (c(1) - c(0)).norm() / (c(2) - c(1)).norm();
    let Some(a) = aspect else {
        return Ok((modulus, modulus, None));
    };
    if !(a > 0.0 && a.is_finite()) {
        return Err(DiskError::InvalidOption {
            name: "aspect",
            reason: "the aspect ratio must be a positive finite number",
        });
    }
    let origin = c(0);
    let s = (a / modulus).sqrt();
    for z in map.iter_mut() {
        let d = *z - origin;
        *z = origin + Complex64::new(d.re * s, d.im / s);
    }
    Ok((modulus, a, Some((a / modulus).max(modulus / a))))
}
