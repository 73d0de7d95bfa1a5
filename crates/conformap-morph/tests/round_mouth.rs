//! A round mouth (issue 37, "Morph on a round mouth"): the neutral ICT face of
//! `fixtures/morph/` morphed onto itself with its mouth pursed into a slightly tall "O"
//! pushed forward (`doc_support::round_mouth`, same vertices and faces, so the exact
//! correspondence is the identity; `--example round_mouth` writes it). The rim of the
//! zipped mouth fill is then round: its two vertices farthest apart are the top and the
//! bottom of the opening, not the mouth corners, and pairing the rims' corners that way
//! turned S1's mouth by a quarter turn. The rims are now cut at the landmarks near them.

#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

use std::path::Path;

use conformap_mesh::TriMesh;
use conformap_morph::creases::crease_loops;
use conformap_morph::doc_support::{round_mouth, Pucker};
use conformap_morph::quality::{face_normal, CREASE_ANGLE_DEG};
use conformap_morph::{morph, Landmarks, Morph, MorphOptions, Surface};

/// A key-frame face counts as folded when its normal turns by more than this many degrees
/// from the key surface's normal where it lies: `120` (the measure; the rims'
/// folds are 127–178°).
const TURNED_DEG: f64 = 120.0;

/// A frame face counts as degenerate when its area is at most this fraction of the
/// frame's mean face area: `1e-12` (the measure).
const DEGENERATE_OF_MEAN: f64 = 1e-12;

/// Frames checked for degenerate faces: `41` (the count).
const FRAMES: usize = 41;

fn neutral() -> Surface {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/morph");
    let mesh = conformap_io::read_mesh(dir.join("ict_neutral.obj"))
        .unwrap()
        .mesh;
    let text = std::fs::read_to_string(dir.join("ict_neutral.landmarks.txt")).unwrap();
    Surface::new(mesh, Landmarks::parse(&text).unwrap())
}

fn landmark(l: &Landmarks, name: &str) -> u32 {
    let k = l.names().iter().position(|n| n == name).unwrap();
    l.vertices()[k]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm([a[0] - b[0], a[1] - b[1], a[2] - b[2]])
}

/// The round-mouth face and S1 morphed onto it.
fn round_mouth_morph() -> (Surface, TriMesh, (u32, u32), Morph) {
    let s1 = neutral();
    let corners = (
        landmark(&s1.landmarks, "mouth_right"),
        landmark(&s1.landmarks, "mouth_left"),
    );
    let round = round_mouth(&s1.mesh, corners, &Pucker::DEFAULT);
    let s2 = Surface::new(round.clone(), s1.landmarks.clone());
    let m = morph(&[s1.clone(), s2], &MorphOptions::DEFAULT).unwrap();
    (s1, round, corners, m)
}

#[test]
fn a_round_mouth_neither_folds_nor_degenerates() {
    let (s1, round, corners, m) = round_mouth_morph();
    let r = &m.report.keys[1];
    let c = r.creases.as_ref().unwrap();
    assert_eq!((c.loops_s1, c.loops, c.matched), (3, 3, 3), "{c:?}");
    // every loop cut at the landmarks near it (mouth and eye corners), every rim vertex
    // of S1 exactly on the round face's rims (with the corners paired by distance: the
    // mouth's moves cut down where S1's disk folded 504 faces, 84 of 158 on the rims)
    assert_eq!((c.landmark_anchored, c.landmark_anchors), (3, 6), "{c:?}");
    assert!(c.rim_vertices == 158 && c.smallest_share >= 1.0, "{c:?}");
    // the landmark cut's carry folds nothing, so the corner cut (the rims' two vertices
    // farthest apart: the top and the bottom of the "O", 30 flipped faces) is not tried
    assert_eq!(c.folded_at_full_move, 0, "{c:?}");
    assert_eq!(c.corner_anchored, 0, "{c:?}");
    assert_eq!(c.flipped_faces_cut_at_corners, None, "{c:?}");

    // the key frame: no face turned by more than 120° against the round face where it
    // lies (with the corners paired by distance: 21, and 30 turned by more than 90° in
    // patches of up to 3)
    let key = &m.keys()[1];
    let cos = TURNED_DEG.to_radians().cos();
    let turned = m
        .faces()
        .iter()
        .zip(&m.landings()[1])
        .filter(|(f, at)| {
            let a = face_normal(key, f);
            let b = face_normal(round.positions(), &round.faces()[at.face as usize]);
            let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            !(dot > cos * norm(a) * norm(b))
        })
        .count();
    assert_eq!(turned, 0, "{r:?}");

    // the mouth rim lands near where the exact correspondence (the identity: the round
    // face has S1's vertices) puts it: measured 0.058 of the opening's half-width at
    // worst (shares of arc length in the disk: 0.24; the corners paired by distance,
    // the mouth turned by a quarter: 0.74)
    let p = s1.mesh.positions();
    let half = 0.5 * dist(p[corners.0 as usize], p[corners.1 as usize]);
    let opening = Pucker::DEFAULT.half_width * half;
    let loops = crease_loops(p, s1.mesh.faces(), CREASE_ANGLE_DEG);
    // the mouth rim: the longest loop (74 vertices; the eye rims have 42)
    let mouth = loops.iter().max_by_key(|l| l.len()).unwrap();
    let off = mouth
        .iter()
        .map(|&v| dist(key[v as usize], round.positions()[v as usize]))
        .fold(0.0, f64::max);
    assert!(
        off < 0.1 * opening,
        "rim {:.3} of the opening off",
        off / opening
    );

    // no degenerate face in any frame
    for (i, t) in m.frame_times(FRAMES).unwrap().into_iter().enumerate() {
        let frame = m.frame(t);
        let areas: Vec<f64> = m
            .faces()
            .iter()
            .map(|f| 0.5 * norm(face_normal(&frame, f)))
            .collect();
        let mean = areas.iter().sum::<f64>() / areas.len() as f64;
        let small = areas
            .iter()
            .filter(|&&a| !(a > DEGENERATE_OF_MEAN * mean))
            .count();
        assert_eq!(small, 0, "frame {i}: {small} degenerate faces");
    }
}
