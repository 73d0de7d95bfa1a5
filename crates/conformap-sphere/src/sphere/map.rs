//! The sphere map of a closed genus-0 mesh: Angenent's map from a Dirac dipole on one face
//! (CEM Eq. 11–14), inverse stereographic projection, then harmonic re-solves in the
//! opposite stereographic chart ("south-pole" corrections) to repair the region around the
//! dipole, which the first solve resolves badly.

use std::time::Instant;

use conformap_disk::initial::angenent_rhs;
use conformap_mesh::{Topology, TriMesh};
use conformap_operators::{
    cotan_laplacian, intrinsic_delaunay_laplacian, relative_residual, triangle_angles, Cholesky,
    CholeskyOptions, LaplacianBlocks, Ordering, Partition,
};
use num_complex::Complex64;
use sprs::CsMat;

use crate::sphere::exact::{centre, inscribed_radial};
use crate::sphere::report::{SphereReport, StageRecord, Timings};
use crate::sphere::source::{farthest_vertex, sphere_source_face};
use crate::sphere::untangle::{inverted_faces, untangle};
use crate::stereo::{
    det3, inverse_stereographic, inverse_stereographic_south, stereographic, stereographic_south,
};
use crate::SphereError;
use conformap_operators::vec3::normalize;

/// Default share of the vertices kept from the previous stage in a correction solve: 0.1.
/// The kept cap lies opposite the badly resolved region, so its values are accurate and the
/// other 90 % are re-solved as a harmonic map with those values fixed; Choi, Lam and Lui's
/// spherical conformal map (2015) fixes the same tenth. Measured on spot, david_head,
/// armadillo and brain: see the crate README.
pub const SPHERE_FIXED_FRACTION: f64 = 0.1;

/// Default cap on correction solves: 4. Each costs one factorization; the first removes the
/// dipole's error, and on the meshes measured a second one (from the other pole) lowers the
/// mean angle distortion by under 1 %, so the loop usually stops after two.
pub const SPHERE_MAX_CORRECTIONS: usize = 4;

/// Default relative gain a correction must bring to the mean angle distortion to be kept and
/// followed by another: 1e-3 (0.1 %). Below it the correction is noise and the loop stops.
pub const SPHERE_MIN_GAIN: f64 = 1e-3;

/// A sphere map counts as converged when the relative residual of its Angenent solve
/// (`SphereReport::residual`, `‖L_uu f − b‖∞ / ‖b‖∞`) is at most this: 1e-8, a thousand
/// times what a sound Cholesky solve leaves on the meshes measured (3e-16 on spot.obj) and
/// far below what would move an angle by a visible amount.
pub const SPHERE_SOLVE_RESIDUAL_TOL: f64 = 1e-8;

/// Options of [`sphere_map`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SphereOptions {
    /// The face carrying Angenent's dipole. Default: `None`, a well-shaped face at the
    /// mesh's approximate centre (see [`sphere_source_face`]).
    pub source_face: Option<usize>,
    /// Share of vertices kept in each correction solve. Default: [`SPHERE_FIXED_FRACTION`];
    /// range `(0, 1)`.
    pub fixed_fraction: f64,
    /// Most correction solves. Default: [`SPHERE_MAX_CORRECTIONS`]; 0 returns Angenent's
    /// map projected to the sphere.
    pub max_corrections: usize,
    /// Relative mean-angle-distortion gain needed to keep a correction and continue.
    /// Default: [`SPHERE_MIN_GAIN`]. A negative value keeps corrections that raise the
    /// distortion by up to that share (to study the stages).
    pub min_gain: f64,
}

impl SphereOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        source_face: None,
        fixed_fraction: SPHERE_FIXED_FRACTION,
        max_corrections: SPHERE_MAX_CORRECTIONS,
        min_gain: SPHERE_MIN_GAIN,
    };

    /// Sets [`Self::source_face`].
    #[must_use]
    pub fn with_source_face(mut self, face: Option<usize>) -> Self {
        self.source_face = face;
        self
    }

    /// Sets [`Self::fixed_fraction`].
    #[must_use]
    pub fn with_fixed_fraction(mut self, fraction: f64) -> Self {
        self.fixed_fraction = fraction;
        self
    }

    /// Sets [`Self::max_corrections`].
    #[must_use]
    pub fn with_max_corrections(mut self, n: usize) -> Self {
        self.max_corrections = n;
        self
    }

    /// Sets [`Self::min_gain`].
    #[must_use]
    pub fn with_min_gain(mut self, gain: f64) -> Self {
        self.min_gain = gain;
        self
    }
}

