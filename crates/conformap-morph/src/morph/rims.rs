//! S1's crease loops carried onto every key surface's (see [`crate::creases`]): the loops
//! of every surface and S1's harmonic extension, set up once; per key surface the
//! matched loops, the rim targets, the extension of their moves to the rest of S1's disk
//! and the fold check.

use conformap_disk::{polygon_area_of, DiskProblem};
use conformap_mesh::TriMesh;
use num_complex::Complex64;
use rayon::prelude::*;

use super::report::CreaseSummary;
use super::{MorphOptions, Surface};
use crate::creases::untangle::{folded, untangle, Rings};
use crate::creases::{
    anchor_points, crease_loops, edge_faces, match_loops, rim_targets, Anchoring, ArcLength,
    LoopOn, RimCut, RimExtension, RimTarget, RIM_HALVING_RADIUS, RIM_MOVE_HALVINGS,
};
use crate::register::warp_landmarks;
use crate::{MorphError, WarpOptions, WarpReport};

/// The crease loops of every surface and S1's extension operator.
pub(super) struct Rims<'a> {
    /// `loops[k]`: the closed crease loops of surface `k`.
    loops: Vec<Vec<Vec<u32>>>,
    /// S1's extension (held: its boundary, its loops, its landmarks); `None` when S1 has
    /// no loop.
    extension: Option<RimExtension>,
    /// `free[v]`: S1's vertex `v` is not held by the extension (the untangling may move it).
    free: Vec<bool>,
    /// S1's vertex rings (the untangling's kernels).
    rings: Rings,
    s1: &'a TriMesh,
    s1_disk: &'a [Complex64],
    /// `surface_landmarks[k]`: the landmark vertices of surface `k` (the loops' anchors).
    surface_landmarks: Vec<&'a [u32]>,
    /// Orientation of S1's disk (the sign of its boundary polygon's area).
    sigma: f64,
}

impl<'a> Rims<'a> {
    /// S1's loop `i` and key surface `k`'s loop `j` (mesh `sk`, registered disk `hk`).
    fn loop_pair<'b>(
        &'b self,
        k: usize,
        sk: &'b TriMesh,
        hk: &'b [Complex64],
        i: usize,
        j: usize,
    ) -> (LoopOn<'b>, LoopOn<'b>) {
        (
            LoopOn {
                vertices: &self.loops[0][i],
                disk: self.s1_disk,
                landmarks: self.surface_landmarks[0],
                positions: self.s1.positions(),
            },
            LoopOn {
                vertices: &self.loops[k][j],
                disk: hk,
                landmarks: self.surface_landmarks[k],
                positions: sk.positions(),
            },
        )
    }

    /// Finds the loops of every surface and factors S1's extension.
    pub fn new(
        surfaces: &'a [Surface],
        problem: &DiskProblem<'_>,
        s1_disk: &'a [Complex64],
        options: &MorphOptions,
    ) -> Result<Self, MorphError> {
        let loops: Vec<Vec<Vec<u32>>> = surfaces
            .par_iter()
            .map(|s| crease_loops(s.mesh.positions(), s.mesh.faces(), options.crease_angle_deg))
            .collect();
        let s1 = &surfaces[0].mesh;
        let mut held = s1.boundary_flags().to_vec();
        for &v in loops[0].iter().flatten() {
            held[v as usize] = true;
        }
        for &v in surfaces[0].landmarks.vertices() {
            held[v as usize] = true;
        }
        let extension = if loops[0].is_empty() {
            None
        } else {
            let ext = RimExtension::new(problem.laplacian(), &held)
                .map_err(|source| MorphError::Operator { surface: 0, source })?;
            Some(ext)
        };
        let area = s1
            .boundary_loops()
            .first()
            .map_or(1.0, |lp| polygon_area_of(lp, s1_disk));
        Ok(Self {
            loops,
            extension,
            free: held.iter().map(|&h| !h).collect(),
            rings: Rings::new(s1.faces(), s1.num_vertices()),
            surface_landmarks: surfaces.iter().map(|s| s.landmarks.vertices()).collect(),
            s1,
            s1_disk,
            sigma: if area >= 0.0 { 1.0 } else { -1.0 },
        })
    }
}

