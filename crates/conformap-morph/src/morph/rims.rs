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
use crate::creases::{
    crease_loops, edge_faces, match_loops, rim_targets, LoopOn, RimExtension, RimTarget,
    RIM_HALVING_RADIUS, RIM_MOVE_HALVINGS,
};
use crate::MorphError;

/// The crease loops of every surface and S1's extension operator.
pub(super) struct Rims<'a> {
    /// `loops[k]`: the closed crease loops of surface `k`.
    loops: Vec<Vec<Vec<u32>>>,
    /// S1's extension (held: its boundary, its loops, its landmarks); `None` when S1 has
    /// no loop.
    extension: Option<RimExtension>,
    s1: &'a TriMesh,
    s1_disk: &'a [Complex64],
    /// Orientation of S1's disk (the sign of its boundary polygon's area).
    sigma: f64,
}

impl<'a> Rims<'a> {
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
        let extension = if loops[0].is_empty() {
            None
        } else {
            let mut held = s1.boundary_flags().to_vec();
            for &v in loops[0].iter().flatten() {
                held[v as usize] = true;
            }
            for &v in surfaces[0].landmarks.vertices() {
                held[v as usize] = true;
            }
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
            s1,
            s1_disk,
            sigma: if area >= 0.0 { 1.0 } else { -1.0 },
        })
    }
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

/// Moves S1's loops onto those of key surface `k` (`sk`, registered disk `hk`): matched
/// loops, targets, the harmonic extension of the moves, and the fold check (the moves of
/// the loop vertices near a face that would fold are halved, up to
/// [`RIM_MOVE_HALVINGS`] rounds; a loop vertex whose move was cut is located where its
/// partial move puts it instead of exactly on the key loop).
pub(super) fn carry_rims(r: &Rims<'_>, k: usize, sk: &TriMesh, hk: &[Complex64]) -> Carried {
    let mut summary = CreaseSummary {
        loops_s1: r.loops[0].len(),
        loops: r.loops[k].len(),
        smallest_share: 1.0,
        ..CreaseSummary::default()
    };
    let Some(ext) = &r.extension else {
        return Carried {
            query: r.s1_disk.to_vec(),
            targets: Vec::new(),
            summary,
        };
    };
    let pairs = match_loops(&r.loops[0], r.s1_disk, &r.loops[k], hk);
    let edge_face = edge_faces(sk.faces());
    let zero = Complex64::new(0.0, 0.0);
    let mut moves = vec![zero; r.s1_disk.len()];
    let mut targets = Vec::new();
    for &(i, j) in &pairs {
        let from = LoopOn {
            vertices: &r.loops[0][i],
            disk: r.s1_disk,
            positions: r.s1.positions(),
        };
        let onto = LoopOn {
            vertices: &r.loops[k][j],
            disk: hk,
            positions: sk.positions(),
        };
        for t in rim_targets(&from, &onto, sk.faces(), &edge_face) {
            moves[t.vertex as usize] = t.disk - r.s1_disk[t.vertex as usize];
            targets.push(t);
        }
    }
    summary.matched = pairs.len();
    summary.largest_move = moves.iter().map(|d| d.norm()).fold(0.0, f64::max);
    // the share of its move every loop vertex gets: 1, halved (again) near the faces of
    // S1's moved disk that would fold
    let mut halvings = vec![0u32; r.s1_disk.len()];
    let mut query = moved(r.s1_disk, &ext.extend(&moves));
    let mut folded = folded_centroids(r.s1.faces(), &query, r.sigma);
    summary.folded_at_full_move = folded.len();
    let mut rounds = 0;
    while !folded.is_empty() && rounds < RIM_MOVE_HALVINGS {
        rounds += 1;
        for t in &targets {
            let z = r.s1_disk[t.vertex as usize];
            if folded.iter().any(|&c| (c - z).norm() < RIM_HALVING_RADIUS) {
                halvings[t.vertex as usize] += 1;
            }
        }
        let scaled: Vec<Complex64> = moves
            .iter()
            .zip(&halvings)
            .map(|(&m, &h)| m * 0.5f64.powi(h as i32))
            .collect();
        query = moved(r.s1_disk, &ext.extend(&scaled));
        folded = folded_centroids(r.s1.faces(), &query, r.sigma);
    }
    if !folded.is_empty() {
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
    Carried {
        query,
        targets,
        summary,
    }
}

/// `disk + delta`.
fn moved(disk: &[Complex64], delta: &[Complex64]) -> Vec<Complex64> {
    disk.iter().zip(delta).map(|(&z, &d)| z + d).collect()
}

/// The centroids of the faces whose image under `map` is folded or degenerate (against
/// the orientation `sigma`), as [`crate::folded_faces`] counts them.
fn folded_centroids(faces: &[[u32; 3]], map: &[Complex64], sigma: f64) -> Vec<Complex64> {
    faces
        .iter()
        .filter_map(|f| {
            let [a, b, c] = f.map(|v| map[v as usize]);
            let area = ((b - a).conj() * (c - a)).im;
            (!(sigma * area > 0.0)).then_some((a + b + c) / 3.0)
        })
        .collect()
}
