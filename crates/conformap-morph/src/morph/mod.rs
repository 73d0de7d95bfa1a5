//! The whole morph (CEM §6): disk maps, normalization, registration onto S1's disk,
//! location of S1's vertices on every key surface, and the spline homotopy.

mod key;
mod report;
mod rims;

use std::time::Instant;

use conformap_disk::{run_disk_method, DiskMap, DiskMethod, DiskOptions, DiskProblem};
use conformap_mesh::TriMesh;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::quality::CREASE_ANGLE_DEG;
use crate::{
    normalize_disk_map, CubicHomotopy, LandmarkMode, Landmarks, Location, MorphError,
    RegisterOptions,
};
use key::{finish_report, morph_key, KeyResult, S1Data};
pub use report::{CreaseSummary, DiskSummary, KeyReport, KeyTimings, LocateSummary, MorphReport};
use rims::Rims;

/// One key surface: a disk-like mesh and its landmarks.
#[derive(Debug, Clone)]
pub struct Surface {
    /// The mesh (one boundary loop, genus 0).
    pub mesh: TriMesh,
    /// Its landmarks (the same names in the same order on every surface).
    pub landmarks: Landmarks,
}

impl Surface {
    /// A surface from its mesh and landmarks.
    pub fn new(mesh: TriMesh, landmarks: Landmarks) -> Self {
        Self { mesh, landmarks }
    }
}

/// Options of [`morph`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct MorphOptions {
    /// The registration (λ or hard landmarks, sweeps). Default:
    /// [`RegisterOptions::DEFAULT`] (λ = [`crate::DEFAULT_LAMBDA`]).
    pub register: RegisterOptions,
    /// Key times, one per surface, strictly increasing. Default: `None` (evenly spaced
    /// on `[0, 1]`).
    pub key_times: Option<Vec<f64>>,
    /// The disk map's method. Default: [`DiskMethod::CcemQn`] (the disk crate's default).
    pub disk_method: DiskMethod,
    /// The disk map's options. Default: [`DiskOptions::DEFAULT`].
    pub disk: DiskOptions,
    /// Carry S1's closed crease loops onto the matching loops of every key surface
    /// (`crate::creases`): each vertex of an S1 loop lands on the key surface's loop, and
    /// the rest of S1's disk follows harmonically. Default: `true` (a crease that lands a
    /// fraction of a face beside its counterpart folds the thin faces along it; on the
    /// shared faces these are the rims of the zipped eye and mouth fills).
    pub match_creases: bool,
    /// The turn of the normals (degrees) above which an edge is a crease for
    /// [`Self::match_creases`]. Default: [`CREASE_ANGLE_DEG`].
    pub crease_angle_deg: f64,
    /// Kernel support radius ρ (unit disk) of the corner warp, the landmark warp that
    /// brings a key surface's loop corners onto S1's where carrying the loops would fold
    /// S1's disk ([`Self::match_creases`]). Default: [`CORNER_WARP_SUPPORT`].
    pub corner_warp_support: f64,
    /// Refine every key frame on its key surface after the location (`crate::refine`):
    /// the free vertices of faces whose normal points against the key triangle nearest to
    /// them slide within the key surface where that leaves fewer such faces (checked for
    /// folds, crushed faces and bent corner angles). Default: `true` (the key frames'
    /// faces on the lips' curl of the shared faces land beside the key's fold and cut
    /// it: wry 11 such faces, pout 30, against 3 and 15 for the face model's exact
    /// correspondence; refined 3 and 6).
    pub refine_key_frames: bool,
}

/// The default of [`MorphOptions::corner_warp_support`]: `0.1`, about twice the distance
/// (in the disk) from the wry face's mouth-slit corner to the nearest landmark, which the
/// warp holds; the corner's move (0.019) is then spread over the lip next to it and not
/// over the whole mouth. Measured on the shared faces (wry): 0.05 leaves 2 flipped
/// faces in the key frame; 0.1–0.5 none, the median per-face change of the largest
/// corner angle against S1 5.43° at 0.1 (without the warp 5.66°), 6.03° at 0.25, 7.16° at
/// 0.5 (the registration's [`crate::WARP_SUPPORT`]), which drags the whole mouth along.
pub const CORNER_WARP_SUPPORT: f64 = 0.1;

