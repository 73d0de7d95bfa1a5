//! Optimal Möbius transformations of a sphere or disk map (Jin et al. 2004, §3.4) for the
//! uniformity energy (Eq. 1–2, 7) or the emphasized area (Eq. 3–4, 8, 10).
//!
//! Rotations change no area, and every Möbius map of the sphere (of the disk) is a rotation
//! after a boost, so both energies depend only on the boost: `u ∈ ℝ³` for the sphere
//! ([`Mobius::boost`]), `v ∈ ℝ²` for the disk ([`DiskAutomorphism::from_vector`]). The
//! optimizer is a damped Newton method on that vector — analytic gradient, Hessian by
//! central differences of it, Levenberg damping, Armijo acceptance — run from several
//! starts; the best local optimum wins, and the given map (`u = 0`) is always one start, so
//! the energy never rises.
//!
//! **The emphasized area has no maximizer.** A boost towards a point inside the region
//! stretches a small disk around that point over almost the whole sphere (or disk), so the
//! region's share of the image area tends to 1 as the boost length grows, without reaching
//! it. The optimization is therefore done over boosts whose own largest area magnification
//! `e^{2|u|}` is at most [`MobiusOptions::max_area_scale`] (default
//! [`EMPHASIZE_MAX_AREA_SCALE`]), and the report says whether that cap is active (it
//! normally is: the optimum is then found by Newton's method on the cap's sphere).
//! [`MobiusObjective::EmphasizeDensity`] is a well-posed alternative with an interior
//! optimum: the region's mean log area magnification.

use std::time::Instant;

use conformap_mesh::TriMesh;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::mobius::energy::{
    check_len, chord_areas, planar_areas, planar_signed_area, region_mask, region_share_from_areas,
    surface_shares, uniformity_from_areas,
};
use crate::mobius::locality::Renumbered;
use crate::mobius::maps::{DiskAutomorphism, Mobius, MobiusCoefficients};
use crate::mobius::newton::{minimize, EvalFn, NewtonSettings};
use crate::mobius::objective::{DiskProblemM, SphereProblem, Target};
#[allow(unused_imports)] // the module docs link to EMPHASIZE_MAX_AREA_SCALE
use crate::mobius::options::{
    MobiusObjective, MobiusOptions, EMPHASIZE_MAX_AREA_SCALE, MAP_RADIUS_TOL,
};
use crate::SphereError;
use conformap_operators::vec3::{norm, normalize};

/// One start of the optimizer.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct StartRecord {
    /// The starting boost vector.
    pub start: Vec<f64>,
    /// The objective at the local optimum found: the uniformity energy, the region's share
    /// (`emphasize`) or its mean log area magnification (`emphasize-density`).
    pub energy: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// Whether it stopped on the step tolerance or by merging (not the iteration cap).
    pub converged: bool,
    /// The earlier start whose optimum this one ran into (within 1e-3 of it, inside
    /// Newton's basin), where it stopped early; `None` for a new optimum.
    pub merged_into: Option<usize>,
}

/// What the Möbius optimization did and achieved.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct MobiusReport {
    /// `"uniform"`, `"emphasize"` or `"emphasize-density"`.
    pub objective: String,
    /// `"sphere"` or `"disk"`.
    pub domain: String,
    /// Uniformity energy of the given map.
    pub uniformity_before: f64,
    /// Uniformity energy of the returned map.
    pub uniformity_after: f64,
    /// Image-area share of the emphasized region before (`None` for `uniform`).
    pub region_share_before: Option<f64>,
    /// Image-area share of the emphasized region after (`None` for `uniform`).
    pub region_share_after: Option<f64>,
    /// Surface-area share of the emphasized region (`None` for `uniform`).
    pub region_surface_share: Option<f64>,
    /// The optimal boost vector (`u ∈ ℝ³` or `v ∈ ℝ²`).
    pub boost: Vec<f64>,
    /// Its hyperbolic length `|u|`.
    pub boost_length: f64,
    /// The boost's own largest area magnification `e^{2|u|}`.
    pub max_area_scale: f64,
    /// Whether the optimum lies on the cap of the boost length.
    pub cap_active: bool,
    /// The optimal map as Möbius coefficients (`ad − bc = 1`; for the disk `c = b̄, d = ā`).
    pub mobius: MobiusCoefficients,
    /// Every start.
    pub starts: Vec<StartRecord>,
    /// Index into `starts` of the optimum.
    pub best_start: usize,
    /// Energy-and-gradient evaluations, all starts.
    pub evaluations: usize,
    /// Whether the best start converged.
    pub converged: bool,
    /// The optimization's residual: the norm of the objective's gradient in the boost
    /// vector at the returned optimum (its tangential part where the boost length is
    /// capped).
    pub gradient_norm: f64,
    /// Wall-clock milliseconds.
    pub time_ms: f64,
    /// `Some(t)` when the optimal boost would have inverted faces of a disk map that
    /// crowds triangles near f64 resolution and was scaled by `t < 1` (the largest scale
    /// that inverts none the input did not); `None` otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flip_limited: Option<f64>,
}