/// The anchors of S1's loops and of key surface `k`'s (`sk`, registered disk `hk`),
/// loops matched as [`carry_rims`] matches them: pairs (S1's anchor in S1's disk, the
/// key loop's vertex at its anchor).
fn anchor_pairs(
    r: &Rims<'_>,
    k: usize,
    sk: &TriMesh,
    hk: &[Complex64],
    cut: RimCut,
) -> Vec<(Complex64, u32)> {
    match_loops(&r.loops[0], r.s1_disk, &r.loops[k], hk)
        .into_iter()
        .flat_map(|(i, j)| {
            let (from, onto) = r.loop_pair(k, sk, hk, i, j);
            anchor_points(&from, &onto, cut)
        })
        .collect()
}

/// S1's disk with its loops moved onto key surface `k`'s.
pub(super) struct Carried {
    /// Where every S1 vertex is looked up in the key surface's registered disk.
    pub query: Vec<Complex64>,
    /// The loop vertices placed exactly on the key surface's loops (those whose move was
    /// not cut).
    pub targets: Vec<RimTarget>,
    /// What was done.
    pub summary: CreaseSummary,
}

/// The key surface `k` as the carrying sees it: its mesh, its landmarks, its registered
/// disk (which the corner warp may change), the warp's options and where the loops are
/// cut.
pub(super) struct KeyDisk<'k> {
    /// The key surface's mesh.
    pub mesh: &'k TriMesh,
    /// Its landmark vertices.
    pub landmarks: &'k [u32],
    /// Its registered disk (in S1's disk).
    pub map: &'k mut [Complex64],
    /// The options of the corner warp (the registration's landmark warp with the support
    /// [`super::MorphOptions::corner_warp_support`]).
    pub warp: WarpOptions,
    /// Where the matched loops are cut ([`RimCut`]).
    pub cut: RimCut,
}

/// What [`rim_moves`] found: the moves of S1's matched loop vertices, their targets, and
/// how many loops were matched, anchored at landmarks (and at how many), or by a ray.
struct RimMoves {
    moves: Vec<Complex64>,
    targets: Vec<RimTarget>,
    matched: usize,
    landmark_anchored: usize,
    landmark_anchors: usize,
    ray_anchored: usize,
    corner_anchored: usize,
}

/// The moves of S1's matched loop vertices onto key surface `k`'s loops (registered disk
/// `hk`), with their targets.
fn rim_moves(
    r: &Rims<'_>,
    k: usize,
    sk: &TriMesh,
    hk: &[Complex64],
    arc: ArcLength,
    cut: RimCut,
) -> RimMoves {
    let pairs = match_loops(&r.loops[0], r.s1_disk, &r.loops[k], hk);
    let edge_face = edge_faces(sk.faces());
    let mut out = RimMoves {
        moves: vec![Complex64::new(0.0, 0.0); r.s1_disk.len()],
        targets: Vec::new(),
        matched: pairs.len(),
        landmark_anchored: 0,
        landmark_anchors: 0,
        ray_anchored: 0,
        corner_anchored: 0,
    };
    for &(i, j) in &pairs {
        let (from, onto) = r.loop_pair(k, sk, hk, i, j);
        let (targets, how) = rim_targets(&from, &onto, sk.faces(), &edge_face, arc, cut);
        match how {
            Anchoring::Landmarks(n) => {
                out.landmark_anchored += 1;
                out.landmark_anchors += n;
            }
            Anchoring::Ray => out.ray_anchored += 1,
            Anchoring::Corners => out.corner_anchored += 1,
        }
        for t in targets {
            out.moves[t.vertex as usize] = t.disk - r.s1_disk[t.vertex as usize];
            out.targets.push(t);
        }
    }
    out
}

