//! Local refinement of a key frame on its key surface (issue 37, creases on the lips'
//! curl): a key-frame face whose normal points against the key surface's triangle nearest
//! to its centroid is a flat triangle that cuts a fold of the key surface (its vertices
//! lie on the surface, a fraction of an edge from where they would lie on the fold's
//! sides). Each free vertex of such a face slides *within the key surface*, onto the
//! nearest point of a lattice on the key faces around it ([`REFINE_LATTICE`], at most
//! [`REFINE_MAX_MOVE_EDGES`] away) where fewer faces around the vertex disagree with the
//! key surface, none of them points against the key face it landed on, none shrinks
//! below [`REFINE_MIN_AREA_RATIO`] of its area, and no corner angle is bent further from
//! S1's than [`REFINE_BEND_SLACK_DEG`] beyond the largest such bend before. A vertex with
//! no such point stays where it is. A frame whose faces all agree with the key surface
//! (the identity: every face *is* a key face) is left exactly as it is.
//!
//! The count this lowers is the one `--example nearest_flips` measures; that count is
//! therefore no longer independent of the morph, and the example's distance of the key
//! frame's vertices to the exact correspondence is the independent check.

use conformap_mesh::TriMesh;
use conformap_operators::vec3::{add, cross, dot, norm, scale, sub};
use serde::Serialize;

use crate::quality::face_normal;
use crate::Location;

mod nearest;

pub use nearest::NearestTriangle;

/// Barycentric step of the candidate points of a vertex's move: `1/4` of a key face
/// (`REFINE_LATTICE` = 4: vertices, quarter points of the edges, interior points; 15
/// points per face). Measured (faces against the nearest key triangle after the
/// refinement, wry / pout / the round mouth of `tests/round_mouth.rs`, from 11 / 30 / 56,
/// the exact correspondence 3 / 15 / 0; the sum over the moved vertices of the change of
/// their distance to the exact correspondence, in mean edges): 1 (key vertices only)
/// 7 / 14 / 46, −0.02 / −0.52 / +0.43; 2: 5 / 10 / 34, −0.04 / −0.86 / +1.70; 4: 3 / 6 /
/// 26, −0.25 / −0.13 / +1.55; 8: 1 / 2 / 18, −0.18 / −0.01 / +0.65, at twice the time.
pub const REFINE_LATTICE: usize = 4;

/// Passes over the disagreeing faces: `4` (a pass tries each free vertex of every face
/// that still disagrees; a vertex that found no move is tried again only after a vertex
/// of a face around it moved; [`RefineSummary::passes`] says how many ran).
pub const REFINE_PASSES: usize = 4;

/// The farthest a vertex may move in one step, in mean edge lengths of the key surface:
/// `0.5` (the key frames' vertices on the lips' curl of the shared faces lie 0.1–0.45 of
/// a mean edge beside their exact places; the moves taken there are at most 0.26; the
/// lattice points farther away only cost time).
pub const REFINE_MAX_MOVE_EDGES: f64 = 0.5;

/// A move is refused when it bends a corner angle of the faces around the vertex further
/// from S1's than this many degrees beyond the largest such change before the move: `10`
/// (the moves follow the key surface's fold without reshaping S1's triangles). Measured
/// (faces against the nearest key triangle after the refinement, wry / pout / the round
/// mouth, from 11 / 30 / 56, exact correspondence 3 / 15 / 0; the sum over the moved
/// vertices of the change of their distance to the exact correspondence, in mean edges;
/// pout's 99th percentile of the largest corner-angle change per face against S1, 45.03°
/// without the refinement): 0° 8 / 22 / 40, −0.010 / −0.077 / +0.54, 44.27°; 5° 5 / 18 /
/// 40, −0.023 / −0.103 / +0.23, 44.27°; 10° 3 / 6 / 26, −0.248 / −0.125 / +1.55, 44.62°;
/// 20° 1 / 2 / 18, −0.32 / −0.14 / +1.48, 45.12°; no limit 0 / 0 / 1, +0.002 / −0.012 /
/// +3.53, 46.35°.
pub const REFINE_BEND_SLACK_DEG: f64 = 10.0;

/// A move is refused when a face around the vertex would keep less than this fraction of
/// its area before the move: `0.1` (no move may crush a face on the way to agreeing with
/// the key surface).
pub const REFINE_MIN_AREA_RATIO: f64 = 0.1;

/// What [`refine_key_frame`] did to one key frame.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RefineSummary {
    /// Faces whose normal pointed against the key triangle nearest to their centroid,
    /// before the refinement.
    pub disagreeing_before: usize,
    /// The same after it.
    pub disagreeing_after: usize,
    /// Vertex moves taken.
    pub moves: usize,
    /// Passes over the disagreeing faces that moved a vertex (at most
    /// [`REFINE_PASSES`]).
    pub passes: usize,
    /// The largest move, in mean edge lengths of the key surface.
    pub largest_move_edges: f64,
    /// Milliseconds taken (the nearest-triangle grid included when the caller times it
    /// in; [`refine_key_frame`] alone leaves 0).
    pub wall_ms: f64,
}