/// A sphere map moved by its optimal Möbius transformation.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct SphereMobius {
    /// The moved map, unit vectors.
    pub points: Vec<[f64; 3]>,
    /// The Möbius map applied (through stereographic projection: `τ⁻¹ ∘ μ ∘ τ`).
    pub mobius: Mobius,
    /// The report.
    pub report: MobiusReport,
}

/// A disk map moved by its optimal automorphism.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct DiskMobius {
    /// The moved map.
    pub map: Vec<Complex64>,
    /// The automorphism applied.
    pub automorphism: DiskAutomorphism,
    /// The report.
    pub report: MobiusReport,
}

fn starts(dim: usize, radius: f64, multi: bool) -> Vec<Vec<f64>> {
    let mut out = vec![vec![0.0; dim]];
    if !multi {
        return out;
    }
    for k in 0..dim {
        for s in [1.0, -1.0] {
            let mut u = vec![0.0; dim];
            u[k] = s * radius;
            out.push(u);
        }
    }
    out
}

struct Prepared {
    shares: Vec<f64>,
    mask: Option<Vec<bool>>,
    /// The objective is the log density, not the share.
    density: bool,
    radius: f64,
}

impl Prepared {
    /// The same problem on the renumbered faces of `r`.
    fn renumbered(&self, r: &Renumbered) -> Self {
        Self {
            shares: r.faces_of(&self.shares),
            mask: self.mask.as_ref().map(|m| r.faces_of(m)),
            density: self.density,
            radius: self.radius,
        }
    }

    fn target(&self) -> Target<'_> {
        match (&self.mask, self.density) {
            (Some(m), true) => Target::EmphasizeDensity(m, &self.shares),
            (Some(m), false) => Target::Emphasize(m),
            (None, _) => Target::Uniform(&self.shares),
        }
    }
}

fn prepare(
    mesh: &TriMesh,
    objective: &MobiusObjective,
    options: &MobiusOptions,
) -> Result<Prepared, SphereError> {
    if !(options.start_radius >= 0.0 && options.start_radius.is_finite()) {
        return Err(SphereError::InvalidOption {
            name: "start_radius",
            reason: "must be a finite number ≥ 0",
        });
    }
    if !(options.step_tol > 0.0) {
        return Err(SphereError::InvalidOption {
            name: "step_tol",
            reason: "must be positive",
        });
    }
    let shares = surface_shares(mesh);
    let check_boost = || {
        if options.max_boost > 0.0 && options.max_boost.is_finite() {
            Ok(options.max_boost)
        } else {
            Err(SphereError::InvalidOption {
                name: "max_boost",
                reason: "must be a positive finite number",
            })
        }
    };
    let (mask, radius) = match objective {
        MobiusObjective::EmphasizeDensity { region } => {
            (Some(region_mask(mesh.num_faces(), region)?), check_boost()?)
        }
        MobiusObjective::Uniform => {
            if !(options.max_boost > 0.0 && options.max_boost.is_finite()) {
                return Err(SphereError::InvalidOption {
                    name: "max_boost",
                    reason: "must be a positive finite number",
                });
            }
            (None, options.max_boost)
        }
        MobiusObjective::Emphasize { region } => {
            if !(options.max_area_scale > 1.0 && options.max_area_scale.is_finite()) {
                return Err(SphereError::InvalidOption {
                    name: "max_area_scale",
                    reason: "must be a finite number > 1",
                });
            }
            (
                Some(region_mask(mesh.num_faces(), region)?),
                0.5 * options.max_area_scale.ln(),
            )
        }
    };
    Ok(Prepared {
        shares,
        mask,
        density: matches!(objective, MobiusObjective::EmphasizeDensity { .. }),
        radius,
    })
}

