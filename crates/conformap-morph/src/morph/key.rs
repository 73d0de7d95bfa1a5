//! One key surface of the morph after the disk maps: its registration onto S1's disk,
//! S1's crease loops carried onto its loops, the location of S1's vertices and faces in
//! its registered disk, their 3D positions, and the quality counts of its key frame.

use std::time::Instant;

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use super::report::{CreaseSummary, KeyReport, LocateSummary};
use super::rims::{carry_rims, Carried, KeyDisk, Rims};
use super::{ms, MorphOptions, Prepared, Surface};
use crate::creases::RimCut;
use crate::quality::{flipped_against_key, flipped_at_vertices, largest_patch};
use crate::refine::{refine_key_frame, KeyFrame, NearestTriangle, RefineSummary};
use crate::{
    register_disk, LandmarkMode, Location, MorphError, Registration, TriangleGrid, WarpOptions,
};

/// What the morph computed for one key surface `k ≥ 1`.
pub(super) struct KeyResult {
    pub registration: Registration,
    /// Where S1's vertices lie on surface `k`.
    pub locations: Vec<Location>,
    /// Where S1's face centroids lie on surface `k`.
    pub landing: Vec<Location>,
    /// The 3D positions of S1's vertices on surface `k`.
    pub key: Vec<[f64; 3]>,
    /// The key frame's flipped faces ([`flipped_against_key`]).
    pub flips: Vec<usize>,
    pub crease: Option<CreaseSummary>,
    /// The key frame's refinement ([`MorphOptions::refine_key_frames`]).
    pub refine: Option<RefineSummary>,
    pub register_ms: f64,
    pub locate_ms: f64,
}

/// What S1 offers every key surface: its disk, the registration targets (its
/// normalized landmarks) and its crease loops.
pub(super) struct S1Data<'a> {
    pub surfaces: &'a [Surface],
    pub prepared: &'a [Prepared<'a>],
    pub targets: Vec<Complex64>,
    pub rims: Option<Rims<'a>>,
}

/// Key surface `k`: registered, S1's loops carried, S1 located and carried to 3D, the key
/// frame refined on the key surface ([`MorphOptions::refine_key_frames`]).
pub(super) fn morph_key(
    s1: &S1Data<'_>,
    k: usize,
    options: &MorphOptions,
) -> Result<KeyResult, MorphError> {
    let (surfaces, prepared) = (s1.surfaces, s1.prepared);
    let t0 = Instant::now();
    let mut registration = register_disk(
        &prepared[k].problem,
        &prepared[k].normalized,
        surfaces[k].landmarks.vertices(),
        &s1.targets,
        &options.register,
        k,
    )?;
    let register_ms = ms(t0);
    let t1 = Instant::now();
    let registered = registration.map.clone();
    let mut placed = place_s1(s1, k, &mut registration.map, options, RimCut::Landmarks)?;
    // the landmark cut leaves flipped faces and its carry folded S1's disk (the rims'
    // anchors are off the key's): the loops cut at their corners, from the registered
    // disk as it was before the carrying (whose corner warp may change it). Where the
    // carry folds nothing the flips are not the rims' (pout's two lie on the lip's curl,
    // and either cut leaves them), and a second carry would only cost time. The cut is
    // chosen by the flips before the key frame's refinement, which runs once, on the
    // cut taken.
    let tried = placed
        .carried
        .as_ref()
        .is_some_and(|c| c.summary.matched > 0 && c.summary.folded_at_full_move > 0);
    if tried && !placed.flips.is_empty() {
        let mut map = registered;
        // a corner warp that cannot be solved (two warp points at one place) only
        // means the corner cut is not taken
        let other = place_s1(s1, k, &mut map, options, RimCut::Corners).ok();
        let at_landmarks = placed.flips.len();
        let at_corners = other.as_ref().map(|o| o.flips.len());
        if let Some(o) = other.filter(|o| o.flips.len() < at_landmarks) {
            placed = o;
            registration.map = map;
        }
        if let Some(c) = placed.carried.as_mut() {
            c.summary.flipped_faces_cut_at_landmarks = Some(at_landmarks);
            c.summary.flipped_faces_cut_at_corners = at_corners;
        }
    }
    if options.refine_key_frames {
        refine_placed(s1, k, &mut placed);
    }
    let Placed {
        carried,
        locations,
        landing,
        key,
        flips,
        refine,
    } = placed;
    Ok(KeyResult {
        registration,
        locations,
        landing,
        key,
        flips,
        crease: carried.map(|c| c.summary),
        refine,
        register_ms,
        locate_ms: ms(t1),
    })
}

