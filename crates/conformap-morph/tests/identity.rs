//! The morph of a surface onto itself is the identity: identical surfaces and landmarks
//! give every frame equal to S1 (to rounding), and a copy moved rigidly is reached by
//! the identity correspondence (every vertex of S1 lands on its own copy).
//!
//! The bound is [`IDENTITY_TOL`] of S1's bounding-box diagonal. Measured (soft λ = 1000,
//! crease matching on): 0 on woody, spothead and alligator (the frames are S1 bit for
//! bit), 7.5e-17 on the ICT neutral face; before the registration was anchored at the
//! surface's own disk map the same runs moved vertices by 49 % (woody), 7.4 %
//! (spothead), 0.065 % (ICT) of the diagonal.

#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

use std::path::{Path, PathBuf};

use conformap_mesh::TriMesh;
use conformap_morph::{morph, Landmarks, Morph, MorphOptions, Surface};

/// The largest distance of a frame vertex from its S1 position allowed, relative to S1's
/// diagonal: `1e-12`, about 10⁴ times what rounding leaves (≤ 1e-16 measured) and 10⁸
/// times below the smallest error this test caught before the fix (1e-4 of a median edge
/// is ~1e-6 of the diagonal on these meshes).
const IDENTITY_TOL: f64 = 1e-12;

/// Frames checked per morph: the two key frames and three in between.
const FRAMES: usize = 5;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

fn read(path: &Path) -> TriMesh {
    conformap_io::read_mesh(path).unwrap().mesh
}