/// Runs the starts and returns the best local minimum, its index and the records.
fn run_starts(
    eval: &EvalFn<'_>,
    dim: usize,
    radius: f64,
    options: &MobiusOptions,
    emphasize: bool,
) -> (Vec<f64>, usize, Vec<StartRecord>, usize, bool, f64) {
    let start_r = options.start_radius.min(0.5 * radius);
    let mut records: Vec<StartRecord> = Vec::new();
    let mut best: Option<(f64, Vec<f64>, usize, bool)> = None;
    let mut evaluations = 0;
    // distinct optima found so far, and the start that found each
    let mut optima: Vec<Vec<f64>> = Vec::new();
    let mut finder: Vec<usize> = Vec::new();
    for (k, x0) in starts(dim, start_r, options.multi_start)
        .into_iter()
        .enumerate()
    {
        let settings = NewtonSettings {
            max_iter: options.max_iter,
            step_tol: options.step_tol,
            radius,
            known: &optima,
        };
        let r = minimize(eval, &x0, &settings);
        evaluations += r.evaluations;
        let merged_into = r.merged.map(|m| finder[m]);
        records.push(StartRecord {
            start: x0,
            energy: if emphasize { -r.f } else { r.f },
            iterations: r.iterations,
            converged: r.converged,
            merged_into,
        });
        if merged_into.is_none() {
            optima.push(r.x.clone());
            finder.push(k);
        }
        if best.as_ref().is_none_or(|b| r.f < b.0) {
            best = Some((r.f, r.x, k, r.converged));
        }
    }
    let (_, x, k, conv) = best.unwrap_or((0.0, vec![0.0; dim], 0, false));
    let residual = tangential_gradient_norm(eval, &x, radius);
    (x, k, records, evaluations, conv, residual)
}