impl Default for SphereOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A sphere map: one unit vector per vertex, in vertex order, and how it was computed.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct SphereMap {
    /// `points[v]` is the image of vertex `v` on the unit sphere (`||x| − 1| ≤ 1e-15`).
    pub points: Vec<[f64; 3]>,
    /// What was done and what it cost.
    pub report: SphereReport,
}

/// The conformal map of a closed genus-0 mesh onto the unit sphere.
///
/// 1. **Angenent's map** (CEM Eq. 11–14; Angenent et al. 1999): solve `L f = b` with the
///    cotangent Laplacian `L` of the closed mesh, one vertex pinned to 0 (CEM Theorem 1),
///    and `b` the discrete dipole `(∂/∂u − i∂/∂v) δ_p` on the source face
///    ([`conformap_disk::initial::angenent_rhs`]). `f` maps the mesh minus `p` conformally onto the
///    plane, `p` to `∞`.
/// 2. **Projection**: `f` is centred on the median of its values and scaled by the median
///    distance from it (half the vertices in each hemisphere), then mapped to the sphere by
///    `τ⁻¹` (the source near the north pole). If the chord triangles come out clockwise
///    seen from outside (negative total `det`), the map is conjugated (mirrored), which keeps
///    angles: CEM's Eq. 13–14 give the mirror image on the meshes we tried.
/// 3. **Corrections**: the few rings around the source are badly resolved (the solution
///    blows up there). The cap of `fixed_fraction` of the vertices farthest from the bad
///    region is kept; the rest is re-solved as a harmonic map `L_FF w_F = −L_FK w_K` in the
///    stereographic chart centred on the bad region, where the conformal map is finite and
///    smooth. The next correction does the same from the other pole. A correction is kept if
///    it lowers the mean angle distortion by more than `min_gain` (relative); the loop stops
///    at the first that does not, or after `max_corrections`. At least 3 vertices are
///    kept; a correction whose kept cap reaches the chart's pole is skipped.
/// 4. **Centring**: if the map still inverts a face (a coarse mesh, whose large faces
///    invert under a poor normalization), the Möbius map moving the vertex centroid to the
///    origin is applied when it inverts fewer.
///
/// A mesh inscribed in a sphere whose radial projection turns no face over is returned as
/// that projection (`method` `"radial-projection"`, no factorization): it keeps every
/// length cross-ratio, the exact answer.
///
/// Factorizations: one of `L` reduced by the pinned vertex, one per correction.
///
/// # Errors
/// [`SphereError::WrongTopology`] unless the mesh is closed, connected and genus 0;
/// [`SphereError::InvalidOption`]; [`SphereError::Operator`] if a factorization fails;
/// [`SphereError::NonFinite`] if a solve overflows.
///
/// # Examples
/// ```
/// use conformap_sphere::{sphere_map, sphere_metrics, SphereOptions};
/// # let mesh = conformap_sphere::doc_support::octahedron_sphere(4);
/// // `mesh`: a closed genus-0 mesh (here an ellipsoid, a subdivided octahedron of 1026
/// // vertices squashed to half height)
/// let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
/// let m = sphere_metrics(&mesh, &map.points)?;
/// assert!(m.radius_residual_max < 1e-12);
/// assert_eq!(m.flipped_faces, 0);
/// assert!(m.angle_distortion_deg.mean < 1.0);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
pub fn sphere_map(mesh: &TriMesh, options: &SphereOptions) -> Result<SphereMap, SphereError> {
    let t_all = Instant::now();
    let found = mesh.topology();
    if found != Topology::Sphere {
        return Err(SphereError::WrongTopology {
            operation: "a sphere map",
            expected: "a closed, connected genus-0 mesh",
            found,
        });
    }
    check_options(mesh, options)?;
    if let Some(points) = inscribed_radial(mesh) {
        return Ok(radial_map(mesh, points, t_all));
    }
    let t = Instant::now();
    let l = cotan_laplacian(mesh);
    let first = solve_with(mesh, &l, options, ms(t), t_all)?;
    let flips = first.report.stages[first.report.best_stage].flipped_faces;
    if flips == 0 {
        return Ok(first);
    }
    // the guard: a face inverted (a folded sliver of a scan, strongly negative cotangent
    // weights); the intrinsic Delaunay Laplacian has no negative weight
    let t = Instant::now();
    let (idl, stats) = intrinsic_delaunay_laplacian(mesh)?;
    let second = solve_with(mesh, &idl, options, ms(t), Instant::now())?;
    let (f1, f2) = (
        first.report.stages[first.report.best_stage].flipped_faces,
        second.report.stages[second.report.best_stage].flipped_faces,
    );
    // candidates: both maps, each as solved and locally untangled with the intrinsic
    // Delaunay weights and with Tutte's uniform weights; the fewest inverted faces win,
    // then the lowest mean angle distortion
    let angles = mesh_corner_angles(mesh);
    let mut best: Option<GuardCandidate> = None;
    for (is_second, map) in [(false, &first), (true, &second)] {
        for how in [None, Some(false), Some(true)] {
            let mut p = map.points.clone();
            let left = match how {
                None => inverted_faces(mesh, &p).len(),
                Some(uniform) => untangle(mesh, &idl, uniform, &mut p),
            };
            let d = stage_record(mesh, &angles, &p, "guard").mean_angle_distortion_deg;
            if best.as_ref().is_none_or(|b| (left, d) < (b.0, b.1)) {
                let label = format!(
                    "{}{}",
                    if is_second {
                        "intrinsic Delaunay"
                    } else {
                        "cotangent"
                    },
                    match how {
                        None => "",
                        Some(false) => " + untangled",
                        Some(true) => " + untangled (uniform weights)",
                    }
                );
                best = Some((left, d, label, p, is_second));
            }
        }
    }
    let Some((left, _, label, points, is_second)) = best else {
        return Ok(first);
    };
    let mut out = if is_second { second } else { first };
    out.points = points;
    out.report.guard = Some(format!(
        "the cotangent Laplacian's map inverted {f1} faces, the intrinsic Delaunay \
         Laplacian's ({} edge flips) {f2}; kept the {label} map: {left} inverted faces",
        stats.flips,
    ));
    out.report.timings_ms.total = ms(t_all);
    Ok(out)
}