/// Moves S1's loops onto those of key surface `k`: matched loops, targets, the harmonic
/// extension of the moves to S1's free vertices, and the local untangling of the free
/// vertices of the faces it folds (into the kernel of their ring). Where faces still
/// fold:
///
/// 1. the corner warp: the key surface's loop corners within [`RIM_HALVING_RADIUS`] of
///    them (S1's corner in S1's disk) become extra points of a landmark warp of its
///    registered disk (`key.map`, fold-checked steps as in the registration), which
///    brings them onto S1's corners, the key's landmarks held where they are (corners
///    that are landmarks or on the boundary are left out); the loops are then carried
///    again from the warped disk;
/// 2. then, where faces still fold, the moves of the loop vertices near them are halved,
///    up to [`RIM_MOVE_HALVINGS`] rounds (a loop vertex whose move was cut is located
///    where its partial move puts it instead of exactly on the key loop).
///
/// # Errors
/// [`MorphError::Operator`] if the corner warp's interpolation matrix is singular (two
/// warp points at one place).
pub(super) fn carry_rims(
    r: &Rims<'_>,
    k: usize,
    mut key: KeyDisk<'_>,
) -> Result<Carried, MorphError> {
    let mut summary = CreaseSummary {
        loops_s1: r.loops[0].len(),
        loops: r.loops[k].len(),
        smallest_share: 1.0,
        ..CreaseSummary::default()
    };
    let Some(ext) = &r.extension else {
        return Ok(Carried {
            query: r.s1_disk.to_vec(),
            targets: Vec::new(),
            summary,
        });
    };
    let sk = key.mesh;
    // S1's disk with the loop moves `scaled` applied and untangled: the disk, the faces
    // the extension alone folds, the untangling
    let place = |scaled: &[Complex64]| {
        let mut query = moved(r.s1_disk, &ext.extend(scaled));
        let at_extension = folded(r.s1.faces(), &query, r.sigma).len();
        let u = untangle(&mut query, r.s1.faces(), &r.rings, &r.free, r.sigma);
        (query, at_extension, u)
    };
    let mut arc = ArcLength::Surface;
    let cut = key.cut;
    let mut found = rim_moves(r, k, sk, key.map, arc, cut);
    let (mut query, mut at_extension, mut untangled) = place(&found.moves);
    let mut folding = folded_centroids(r.s1.faces(), &query, r.sigma);
    if !folding.is_empty() {
        // where shares of 3D arc length fold S1's disk, shares of disk arc length may
        // fold less (wry's raised mouth corner: 24 faces after the untangling, against
        // 10): the one that folds fewer faces
        let other = rim_moves(r, k, sk, key.map, ArcLength::Disk, cut);
        let (q, at, u) = place(&other.moves);
        let f = folded_centroids(r.s1.faces(), &q, r.sigma);
        if f.len() < folding.len() {
            (arc, found, query, at_extension, untangled, folding) =
                (ArcLength::Disk, other, q, at, u, f);
        }
    }
    summary.folded_at_full_move = at_extension;
    summary.folded_after_untangling = folding.len();
    summary.arc_length_in_disk = arc == ArcLength::Disk;
    if !folding.is_empty() {
        if let Some((corners, report)) = warp_corners(r, k, &mut key, &folding)? {
            summary.warped_corners = corners;
            summary.corner_warp = Some(report);
            found = rim_moves(r, k, sk, key.map, arc, cut);
            (query, _, untangled) = place(&found.moves);
            folding = folded_centroids(r.s1.faces(), &query, r.sigma);
        }
    }
    summary.matched = found.matched;
    summary.landmark_anchored = found.landmark_anchored;
    summary.landmark_anchors = found.landmark_anchors;
    summary.ray_anchored = found.ray_anchored;
    summary.corner_anchored = found.corner_anchored;
    let RimMoves {
        moves, mut targets, ..
    } = found;
    summary.largest_move = moves.iter().map(|d| d.norm()).fold(0.0, f64::max);
    // the share of its move every loop vertex gets: 1, halved (again) near the faces of
    // S1's moved disk that still fold
    let mut halvings = vec![0u32; r.s1_disk.len()];
    let mut rounds = 0;
    while !folding.is_empty() && rounds < RIM_MOVE_HALVINGS {
        rounds += 1;
        for t in &targets {
            let z = r.s1_disk[t.vertex as usize];
            if folding.iter().any(|&c| (c - z).norm() < RIM_HALVING_RADIUS) {
                halvings[t.vertex as usize] += 1;
            }
        }
        let scaled: Vec<Complex64> = moves
            .iter()
            .zip(&halvings)
            .map(|(&m, &h)| m * 0.5f64.powi(h as i32))
            .collect();
        (query, _, untangled) = place(&scaled);
        folding = folded_centroids(r.s1.faces(), &query, r.sigma);
    }
    summary.untangled_vertices = untangled.moved;
    summary.untangling_rounds = untangled.rounds;
    if !folding.is_empty() {
        // still folding: no loop is moved
        query = r.s1_disk.to_vec();
        for t in &targets {
            halvings[t.vertex as usize] = u32::MAX;
        }
    }
    summary.smallest_share = targets
        .iter()
        .map(|t| 0.5f64.powi(halvings[t.vertex as usize].min(1100) as i32))
        .fold(1.0, f64::min);
    targets.retain(|t| halvings[t.vertex as usize] == 0);
    summary.rim_vertices = targets.len();
    Ok(Carried {
        query,
        targets,
        summary,
    })
}