/// `|∇f(x)|`, without its radial part where `x` lies on the ball's cap (there the optimum
/// is constrained and only the tangential gradient vanishes): the optimization's residual.
fn tangential_gradient_norm(eval: &EvalFn<'_>, x: &[f64], radius: f64) -> f64 {
    let (_, mut g) = eval(x);
    let len = x.iter().map(|v| v * v).sum::<f64>().sqrt();
    if len >= radius * (1.0 - 1e-9) && len > 0.0 {
        let radial = g.iter().zip(x).map(|(a, b)| a * b).sum::<f64>() / (len * len);
        for (gi, xi) in g.iter_mut().zip(x) {
            *gi -= radial * xi;
        }
    }
    g.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The Möbius transformation of the sphere that optimizes `objective` for the sphere map
/// `points` of `mesh` (Jin et al. 2004, §3.4, "topological sphere"), and the moved map.
///
/// # Errors
/// [`SphereError::MapLength`], [`SphereError::NonFiniteMap`], [`SphereError::NotOnSphere`]
/// (a point farther than [`MAP_RADIUS_TOL`] from the unit sphere), the region errors of
/// [`crate::region_mask`], [`SphereError::InvalidOption`].
///
/// # Examples
/// ```
/// use conformap_sphere::{optimize_sphere_mobius, sphere_map, MobiusObjective, MobiusOptions, SphereOptions};
/// # let mesh = conformap_sphere::doc_support::octahedron_sphere(2);
/// let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
/// let best = optimize_sphere_mobius(&mesh, &map.points, &MobiusObjective::Uniform, &MobiusOptions::DEFAULT)?;
/// assert!(best.report.uniformity_after <= best.report.uniformity_before);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
pub fn optimize_sphere_mobius(
    mesh: &TriMesh,
    points: &[[f64; 3]],
    objective: &MobiusObjective,
    options: &MobiusOptions,
) -> Result<SphereMobius, SphereError> {
    let t0 = Instant::now();
    check_len(mesh, points.len())?;
    for (v, p) in points.iter().enumerate() {
        if !p.iter().all(|x| x.is_finite()) {
            return Err(SphereError::NonFiniteMap { vertex: v });
        }
        let r = norm(*p);
        if !((r - 1.0).abs() <= MAP_RADIUS_TOL) {
            return Err(SphereError::NotOnSphere {
                vertex: v,
                radius: r,
            });
        }
    }
    let base: Vec<[f64; 3]> = points.iter().map(|p| normalize(*p)).collect();
    let prep = prepare(mesh, objective, options)?;
    let prob = SphereProblem::new(&base, mesh.faces());
    // the evaluations run on a renumbered copy (see `locality.rs`): the same sums, fewer
    // cache misses
    let local = Renumbered::new(mesh.positions(), mesh.faces(), &base);
    let local_prep = prep.renumbered(&local);
    let local_prob = SphereProblem::new(&local.points, &local.faces);
    let target = local_prep.target();
    let eval = |x: &[f64]| local_prob.eval(x, target);
    let (u, best_start, starts, evaluations, converged, residual) =
        run_starts(&eval, 3, prep.radius, options, prep.mask.is_some());
    let moved: Vec<[f64; 3]> = prob.boosted(&u).into_iter().map(normalize).collect();
    let mobius = Mobius::boost([u[0], u[1], u[2]]);
    let areas_before = chord_areas(mesh, &base);
    let areas_after = chord_areas(mesh, &moved);
    let report = finish_report(
        objective,
        "sphere",
        &prep,
        (&areas_before, &areas_after),
        u,
        mobius.to_report(),
        (starts, best_start, evaluations, converged),
        t0,
    );
    let report = MobiusReport {
        gradient_norm: residual,
        ..report
    };
    Ok(SphereMobius {
        points: moved,
        mobius,
        report,
    })
}

/// The automorphism of the unit disk that optimizes `objective` for the disk map `map` of
/// `mesh` (Jin et al. 2004, §3.4, "topological disk"), and the moved map.
///
/// # Errors
/// [`SphereError::MapLength`], [`SphereError::NonFiniteMap`], [`SphereError::NotInDisk`]
/// (a point farther than [`MAP_RADIUS_TOL`] outside the unit circle), the region errors of
/// [`crate::region_mask`], [`SphereError::InvalidOption`].
///
/// # Examples
/// ```
/// use conformap_sphere::{optimize_disk_mobius, MobiusObjective, MobiusOptions};
/// use num_complex::Complex64;
/// # let mesh = conformap_testkit::flat_disk(8, 8);
/// // a flat unit disk mesh, mapped by a disk automorphism that crowds it to one side
/// let moved = conformap_sphere::DiskAutomorphism::from_vector([1.0, 0.5]);
/// let map: Vec<Complex64> = mesh.positions().iter()
///     .map(|p| moved.apply(Complex64::new(p[0], p[1]))).collect();
/// let best = optimize_disk_mobius(&mesh, &map, &MobiusObjective::Uniform, &MobiusOptions::DEFAULT)?;
/// // the optimum undoes the crowding
/// assert!(best.report.uniformity_after < 0.01 * best.report.uniformity_before);
/// # Ok::<(), conformap_sphere::SphereError>(())
/// ```
pub fn optimize_disk_mobius(
    mesh: &TriMesh,
    map: &[Complex64],
    objective: &MobiusObjective,
    options: &MobiusOptions,
) -> Result<DiskMobius, SphereError> {
    let t0 = Instant::now();
    check_len(mesh, map.len())?;
    for (v, z) in map.iter().enumerate() {
        if !(z.re.is_finite() && z.im.is_finite()) {
            return Err(SphereError::NonFiniteMap { vertex: v });
        }
        if !(z.norm() <= 1.0 + MAP_RADIUS_TOL) {
            return Err(SphereError::NotInDisk {
                vertex: v,
                radius: z.norm(),
            });
        }
    }
    let prep = prepare(mesh, objective, options)?;
    let prob = DiskProblemM {
        map,
        faces: mesh.faces(),
    };
    let target = prep.target();
    let eval = |x: &[f64]| prob.eval(x, target);
    let (v, best_start, starts, evaluations, converged, residual) =
        run_starts(&eval, 2, prep.radius, options, prep.mask.is_some());
    let (v, moved, flip_limit) = keep_orientation(mesh, map, &prob, v);
    let automorphism = DiskAutomorphism::from_vector([v[0], v[1]]);
    let areas_before = planar_areas(mesh, map);
    let areas_after = planar_areas(mesh, &moved);
    // a boost shortened to keep the orientation is no longer the optimum: its own residual
    let gradient_norm = match flip_limit {
        Some(_) => tangential_gradient_norm(&eval, &v, prep.radius),
        None => residual,
    };
    let report = finish_report(
        objective,
        "disk",
        &prep,
        (&areas_before, &areas_after),
        v,
        automorphism.to_mobius().to_report(),
        (starts, best_start, evaluations, converged),
        t0,
    );
    let report = MobiusReport {
        flip_limited: flip_limit,
        gradient_norm,
        ..report
    };
    Ok(DiskMobius {
        map: moved,
        automorphism,
        report,
    })
}

/// Faces of a planar map with non-positive signed area (inverted or collapsed).
fn planar_inverted(mesh: &TriMesh, map: &[Complex64]) -> usize {
    mesh.faces()
        .iter()
        .filter(|t| !(planar_signed_area(t.map(|v| map[v as usize])) > 0.0))
        .count()
}

/// Bisection steps of [`keep_orientation`] (the boost is found to `2⁻⁴⁰` of its length).
const FLIP_BISECTION_STEPS: usize = 40;

/// The optimal boost `v`, shortened if its map inverts faces the input map did not: a
/// Möbius map is a bijection of the disk, but where a map crowds triangles near f64
/// resolution (maze.obj's corridors, boundary gaps at the 1e-13 floor) moving the points
/// re-rounds them and a long boost can invert some (maze: 2,393 faces at the optimum of
/// length 2.5). The boost is then scaled by the largest `t ∈ [0, 1]` (bisection) whose map
/// inverts no more faces than the input. Returns the boost, its map and `Some(t)` when it
/// was shortened.
fn keep_orientation(
    mesh: &TriMesh,
    map: &[Complex64],
    prob: &DiskProblemM<'_>,
    v: Vec<f64>,
) -> (Vec<f64>, Vec<Complex64>, Option<f64>) {
    let moved = prob.moved(&v);
    let allowed = planar_inverted(mesh, map);
    if planar_inverted(mesh, &moved) <= allowed {
        return (v, moved, None);
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..FLIP_BISECTION_STEPS {
        let t = 0.5 * (lo + hi);
        let vt: Vec<f64> = v.iter().map(|x| x * t).collect();
        if planar_inverted(mesh, &prob.moved(&vt)) <= allowed {
            lo = t;
        } else {
            hi = t;
        }
    }
    let vt: Vec<f64> = v.iter().map(|x| x * lo).collect();
    let moved = prob.moved(&vt);
    (vt, moved, Some(lo))
}

#[allow(clippy::too_many_arguments)]
fn finish_report(
    objective: &MobiusObjective,
    domain: &str,
    prep: &Prepared,
    areas: (&[f64], &[f64]),
    boost: Vec<f64>,
    mobius: MobiusCoefficients,
    run: (Vec<StartRecord>, usize, usize, bool),
    t0: Instant,
) -> MobiusReport {
    let (before, after) = areas;
    let len = boost.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (share_b, share_a, surf) = match &prep.mask {
        Some(m) => (
            Some(region_share_from_areas(before, m)),
            Some(region_share_from_areas(after, m)),
            Some(
                prep.shares
                    .iter()
                    .zip(m)
                    .filter(|(_, &k)| k)
                    .map(|(s, _)| s)
                    .sum(),
            ),
        ),
        None => (None, None, None),
    };
    let (starts, best_start, evaluations, converged) = run;
    MobiusReport {
        objective: objective.name().to_string(),
        domain: domain.to_string(),
        uniformity_before: uniformity_from_areas(before, &prep.shares),
        uniformity_after: uniformity_from_areas(after, &prep.shares),
        region_share_before: share_b,
        region_share_after: share_a,
        region_surface_share: surf,
        cap_active: len >= prep.radius * (1.0 - 1e-9),
        boost_length: len,
        max_area_scale: (2.0 * len).exp(),
        boost,
        mobius,
        starts,
        best_start,
        evaluations,
        converged,
        gradient_norm: f64::NAN,
        time_ms: t0.elapsed().as_secs_f64() * 1e3,
        flip_limited: None,
    }
}