/// A candidate of the flip-free guard: inverted faces, mean angle distortion, its name, its
/// points, whether it is the intrinsic Delaunay map.
type GuardCandidate = (usize, f64, String, Vec<[f64; 3]>, bool);

/// Steps 1–3 of [`sphere_map`] with the Laplacian `l` (assembled in `assemble_ms`).
fn solve_with(
    mesh: &TriMesh,
    l: &CsMat<f64>,
    options: &SphereOptions,
    assemble_ms: f64,
    t_all: Instant,
) -> Result<SphereMap, SphereError> {
    let n = mesh.num_vertices();
    let mut timings = Timings {
        assemble: assemble_ms,
        ..Timings::default()
    };

    let source = match options.source_face {
        Some(f) => f,
        None => sphere_source_face(mesh),
    };
    let pinned = farthest_vertex(mesh, source);
    // 1. Angenent's map
    let t = Instant::now();
    let part = Partition::new(n, &[pinned as u32]);
    let blocks = LaplacianBlocks::new(l, &part);
    timings.assemble += ms(t);
    let t = Instant::now();
    let factor = Cholesky::factor(&blocks.ii)?;
    // each vertex's elimination rank: the corrections' factorizations inherit the order
    let mut rank = vec![u32::MAX; n];
    for (k, p) in factor.permutation().into_iter().enumerate() {
        rank[part.interior[p] as usize] = k as u32;
    }
    timings.factor += ms(t);
    let t = Instant::now();
    let mut rhs = vec![Complex64::new(0.0, 0.0); n - 1];
    for (v, val) in angenent_rhs(mesh, source) {
        if v as usize != pinned {
            rhs[part.local[v as usize] as usize] += val;
        }
    }
    let sol = factor.solve_complex(&rhs);
    let residual = relative_residual(&blocks.ii, &sol, &rhs);
    let f = part.assemble(&sol, &[Complex64::new(0.0, 0.0)]);
    check_finite(&f, "Angenent solve")?;
    // 2. centre, scale, project
    let z = centre_and_scale(&f);
    let mut points: Vec<[f64; 3]> = z.iter().map(|&w| inverse_stereographic(w)).collect();
    let conjugated = total_det(mesh, &points) < 0.0;
    if conjugated {
        for p in &mut points {
            p[1] = -p[1];
        }
    }
    timings.solve += ms(t);
    let mesh_angles = mesh_corner_angles(mesh);
    let mut stages = vec![stage_record(mesh, &mesh_angles, &points, "angenent")];
    // 3. corrections, alternating poles
    let mut best = 0usize;
    let mut best_points = points.clone();
    let mut fixed_vertices = 0;
    let mut factorizations = 1;
    let mut kept = 0;
    for k in 0..options.max_corrections {
        let from_south = k % 2 == 0;
        let (next, nfixed, fms) =
            correct(l, &best_points, &rank, options.fixed_fraction, from_south)?;
        factorizations += 1;
        timings.factor += fms;
        fixed_vertices = nfixed;
        let Some(next) = next else {
            // the kept cap reaches the chart's pole (a small mesh): nothing to correct
            stages.push(StageRecord {
                stage: "correction skipped: the kept cap reaches the chart's pole".to_string(),
                mean_angle_distortion_deg: stages[best].mean_angle_distortion_deg,
                flipped_faces: stages[best].flipped_faces,
            });
            break;
        };
        let rec = stage_record(
            mesh,
            &mesh_angles,
            &next,
            if from_south {
                "correction from the south cap"
            } else {
                "correction from the north cap"
            },
        );
        let prev = stages[best].mean_angle_distortion_deg;
        let gain = (prev - rec.mean_angle_distortion_deg) / prev.max(f64::MIN_POSITIVE);
        let no_new_flips = rec.flipped_faces <= stages[best].flipped_faces;
        stages.push(rec);
        if gain > options.min_gain && no_new_flips {
            kept += 1;
            best = stages.len() - 1;
            best_points = next;
        } else {
            break;
        }
    }
    if stages[best].flipped_faces > 0 {
        // a face larger than a hemisphere inverts under a poor normalization (coarse
        // meshes): the centred Möbius normalization
        let mut moved = best_points.clone();
        centre(&mut moved);
        let rec = stage_record(mesh, &mesh_angles, &moved, "Möbius centring");
        let fewer = rec.flipped_faces < stages[best].flipped_faces;
        stages.push(rec);
        if fewer {
            best = stages.len() - 1;
            best_points = moved;
        }
    }
    timings.solve = ms(t_all) - timings.assemble - timings.factor;
    timings.total = ms(t_all);
    let report = SphereReport {
        method: "angenent+stereographic-corrections".to_string(),
        source_face: source,
        pinned_vertex: pinned,
        conjugated,
        fixed_vertices,
        corrections: kept,
        stages,
        best_stage: best,
        factorizations,
        residual,
        timings_ms: timings,
        guard: None,
    };
    Ok(SphereMap {
        points: best_points,
        report,
    })
}