/// Faces of `frame` (connectivity `faces`) whose normal points against the normal of the
/// key triangle nearest (in 3D) to their centroid, ascending. `landing[f]` (a key face
/// near face `f`, e.g. where it landed) starts each search.
pub fn disagreeing_faces(
    near: &NearestTriangle<'_>,
    frame: &[[f64; 3]],
    faces: &[[u32; 3]],
    landing: &[Location],
) -> Vec<usize> {
    faces
        .iter()
        .zip(landing)
        .enumerate()
        .filter(|(_, (f, at))| disagrees(near, frame, f, at.face))
        .map(|(k, _)| k)
        .collect()
}

/// Whether face `f` of `frame` points against the key triangle nearest to its centroid
/// (searched from key face `start`).
fn disagrees(near: &NearestTriangle<'_>, frame: &[[f64; 3]], f: &[u32; 3], start: u32) -> bool {
    let c = scale(
        1.0 / 3.0,
        add(
            add(frame[f[0] as usize], frame[f[1] as usize]),
            frame[f[2] as usize],
        ),
    );
    near.nearest_points_against(c, start as usize, face_normal(frame, f))
}

/// The 3D point of `mesh` at `l`.
fn point_at(mesh: &TriMesh, l: &Location) -> [f64; 3] {
    let f = mesh.faces()[l.face as usize];
    let p = mesh.positions();
    let mut q = [0.0; 3];
    for i in 0..3 {
        for c in 0..3 {
            q[c] += l.bary[i] * p[f[i] as usize][c];
        }
    }
    q
}

/// The key frame to refine: S1's faces, the key surface, and per S1 vertex and face what
/// the morph computed.
pub struct KeyFrame<'a> {
    /// S1's faces (the frame's connectivity).
    pub faces: &'a [[u32; 3]],
    /// S1's vertex positions (the shape whose corner angles a move may not bend by
    /// more than [`REFINE_BEND_SLACK_DEG`] further).
    pub rest: &'a [[f64; 3]],
    /// The key surface.
    pub key: &'a TriMesh,
    /// Where every S1 vertex lies on the key surface (moved by the refinement).
    pub locations: &'a mut [Location],
    /// The 3D positions of S1's vertices on the key surface (moved with `locations`).
    pub frame: &'a mut [[f64; 3]],
    /// The key face every S1 face landed on ([`crate::quality::flipped_against_key`]);
    /// a move never makes a face point against it.
    pub landing: &'a [Location],
    /// Vertices that never move (S1's boundary, landmarks, vertices carried onto the key
    /// surface's rims).
    pub held: &'a [bool],
}