/// S1 placed on key surface `k`: its loops carried, its vertices and face centroids
/// located, its key frame and the frame's flipped faces.
struct Placed {
    carried: Option<Carried>,
    locations: Vec<Location>,
    landing: Vec<Location>,
    key: Vec<[f64; 3]>,
    flips: Vec<usize>,
    refine: Option<RefineSummary>,
}

/// S1's loops carried onto key surface `k`'s (cut at `cut`; the corner warp may change
/// the registered disk `map`), S1's vertices and face centroids located in `map`, the
/// key frame and its flipped faces ([`flipped_against_key`]).
fn place_s1(
    s1: &S1Data<'_>,
    k: usize,
    map: &mut [Complex64],
    options: &MorphOptions,
    cut: RimCut,
) -> Result<Placed, MorphError> {
    let surfaces = s1.surfaces;
    let carried = carry_creases(s1, k, map, options, cut)?;
    let s1_disk = &s1.prepared[0].normalized;
    let grid = TriangleGrid::new(map, surfaces[k].mesh.faces());
    // S1's disk, its crease loops moved onto this surface's (rims: exact edge locations
    // of the loop vertices; the corner warp may have changed the registered disk)
    let query = carried.as_ref().map_or(s1_disk, |c| &c.query);
    let mut locations: Vec<Location> = query.iter().map(|&z| grid.locate(z)).collect();
    if let Some(c) = &carried {
        for t in &c.targets {
            locations[t.vertex as usize] = t.location;
        }
    }
    if options.register.mode == LandmarkMode::Hard {
        pin_landmarks(&mut locations, &surfaces[0], &surfaces[k]);
    }
    let landing: Vec<Location> = surfaces[0]
        .mesh
        .faces()
        .iter()
        .map(|f| grid.locate(f.iter().map(|&v| query[v as usize]).sum::<Complex64>() / 3.0))
        .collect();
    let sk = &surfaces[k].mesh;
    let key = carry(sk, &locations);
    let flips = flipped_against_key(
        &key,
        surfaces[0].mesh.faces(),
        sk.positions(),
        sk.faces(),
        &landing,
    );
    Ok(Placed {
        carried,
        locations,
        landing,
        key,
        flips,
        refine: None,
    })
}

/// The key frame of `placed` refined on key surface `k` (`crate::refine`), its flipped
/// faces counted again. Held: S1's boundary, its landmarks, the vertices carried onto the
/// key surface's rims.
fn refine_placed(s1: &S1Data<'_>, k: usize, placed: &mut Placed) {
    let t = Instant::now();
    let (s1_mesh, sk) = (&s1.surfaces[0].mesh, &s1.surfaces[k].mesh);
    let mut held = s1_mesh.boundary_flags().to_vec();
    for &v in s1.surfaces[0].landmarks.vertices() {
        held[v as usize] = true;
    }
    for target in placed.carried.iter().flat_map(|c| &c.targets) {
        held[target.vertex as usize] = true;
    }
    let mut summary = refine_key_frame(
        &NearestTriangle::new(sk),
        KeyFrame {
            faces: s1_mesh.faces(),
            rest: s1_mesh.positions(),
            key: sk,
            locations: &mut placed.locations,
            frame: &mut placed.key,
            landing: &placed.landing,
            held: &held,
        },
    );
    if summary.moves > 0 {
        placed.flips = flipped_against_key(
            &placed.key,
            s1_mesh.faces(),
            sk.positions(),
            sk.faces(),
            &placed.landing,
        );
    }
    summary.wall_ms = ms(t);
    placed.refine = Some(summary);
}