fn check_options(mesh: &TriMesh, o: &SphereOptions) -> Result<(), SphereError> {
    if !(o.fixed_fraction > 0.0 && o.fixed_fraction < 1.0) {
        return Err(SphereError::InvalidOption {
            name: "fixed_fraction",
            reason: "must lie strictly between 0 and 1",
        });
    }
    if !o.min_gain.is_finite() {
        return Err(SphereError::InvalidOption {
            name: "min_gain",
            reason: "must be finite",
        });
    }
    if let Some(f) = o.source_face {
        if f >= mesh.num_faces() {
            return Err(SphereError::InvalidOption {
                name: "source_face",
                reason: "must be a face index of the mesh",
            });
        }
    }
    Ok(())
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn check_finite(f: &[Complex64], stage: &'static str) -> Result<(), SphereError> {
    match f
        .iter()
        .position(|z| !(z.re.is_finite() && z.im.is_finite()))
    {
        Some(vertex) => Err(SphereError::NonFinite { vertex, stage }),
        None => Ok(()),
    }
}

/// `(f − c)/s` with `c` the coordinate-wise median of `f` and `s` the median of `|f − c|`.
fn centre_and_scale(f: &[Complex64]) -> Vec<Complex64> {
    let median = |mut v: Vec<f64>| -> f64 {
        let k = v.len() / 2;
        *v.select_nth_unstable_by(k, f64::total_cmp).1
    };
    let c = Complex64::new(
        median(f.iter().map(|z| z.re).collect()),
        median(f.iter().map(|z| z.im).collect()),
    );
    let s = median(f.iter().map(|z| (z - c).norm()).collect()).max(f64::MIN_POSITIVE);
    f.iter().map(|z| (z - c) / s).collect()
}

fn total_det(mesh: &TriMesh, points: &[[f64; 3]]) -> f64 {
    mesh.faces()
        .iter()
        .map(|t| {
            det3(
                points[t[0] as usize],
                points[t[1] as usize],
                points[t[2] as usize],
            )
        })
        .sum()
}

fn mesh_corner_angles(mesh: &TriMesh) -> Vec<[f64; 3]> {
    conformap_operators::corner_angles(mesh)
}

/// Mean chord-angle distortion and inverted faces of a stage.
fn stage_record(
    mesh: &TriMesh,
    mesh_angles: &[[f64; 3]],
    points: &[[f64; 3]],
    name: &str,
) -> StageRecord {
    let mut sum = 0.0;
    let mut count = 0usize;
    let mut flipped = 0usize;
    for (t, am) in mesh.faces().iter().zip(mesh_angles) {
        let q = t.map(|v| points[v as usize]);
        if !(det3(q[0], q[1], q[2]) > 0.0) {
            flipped += 1;
        }
        let ai = triangle_angles(q);
        for k in 0..3 {
            let d = (am[k] - ai[k]).abs();
            if d.is_finite() {
                sum += d;
                count += 1;
            }
        }
    }
    StageRecord {
        stage: name.to_string(),
        mean_angle_distortion_deg: (sum / count.max(1) as f64).to_degrees(),
        flipped_faces: flipped,
    }
}

/// What [`correct`] returns: the new points (or `None`), the number of vertices kept and
/// the factorization time in milliseconds.
type Correction = (Option<Vec<[f64; 3]>>, usize, f64);

/// One correction: keep the `fraction` of vertices nearest the south pole (`from_south`) or
/// the north pole, and re-solve the rest as a harmonic map in the chart centred on the other
/// pole. Returns the new points (`None` when a kept value is not finite in the chart: the
/// cap reaches its pole, as on a mesh of a few vertices, or the solve overflows), the number
/// kept and the factorization time. At least 3 vertices are kept (fewer pin the harmonic
/// map to a point or a line).
///
/// The factorization eliminates the free vertices in the order of the first stage's
/// (`rank`, per vertex): an elimination order restricted to a principal submatrix fills no
/// more than it did on the whole, and the fresh fill-reducing ordering it saves was a third
/// of each correction's factorization (armadillo: the three factorizations 235–245 → 191–194
/// ms).
fn correct(
    l: &CsMat<f64>,
    points: &[[f64; 3]],
    rank: &[u32],
    fraction: f64,
    from_south: bool,
) -> Result<Correction, SphereError> {
    let n = points.len();
    let keep = ((fraction * n as f64).ceil() as usize).clamp(3.min(n - 1), n - 1);
    let mut order: Vec<u32> = (0..n as u32).collect();
    let height = |v: u32| points[v as usize][2];
    if from_south {
        order.sort_by(|&a, &b| height(a).total_cmp(&height(b)).then(a.cmp(&b)));
    } else {
        order.sort_by(|&a, &b| height(b).total_cmp(&height(a)).then(a.cmp(&b)));
    }
    let kept: Vec<u32> = order[..keep].to_vec();
    let part = Partition::new(n, &kept);
    let blocks = LaplacianBlocks::new(l, &part);
    let t = Instant::now();
    let mut perm: Vec<usize> = (0..part.interior.len()).collect();
    perm.sort_unstable_by_key(|&p| (rank[part.interior[p] as usize], p));
    let inherited = CholeskyOptions::DEFAULT.with_ordering(Ordering::Custom(perm));
    let factor = Cholesky::factor_with(&blocks.ii, &inherited)?;
    let fms = ms(t);
    // the chart where the free region is finite: σ (centred on the north pole) when the
    // south cap is kept, τ otherwise
    let chart = |p: [f64; 3]| {
        if from_south {
            stereographic_south(p)
        } else {
            stereographic(p)
        }
    };
    let wb: Vec<Complex64> = kept.iter().map(|&v| chart(points[v as usize])).collect();
    if !wb.iter().all(|z| z.re.is_finite() && z.im.is_finite()) {
        return Ok((None, keep, 0.0));
    }
    let mut rhs = blocks.ib_mul(&wb);
    for z in &mut rhs {
        *z = -*z;
    }
    let wi = factor.solve_complex(&rhs);
    if check_finite(&wi, "correction solve").is_err() {
        return Ok((None, keep, fms));
    }
    let mut out = points.to_vec();
    for (k, &v) in part.interior.iter().enumerate() {
        out[v as usize] = if from_south {
            inverse_stereographic_south(wi[k])
        } else {
            inverse_stereographic(wi[k])
        };
    }
    for p in &mut out {
        *p = normalize(*p);
    }
    Ok((Some(out), keep, fms))
}

/// The map of an inscribed mesh: its radial projection (see `exact.rs`).
fn radial_map(mesh: &TriMesh, points: Vec<[f64; 3]>, t_all: Instant) -> SphereMap {
    let angles = mesh_corner_angles(mesh);
    let stage = stage_record(mesh, &angles, &points, "radial projection (inscribed mesh)");
    let total = ms(t_all);
    SphereMap {
        points,
        report: SphereReport {
            method: "radial-projection".to_string(),
            stages: vec![stage],
            timings_ms: Timings {
                solve: total,
                total,
                ..Timings::default()
            },
            ..SphereReport::default()
        },
    }
}