impl MorphOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        register: RegisterOptions::DEFAULT,
        key_times: None,
        disk_method: DiskMethod::CcemQn,
        disk: DiskOptions::DEFAULT,
        match_creases: true,
        crease_angle_deg: CREASE_ANGLE_DEG,
        corner_warp_support: CORNER_WARP_SUPPORT,
        refine_key_frames: true,
    };

    /// Soft landmarks with weight `lambda` (Eq. 34).
    #[must_use]
    pub fn with_lambda(mut self, lambda: f64) -> Self {
        self.register.mode = LandmarkMode::Soft(lambda);
        self
    }

    /// Hard landmarks: exactly on their targets.
    #[must_use]
    pub fn with_hard_landmarks(mut self) -> Self {
        self.register.mode = LandmarkMode::Hard;
        self
    }

    /// Sets [`Self::match_creases`].
    #[must_use]
    pub fn with_crease_matching(mut self, on: bool) -> Self {
        self.match_creases = on;
        self
    }

    /// Sets [`Self::refine_key_frames`].
    #[must_use]
    pub fn with_key_frame_refinement(mut self, on: bool) -> Self {
        self.refine_key_frames = on;
        self
    }

    /// Sets [`Self::corner_warp_support`].
    #[must_use]
    pub fn with_corner_warp_support(mut self, support: f64) -> Self {
        self.corner_warp_support = support;
        self
    }

    /// Key times (one per surface).
    #[must_use]
    pub fn with_key_times(mut self, times: Vec<f64>) -> Self {
        self.key_times = Some(times);
        self
    }
}

impl Default for MorphOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A computed morph: S1's connectivity, its vertices' positions on every key surface, the
/// spline through them, and the report.
#[derive(Debug, Clone)]
pub struct Morph {
    faces: Vec<[u32; 3]>,
    keys: Vec<Vec<[f64; 3]>>,
    locations: Vec<Vec<Location>>,
    landings: Vec<Vec<Location>>,
    homotopy: CubicHomotopy,
    /// What was done, per key surface.
    pub report: MorphReport,
}

impl Morph {
    /// S1's faces (the connectivity of every frame).
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// `keys()[k][v]`: the position of S1's vertex `v` on key surface `k` (`keys()[0]` is
    /// S1 itself).
    pub fn keys(&self) -> &[Vec<[f64; 3]>] {
        &self.keys
    }

    /// `locations()[k][v]`: where S1's vertex `v` lies on surface `k` (a face of surface
    /// `k` and barycentric coordinates; empty for `k = 0`).
    pub fn locations(&self) -> &[Vec<Location>] {
        &self.locations
    }

    /// `landings()[k][f]`: where S1's face `f` lies on surface `k` (the location of the
    /// image of its centroid in S1's disk; empty for `k = 0`): the key face whose normal
    /// [`crate::quality::flipped_against_key`] compares it with.
    pub fn landings(&self) -> &[Vec<Location>] {
        &self.landings
    }

    /// The spline basis (key times, weights).
    pub fn homotopy(&self) -> &CubicHomotopy {
        &self.homotopy
    }

    /// The positions of S1's vertices at time `t` (between the first and last key
    /// times): `Σ_k φ_k(t) P_k`, exactly `P_k` at key time `k`.
    pub fn frame(&self, t: f64) -> Vec<[f64; 3]> {
        let w = self.homotopy.weights(t);
        let n = self.keys[0].len();
        (0..n)
            .map(|v| {
                let mut p = [0.0; 3];
                for (wk, key) in w.iter().zip(&self.keys) {
                    for c in 0..3 {
                        p[c] += wk * key[v][c];
                    }
                }
                p
            })
            .collect()
    }

    /// The frame index of every key surface for `n` frames: `round(k(n−1)/(K−1))` for
    /// evenly spaced keys, in general `round((t_k − t_0)/(t_last − t_0) · (n−1))`.
    ///
    /// # Errors
    /// [`MorphError::InvalidOption`] if two keys fall on the same frame (`n` too small).
    pub fn key_frames(&self, n: usize) -> Result<Vec<usize>, MorphError> {
        let t = self.homotopy.times();
        let (t0, t1) = (t[0], t[t.len() - 1]);
        let idx: Vec<usize> = t
            .iter()
            .map(|&tk| ((tk - t0) / (t1 - t0) * (n.max(1) - 1) as f64).round() as usize)
            .collect();
        if n < 2 || idx.windows(2).any(|w| w[1] <= w[0]) {
            return Err(MorphError::InvalidOption {
                name: "frames",
                reason: format!(
                    "{n} frames cannot hold the {} key surfaces on distinct frames",
                    t.len()
                ),
            });
        }
        Ok(idx)
    }

    /// The time of each of `n` frames: key frame `k` ([`Self::key_frames`]) at key time
    /// `t_k` exactly, the frames between two keys evenly spaced in time.
    ///
    /// # Errors
    /// As [`Self::key_frames`].
    pub fn frame_times(&self, n: usize) -> Result<Vec<f64>, MorphError> {
        let idx = self.key_frames(n)?;
        let t = self.homotopy.times();
        let mut out = vec![0.0; n];
        for k in 0..idx.len() - 1 {
            let (a, b) = (idx[k], idx[k + 1]);
            for i in a..=b {
                out[i] = if i == a {
                    t[k]
                } else if i == b {
                    t[k + 1]
                } else {
                    t[k] + (i - a) as f64 / (b - a) as f64 * (t[k + 1] - t[k])
                };
            }
        }
        Ok(out)
    }