/// S1's crease loops carried onto key surface `k`'s (`None` without crease matching);
/// the corner warp may change the registered disk `map`.
fn carry_creases(
    s1: &S1Data<'_>,
    k: usize,
    map: &mut [Complex64],
    options: &MorphOptions,
    cut: RimCut,
) -> Result<Option<Carried>, MorphError> {
    let Some(r) = &s1.rims else {
        return Ok(None);
    };
    let surface = &s1.surfaces[k];
    let key = KeyDisk {
        mesh: &surface.mesh,
        landmarks: surface.landmarks.vertices(),
        map: &mut *map,
        warp: WarpOptions {
            support: options.corner_warp_support,
            ..options.register.warp
        },
        cut,
    };
    let mut c = carry_rims(r, k, key)?;
    if c.summary.corner_warp.is_some() {
        c.summary.dirichlet_energy_after_corner_warp =
            Some(s1.prepared[k].problem.dirichlet_energy(map));
    }
    Ok(Some(c))
}

/// Completes `r`, the report of key surface `k`, with what [`morph_key`] found: the
/// snapped locations, the flip counts of the key frame, the registration, the creases
/// and the timings.
pub(super) fn finish_report(
    r: &mut KeyReport,
    surfaces: &[Surface],
    k: usize,
    result: &KeyResult,
    rims_setup_ms: f64,
) {
    let snapped: Vec<f64> = result
        .locations
        .iter()
        .map(|l| l.outside)
        .filter(|&d| d > 0.0)
        .collect();
    r.locate = Some(LocateSummary {
        snapped: snapped.len(),
        max_outside: snapped.iter().copied().fold(0.0, f64::max),
    });
    let (s1, sk) = (&surfaces[0].mesh, &surfaces[k].mesh);
    let (key, faces) = (&result.key, s1.faces());
    r.key_frame_flipped_faces = result.flips.len();
    r.key_frame_largest_flip_patch = largest_patch(faces, &result.flips);
    let at_vertices =
        flipped_at_vertices(key, faces, sk.positions(), sk.faces(), &result.locations);
    r.key_frame_flipped_faces_at_vertices = at_vertices.len();
    r.key_frame_largest_flip_patch_at_vertices = largest_patch(faces, &at_vertices);
    r.creases = result.crease.clone();
    r.refine = result.refine.clone();
    r.registration = Some(result.registration.report.clone());
    r.timings_ms.register = result.register_ms;
    r.timings_ms.locate = result.locate_ms;
    r.timings_ms.creases_setup = rims_setup_ms;
}

/// Hard landmarks: S1's landmark vertex `j` is located exactly at surface `k`'s landmark
/// vertex `j` (the registration sends the one onto the other; where the registered disk
/// folds around a landmark, point location could pick an overlapping face instead).
fn pin_landmarks(locations: &mut [Location], s1: &Surface, sk: &Surface) {
    for (&v1, &vk) in s1.landmarks.vertices().iter().zip(sk.landmarks.vertices()) {
        let found = sk
            .mesh
            .faces()
            .iter()
            .enumerate()
            .find_map(|(f, tri)| tri.iter().position(|&v| v == vk).map(|c| (f, c)));
        if let Some((face, corner)) = found {
            let mut bary = [0.0; 3];
            bary[corner] = 1.0;
            locations[v1 as usize] = Location {
                face: face as u32,
                bary,
                outside: 0.0,
            };
        }
    }
}

/// The 3D point of `mesh` at every location.
fn carry(mesh: &TriMesh, locations: &[Location]) -> Vec<[f64; 3]> {
    let pos = mesh.positions();
    locations
        .iter()
        .map(|l| {
            let f = mesh.faces()[l.face as usize];
            let mut p = [0.0; 3];
            for i in 0..3 {
                for c in 0..3 {
                    p[c] += l.bary[i] * pos[f[i] as usize][c];
                }
            }
            p
        })
        .collect()
}