/// Refines a key frame in place ([module docs](self)): free vertices of faces that
/// disagree with the key triangle nearest to them slide within the key surface.
pub fn refine_key_frame(near: &NearestTriangle<'_>, kf: KeyFrame<'_>) -> RefineSummary {
    let KeyFrame {
        faces,
        rest,
        key,
        locations,
        frame,
        landing,
        held,
    } = kf;
    let mut bad = vec![false; faces.len()];
    for f in disagreeing_faces(near, frame, faces, landing) {
        bad[f] = true;
    }
    let before = bad.iter().filter(|&&b| b).count();
    let mut summary = RefineSummary {
        disagreeing_before: before,
        disagreeing_after: before,
        ..RefineSummary::default()
    };
    if before == 0 {
        return summary;
    }
    let star = vertex_faces(faces, frame.len());
    let key_star = vertex_faces(key.faces(), key.num_vertices());
    let mean_edge = mean_edge(key);
    let key_normal =
        |g: usize| face_normal(key.positions(), &key.faces()[landing[g].face as usize]);
    // a vertex that found no move stays stuck until a vertex of a face around it moves
    let mut stuck = vec![false; frame.len()];
    for _ in 0..REFINE_PASSES {
        let mut moved = false;
        let todo: Vec<usize> = (0..faces.len()).filter(|&f| bad[f]).collect();
        for f in todo {
            if !bad[f] {
                continue;
            }
            for &v in &faces[f] {
                let v = v as usize;
                if held[v] || stuck[v] {
                    continue;
                }
                let around = &star[v];
                let current = around.iter().filter(|&&g| bad[g as usize]).count();
                if current == 0 {
                    continue;
                }
                let areas: Vec<f64> = around
                    .iter()
                    .map(|&g| norm(face_normal(frame, &faces[g as usize])))
                    .collect();
                // a move is taken when no face around v is crushed or points against
                // the key face it landed on, and fewer of them disagree with the
                // nearest key triangle
                // the largest change of a corner angle from S1 over the faces around v
                let rest_angles: Vec<[f64; 3]> = around
                    .iter()
                    .map(|&g| corner_angles(rest, &faces[g as usize]))
                    .collect();
                let bend = |frame: &[[f64; 3]]| -> f64 {
                    around
                        .iter()
                        .zip(&rest_angles)
                        .map(|(&g, a)| {
                            let b = corner_angles(frame, &faces[g as usize]);
                            (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f64::max)
                        })
                        .fold(0.0, f64::max)
                };
                let bend_limit = bend(frame) + REFINE_BEND_SLACK_DEG.to_radians();
                // cheapest checks first: areas and landing faces, the bend, then the
                // nearest key triangles (stopping once `current` faces disagree)
                let takes = |frame: &[[f64; 3]]| -> bool {
                    let fits = around.iter().zip(&areas).all(|(&g, &area)| {
                        let a = face_normal(frame, &faces[g as usize]);
                        norm(a) >= REFINE_MIN_AREA_RATIO * area
                            && dot(a, key_normal(g as usize)) > 0.0
                    });
                    if !fits || !(bend(frame) <= bend_limit) {
                        return false;
                    }
                    let mut n = 0;
                    around.iter().all(|&g| {
                        let g = g as usize;
                        n += usize::from(disagrees(near, frame, &faces[g], landing[g].face));
                        n < current
                    })
                };
                let old = frame[v];
                let mut cands = candidates(key, &key_star, &locations[v], old);
                cands.retain(|c| c.0 <= REFINE_MAX_MOVE_EDGES * mean_edge);
                cands.sort_by(|a, b| a.0.total_cmp(&b.0));
                let mut taken = None;
                for (d, l, q) in cands {
                    frame[v] = q;
                    if takes(frame) {
                        taken = Some((d, l));
                        break;
                    }
                }
                frame[v] = old;
                let Some((d, l)) = taken else {
                    stuck[v] = true;
                    continue;
                };
                locations[v] = l;
                frame[v] = point_at(key, &l);
                for &g in around {
                    let g = g as usize;
                    bad[g] = disagrees(near, frame, &faces[g], landing[g].face);
                    for &u in &faces[g] {
                        stuck[u as usize] = false;
                    }
                }
                summary.moves += 1;
                summary.largest_move_edges = summary.largest_move_edges.max(d / mean_edge);
                moved = true;
            }
        }
        if !moved {
            break;
        }
        summary.passes += 1;
    }
    summary.disagreeing_after = bad.iter().filter(|&&b| b).count();
    summary
}

/// The lattice points ([`REFINE_LATTICE`]) of the key faces around the key face at `at`
/// (every face sharing a vertex with it): distance from `from`, location, 3D point.
fn candidates(
    key: &TriMesh,
    key_star: &[Vec<u32>],
    at: &Location,
    from: [f64; 3],
) -> Vec<(f64, Location, [f64; 3])> {
    let mut kfs: Vec<u32> = Vec::new();
    for &kv in &key.faces()[at.face as usize] {
        kfs.extend_from_slice(&key_star[kv as usize]);
    }
    kfs.sort_unstable();
    kfs.dedup();
    let n = REFINE_LATTICE;
    let mut out = Vec::with_capacity(kfs.len() * (n + 1) * (n + 2) / 2);
    for &face in &kfs {
        for i in 0..=n {
            for j in 0..=n - i {
                let bary = [i, j, n - i - j].map(|x| x as f64 / n as f64);
                let l = Location {
                    face,
                    bary,
                    outside: 0.0,
                };
                let q = point_at(key, &l);
                out.push((norm(sub(q, from)), l, q));
            }
        }
    }
    out
}

/// The faces around every vertex.
fn vertex_faces(faces: &[[u32; 3]], n: usize) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new(); n];
    for (k, f) in faces.iter().enumerate() {
        for &v in f {
            out[v as usize].push(k as u32);
        }
    }
    out
}

/// The mean edge length of `mesh` (every face's three edges).
fn mean_edge(mesh: &TriMesh) -> f64 {
    let p = mesh.positions();
    let total: f64 = mesh
        .faces()
        .iter()
        .flat_map(|f| (0..3).map(move |e| (f[e], f[(e + 1) % 3])))
        .map(|(a, b)| norm(sub(p[a as usize], p[b as usize])))
        .sum();
    total / (3 * mesh.num_faces()).max(1) as f64
}

/// The corner angles (radians) of face `f` of `p`.
fn corner_angles(p: &[[f64; 3]], f: &[u32; 3]) -> [f64; 3] {
    let [a, b, c] = f.map(|v| p[v as usize]);
    let angle = |o: [f64; 3], x: [f64; 3], y: [f64; 3]| {
        let (u, w) = (sub(x, o), sub(y, o));
        norm(cross(u, w)).atan2(dot(u, w))
    };
    [angle(a, b, c), angle(b, c, a), angle(c, a, b)]
}