    /// The weights of the glTF morph targets `P_k − P_0` (`k ≥ 1`) at time `t`:
    /// `φ_1(t) … φ_{K−1}(t)` (the frame is `P_0 + Σ_k φ_k (P_k − P_0)`, as `Σ φ_k = 1`).
    pub fn target_weights(&self, t: f64) -> Vec<f64> {
        self.homotopy.weights(t)[1..].to_vec()
    }
}

/// Everything computed per surface before the registration.
struct Prepared<'m> {
    problem: DiskProblem<'m>,
    disk: DiskMap,
    normalized: Vec<Complex64>,
    disk_ms: f64,
    normalize_ms: f64,
}

/// Morphs `surfaces[0]` (S1) through the others: their disk maps (the default method),
/// the normalization `m₁` (first landmark to the centre, second onto the positive real
/// axis), the registration of every other disk onto S1's (Eq. 34, boundary sliding on
/// the circle, fold-checked), S1's closed crease loops carried onto every key surface's
/// ([`MorphOptions::match_creases`]; where that would fold S1's disk, the key surface's
/// loop corners are first warped onto S1's, [`MorphOptions::corner_warp_support`]), the
/// location of S1's vertices in every registered disk, every key frame refined on its key
/// surface ([`MorphOptions::refine_key_frames`]), and the natural cubic spline through
/// the K positions of every vertex.
///
/// # Errors
/// [`MorphError::TooFewSurfaces`]; the landmark checks ([`Landmarks::check_against`],
/// [`Landmarks::check_same_names`]); [`MorphError::Disk`] when a surface is not a disk or
/// its map fails; [`MorphError::LandmarkOnBoundary`] (a boundary vertex) or
/// [`MorphError::LandmarkNearCircle`] (an interior one the disk map crowds against the
/// circle) for the first two landmarks; the registration's errors
/// ([`crate::register_disk`]); [`MorphError::InvalidOption`] for bad key times, crease
/// angle or corner warp support; [`MorphError::Operator`] if S1's crease-loop extension cannot be
/// factored or the corner warp's interpolation matrix is singular.
pub fn morph(surfaces: &[Surface], options: &MorphOptions) -> Result<Morph, MorphError> {
    let t_all = Instant::now();
    let homotopy = check_inputs(surfaces, options)?;
    let prepared: Vec<Prepared<'_>> = surfaces
        .par_iter()
        .enumerate()
        .map(|(k, s)| prepare(k, s, options))
        .collect::<Result<_, _>>()?;
    let s1_disk = &prepared[0].normalized;
    let targets: Vec<Complex64> = surfaces[0]
        .landmarks
        .vertices()
        .iter()
        .map(|&v| s1_disk[v as usize])
        .collect();
    let t_rims = Instant::now();
    let rims = if options.match_creases {
        Some(Rims::new(surfaces, &prepared[0].problem, s1_disk, options)?)
    } else {
        None
    };
    let rims_setup_ms = ms(t_rims);
    let s1 = S1Data {
        surfaces,
        prepared: &prepared,
        targets,
        rims,
    };
    let later: Vec<KeyResult> = (1..surfaces.len())
        .into_par_iter()
        .map(|k| morph_key(&s1, k, options))
        .collect::<Result<_, MorphError>>()?;
    let mut keys = vec![surfaces[0].mesh.positions().to_vec()];
    let mut locations = vec![Vec::new()];
    let mut landings = vec![Vec::new()];
    let mut reports = vec![key_report(0, surfaces, &prepared[0], &homotopy, None)];
    for (i, result) in later.into_iter().enumerate() {
        let k = i + 1;
        let mut r = key_report(k, surfaces, &prepared[k], &homotopy, Some(&result.key));
        finish_report(&mut r, surfaces, k, &result, rims_setup_ms);
        reports.push(r);
        keys.push(result.key);
        locations.push(result.locations);
        landings.push(result.landing);
    }
    Ok(Morph {
        faces: surfaces[0].mesh.faces().to_vec(),
        keys,
        locations,
        landings,
        homotopy,
        report: MorphReport {
            landmarks: surfaces[0].landmarks.names().to_vec(),
            keys: reports,
            total_ms: ms(t_all),
        },
    })
}