fn dist(p: [f64; 3], q: [f64; 3]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

/// The largest distance (relative to S1's diagonal) of any vertex of any of [`FRAMES`]
/// frames from `expected(t, v)`.
fn worst_frame_error(m: &Morph, s1: &TriMesh, expected: impl Fn(f64, [f64; 3]) -> [f64; 3]) -> f64 {
    let diag = s1.bbox_diagonal();
    m.frame_times(FRAMES)
        .unwrap()
        .into_iter()
        .map(|t| {
            m.frame(t)
                .iter()
                .zip(s1.positions())
                .map(|(&p, &q)| dist(p, expected(t, q)))
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
        / diag
}

/// Morphs `mesh` (landmarks `lm`) onto an identical copy and checks every frame and the
/// registration report; returns the worst frame error.
fn assert_identity(name: &str, mesh: &TriMesh, lm: &Landmarks, options: &MorphOptions) -> f64 {
    let s = Surface::new(mesh.clone(), lm.clone());
    let m = morph(&[s.clone(), s], options).unwrap_or_else(|e| panic!("{name}: {e}"));
    let worst = worst_frame_error(&m, mesh, |_, q| q);
    assert!(
        worst <= IDENTITY_TOL,
        "{name}: a frame is {worst:.3e} of the diagonal off S1"
    );
    let reg = m.report.keys[1].registration.as_ref().unwrap();
    // the registration is the identity: nothing folds, nothing is backed off or warped,
    // the energy is the disk map's
    assert_eq!(reg.folded_faces, 0, "{name}: {:?}", reg.notes);
    assert!(
        reg.warp.is_none() && reg.notes.is_empty(),
        "{name}: {reg:?}"
    );
    assert!(
        (reg.dirichlet_energy - reg.dirichlet_energy_before).abs()
            <= 1e-12 * reg.dirichlet_energy_before,
        "{name}: E_D {} → {}",
        reg.dirichlet_energy_before,
        reg.dirichlet_energy
    );
    assert!(reg.landmark_disk_errors.iter().all(|&e| e <= 1e-15));
    assert_eq!(m.report.keys[1].key_frame_flipped_faces, 0, "{name}");
    worst
}

fn fixture_cases() -> Vec<(&'static str, TriMesh, Landmarks)> {
    let dir = fixtures();
    let ict = std::fs::read_to_string(dir.join("morph/ict_neutral.landmarks.txt")).unwrap();
    [
        ("woody", "woody.obj", "400 a\n401 b\n".to_string()),
        ("spothead", "spothead.obj", "149 a\n844 b\n".to_string()),
        ("alligator", "alligator.obj", "3149 a\n977 b\n".to_string()),
        ("ict_neutral", "morph/ict_neutral.obj", ict),
    ]
    .into_iter()
    .map(|(name, file, lm)| (name, read(&dir.join(file)), Landmarks::parse(&lm).unwrap()))
    .collect()
}

#[test]
fn every_fixture_disk_morphed_onto_itself_is_the_identity() {
    for (name, mesh, lm) in fixture_cases() {
        let soft = assert_identity(name, &mesh, &lm, &MorphOptions::DEFAULT);
        let hard = assert_identity(
            name,
            &mesh,
            &lm,
            &MorphOptions::DEFAULT.with_hard_landmarks(),
        );
        let plain = assert_identity(
            name,
            &mesh,
            &lm,
            &MorphOptions::DEFAULT.with_crease_matching(false),
        );
        eprintln!("{name}: soft {soft:.2e}, hard {hard:.2e}, no creases {plain:.2e}");
    }
}

/// A rotation about the axis `(1, 2, 2)/3` by 0.7 rad, then a translation by `shift`.
fn rigid(p: [f64; 3], shift: f64) -> [f64; 3] {
    let a = [1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0];
    let (s, c) = 0.7f64.sin_cos();
    let dot = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
    let cross = [
        a[1] * p[2] - a[2] * p[1],
        a[2] * p[0] - a[0] * p[2],
        a[0] * p[1] - a[1] * p[0],
    ];
    let mut out = [0.0; 3];
    for i in 0..3 {
        out[i] = p[i] * c + cross[i] * s + a[i] * dot * (1.0 - c) + shift * (i as f64 + 1.0);
    }
    out
}

/// S2 = S1 rotated and moved: the key frame is S1 moved rigidly (every vertex of S1 on
/// its own copy), i.e. the registration is the identity; the frames in between are the
/// straight interpolation between the two copies (a spline through two keys).
#[test]
fn a_rigidly_moved_copy_is_reached_by_the_identity() {
    // not alligator: its disk map squeezes the tail into faces of area 1e-28, and the disk
    // maps of the two copies (whose cotangent weights differ by rounding) differ by up to
    // 8e-10 there, hundreds of face sizes: 331 of S1's vertices fall outside the copy's
    // disk and the key frame is 9.7 % of the diagonal off. That is the disk map's
    // conditioning, not the morph's; identical copies are exact (test above).
    for (name, mesh, lm) in fixture_cases().into_iter().filter(|c| c.0 != "alligator") {
        let shift = 0.3 * mesh.bbox_diagonal();
        let moved: Vec<[f64; 3]> = mesh.positions().iter().map(|&p| rigid(p, shift)).collect();
        let copy = TriMesh::try_new(moved, mesh.faces().to_vec()).unwrap();
        let s1 = Surface::new(mesh.clone(), lm.clone());
        let m = morph(&[s1, Surface::new(copy, lm)], &MorphOptions::DEFAULT).unwrap();
        let worst = worst_frame_error(&m, &mesh, |t, q| {
            let r = rigid(q, shift);
            [0, 1, 2].map(|i| (1.0 - t) * q[i] + t * r[i])
        });
        // measured: 3.1e-14 (woody), 2.8e-14 (spothead), 1.2e-14 (ICT neutral)
        assert!(worst <= 1e-9, "{name}: {worst:.3e} of the diagonal off");
        eprintln!("{name}: rigid copy {worst:.2e}");
    }
}

/// Two interior landmarks of a mesh without a landmark file, well inside its disk map
/// (the normalization refuses landmarks within 1e-9 of the circle, where meshes such as
/// the maze put most of their vertices): the two vertices nearest radius 0.3 of the disk.
fn two_interior_landmarks(mesh: &TriMesh) -> Landmarks {
    use conformap_disk::{run_disk_method, DiskMethod, DiskOptions, DiskProblem};
    let mut problem = DiskProblem::new(mesh).unwrap();
    let disk = run_disk_method(&mut problem, DiskMethod::CcemQn, &DiskOptions::DEFAULT).unwrap();
    let mut order: Vec<usize> = (0..disk.map.len()).collect();
    order.sort_by(|&a, &b| {
        let (ra, rb) = (disk.map[a].norm(), disk.map[b].norm());
        (ra - 0.3).abs().total_cmp(&(rb - 0.3).abs())
    });
    let (a, b) = (order[0], order[1]);
    Landmarks::parse(&format!("{a} a\n{b} b\n")).unwrap()
}

#[test]
#[ignore = "reads ../shared/meshes and ../shared/morph (large disk meshes)"]
fn every_shared_disk_morphed_onto_itself_is_the_identity() {
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared");
    let given: [(&str, &str); 4] = [
        ("woody", "400 a\n401 b\n"),
        ("spothead", "149 a\n844 b\n"),
        ("alligator", "3149 a\n977 b\n"),
        ("human_face", "7636 a\n7825 b\n"),
    ];
    // not the maze: its disk map puts thousands of vertices within 1e-12 of each other
    // near the circle, and the normalized map folds 1412 faces by rounding alone (none
    // before the Möbius normalization); where faces overlap, point location cannot tell
    // which one a vertex of S1 belongs to (1917 vertices off, up to 25 % of the diagonal)
    for name in [
        "woody",
        "alligator",
        "spothead",
        "camelhead",
        "human_face",
        "chinese_lion",
        "hand",
    ] {
        let mesh = read(&shared.join(format!("meshes/{name}.obj")));
        let lm = given.iter().find(|g| g.0 == name).map_or_else(
            || two_interior_landmarks(&mesh),
            |g| Landmarks::parse(g.1).unwrap(),
        );
        let worst = assert_identity(name, &mesh, &lm, &MorphOptions::DEFAULT);
        eprintln!("{name}: {worst:.2e}");
    }
    for face in ["ict_neutral", "ict_wry", "ict_pout"] {
        let mesh = read(&shared.join(format!("morph/{face}.obj")));
        let text = std::fs::read_to_string(shared.join(format!("morph/{face}.landmarks.txt")));
        let lm = Landmarks::parse(&text.unwrap()).unwrap();
        let worst = assert_identity(face, &mesh, &lm, &MorphOptions::DEFAULT);
        eprintln!("{face}: {worst:.2e}");
    }
}