/// The corner warp of [`carry_rims`]: the corners of key surface `k`'s loops whose S1
/// corner lies within [`RIM_HALVING_RADIUS`] of a centroid in `folding` (and that are
/// neither landmarks nor on the boundary) are warped onto S1's corners in `key.map`, the
/// key's landmarks held. Returns the number of corners warped and the warp's report, or
/// `None` when no corner qualifies (the map is left as it is).
fn warp_corners(
    r: &Rims<'_>,
    k: usize,
    key: &mut KeyDisk<'_>,
    folding: &[Complex64],
) -> Result<Option<(usize, WarpReport)>, MorphError> {
    let sk = key.mesh;
    let near = |z: Complex64| folding.iter().any(|&c| (c - z).norm() < RIM_HALVING_RADIUS);
    let boundary = sk.boundary_flags();
    let corners: Vec<(Complex64, u32)> = anchor_pairs(r, k, sk, key.map, key.cut)
        .into_iter()
        .filter(|&(a, b)| {
            near(a)
                && !key.landmarks.contains(&b)
                && !boundary[b as usize]
                && (key.map[b as usize] - a).norm() > 0.0
        })
        .collect();
    if corners.is_empty() {
        return Ok(None);
    }
    // the key's landmarks stay where the registration put them
    let mut points: Vec<u32> = key.landmarks.to_vec();
    let mut goals: Vec<Complex64> = points.iter().map(|&v| key.map[v as usize]).collect();
    for &(a, b) in &corners {
        points.push(b);
        goals.push(a);
    }
    let area = sk
        .boundary_loops()
        .first()
        .map_or(1.0, |lp| polygon_area_of(lp, key.map));
    let sigma = if area >= 0.0 { 1.0 } else { -1.0 };
    let active = vec![true; points.len()];
    let report = warp_landmarks(
        key.map,
        sk.faces(),
        &points,
        &goals,
        &active,
        sigma,
        &key.warp,
    )
    .map_err(|source| MorphError::Operator { surface: k, source })?;
    Ok(Some((corners.len(), report)))
}

/// `disk + delta`.
fn moved(disk: &[Complex64], delta: &[Complex64]) -> Vec<Complex64> {
    disk.iter().zip(delta).map(|(&z, &d)| z + d).collect()
}

/// The centroids of the faces whose image under `map` is folded or degenerate (against
/// the orientation `sigma`), as [`crate::folded_faces`] counts them.
fn folded_centroids(faces: &[[u32; 3]], map: &[Complex64], sigma: f64) -> Vec<Complex64> {
    folded(faces, map, sigma)
        .into_iter()
        .map(|f| faces[f].iter().map(|&v| map[v as usize]).sum::<Complex64>() / 3.0)
        .collect()
}