/// The checks before any work (at least two surfaces, the crease angle, the corner warp
/// support, the landmarks of every surface against S1's, the key times) and the spline
/// basis of the key times.
fn check_inputs(surfaces: &[Surface], options: &MorphOptions) -> Result<CubicHomotopy, MorphError> {
    if surfaces.len() < 2 {
        return Err(MorphError::TooFewSurfaces {
            found: surfaces.len(),
        });
    }
    let angle = options.crease_angle_deg;
    if !(angle > 0.0 && angle < 180.0) {
        return Err(MorphError::InvalidOption {
            name: "crease_angle_deg",
            reason: format!("must be between 0 and 180 degrees, got {angle}"),
        });
    }
    let support = options.corner_warp_support;
    if !(support > 0.0 && support.is_finite()) {
        return Err(MorphError::InvalidOption {
            name: "corner_warp_support",
            reason: format!("must be positive and finite, got {support}"),
        });
    }
    for (k, s) in surfaces.iter().enumerate() {
        s.landmarks.check_against(k, s.mesh.num_vertices())?;
        s.landmarks.check_same_names(k, &surfaces[0].landmarks)?;
    }
    match &options.key_times {
        Some(t) if t.len() != surfaces.len() => Err(MorphError::InvalidOption {
            name: "key_times",
            reason: format!("{} key times for {} surfaces", t.len(), surfaces.len()),
        }),
        Some(t) => CubicHomotopy::new(t.clone()),
        None => CubicHomotopy::evenly_spaced(surfaces.len()),
    }
}

/// Disk map and normalization of surface `k`.
fn prepare<'m>(
    k: usize,
    s: &'m Surface,
    options: &MorphOptions,
) -> Result<Prepared<'m>, MorphError> {
    let disk_err = |source| MorphError::Disk { surface: k, source };
    let t0 = Instant::now();
    let mut problem = DiskProblem::new(&s.mesh).map_err(disk_err)?;
    let disk =
        run_disk_method(&mut problem, options.disk_method, &options.disk).map_err(disk_err)?;
    let disk_ms = ms(t0);
    let t1 = Instant::now();
    let lm = s.landmarks.vertices();
    let normalized = normalize_disk_map(&disk.map, lm[0], lm[1], k)
        .map_err(|e| near_circle(e, &s.mesh))?
        .map;
    Ok(Prepared {
        problem,
        disk,
        normalized,
        disk_ms,
        normalize_ms: ms(t1),
    })
}

/// A landmark the normalization refused as on the circle that is an interior vertex of
/// the mesh: [`MorphError::LandmarkNearCircle`] (the disk map crowds it there).
fn near_circle(e: MorphError, mesh: &TriMesh) -> MorphError {
    match e {
        MorphError::LandmarkOnBoundary {
            surface,
            index,
            vertex,
            radius,
        } if !mesh.is_boundary_vertex(vertex as usize) => MorphError::LandmarkNearCircle {
            surface,
            index,
            vertex,
            radius,
        },
        other => other,
    }
}

/// The report of surface `k` without its registration, location and flip counts.
fn key_report(
    k: usize,
    surfaces: &[Surface],
    prep: &Prepared<'_>,
    homotopy: &CubicHomotopy,
    key: Option<&[[f64; 3]]>,
) -> KeyReport {
    let mesh = &surfaces[k].mesh;
    let diagonal = mesh.bbox_diagonal();
    let errors: Vec<f64> = match key {
        None => vec![0.0; surfaces[k].landmarks.len()],
        Some(key) => surfaces[0]
            .landmarks
            .vertices()
            .iter()
            .zip(surfaces[k].landmarks.vertices())
            .map(|(&v1, &vk)| {
                let (a, b) = (key[v1 as usize], mesh.positions()[vk as usize]);
                let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() / diagonal
            })
            .collect(),
    };
    let r = &prep.disk.report;
    KeyReport {
        surface: k,
        time: homotopy.times()[k],
        vertices: mesh.num_vertices(),
        faces: mesh.num_faces(),
        boundary_vertices: mesh.boundary_loops().first().map_or(0, Vec::len),
        diagonal,
        disk: DiskSummary {
            method: r.method.clone(),
            conformal_energy: r
                .energy_history
                .get(r.best_iteration)
                .copied()
                .unwrap_or(f64::NAN),
            iterations: r.iterations,
            converged: r.converged,
            notes: r.notes.clone(),
        },
        registration: None,
        locate: None,
        landmark_error_max_rel: errors.iter().copied().fold(0.0, f64::max),
        landmark_errors_rel: errors,
        creases: None,
        refine: None,
        key_frame_flipped_faces: 0,
        key_frame_largest_flip_patch: 0,
        key_frame_flipped_faces_at_vertices: 0,
        key_frame_largest_flip_patch_at_vertices: 0,
        timings_ms: KeyTimings {
            disk_map: prep.disk_ms,
            normalize: prep.normalize_ms,
            creases_setup: 0.0,
            register: 0.0,
            locate: 0.0,
        },
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
