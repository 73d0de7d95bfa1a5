//! End-to-end runs of `conformap morph` on the ICT faces in `fixtures/morph/` (neutral →
//! pout: different vertex counts 6706 / 7432, boundaries 138 / 166).

#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::path::PathBuf;

use support::{conformap, fixture, json, s, stderr, tmpdir};

fn face(name: &str) -> (PathBuf, PathBuf) {
    (
        fixture(&format!("morph/{name}.obj")),
        fixture(&format!("morph/{name}.landmarks.txt")),
    )
}

#[test]
fn glb_loads_in_a_standard_reader_with_targets_and_animation() {
    let d = tmpdir("morph-glb");
    let ((m1, l1), (m2, l2)) = (face("ict_neutral"), face("ict_pout"));
    let (out, rep) = (d.join("morph.glb"), d.join("r.json"));
    let o = conformap(&[
        "morph",
        s(&m1),
        s(&m2),
        "--landmarks",
        s(&l1),
        s(&l2),
        "--frames",
        "12",
        "-o",
        s(&out),
        "--report",
        s(&rep),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (doc, buffers, _) = gltf::import(&out).expect("gltf reads the GLB");
    let mesh = doc.meshes().next().expect("a mesh");
    let prim = mesh.primitives().next().expect("a primitive");
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    assert_eq!(reader.read_positions().expect("positions").count(), 6706);
    assert_eq!(
        reader.read_indices().expect("indices").into_u32().count(),
        3 * 13272
    );
    assert_eq!(reader.read_morph_targets().count(), 1);
    let anim = doc.animations().next().expect("an animation");
    let ch = anim.channels().next().expect("a channel");
    assert_eq!(
        ch.target().property(),
        gltf::animation::Property::MorphTargetWeights
    );
    let r = ch.reader(|b| Some(&buffers[b.index()]));
    let inputs: Vec<f32> = r.read_inputs().expect("times").collect();
    assert_eq!(inputs.len(), 12);
    let Some(gltf::animation::util::ReadOutputs::MorphTargetWeights(w)) = r.read_outputs() else {
        panic!("no weights");
    };
    let w: Vec<f32> = w.into_f32().collect();
    assert_eq!((w[0], w[11]), (0.0, 1.0)); // S1 first, S2 last
    let r = json(&rep);
    assert_eq!(r["command"], "morph");
    assert_eq!(r["key_frames"], serde_json::json!([0, 11]));
    let key = &r["morph"]["keys"][1];
    assert_eq!(key["registration"]["folded_faces"], 0);
    // measured 9.0e-4 (Eq. 34 folds at λ = 1000: largest λ without a fold, then the
    // fold-free landmark warp); the issue asks ≤ 1 %
    assert!(key["landmark_error_max_rel"].as_f64().unwrap() < 0.01);
    assert_eq!(key["registration"]["warp"]["reached"], true);
    assert!(r["timings_ms"]["total"].as_f64().unwrap() > 0.0);
}

#[test]
fn frames_dir_hard_mode_starts_at_s1_and_ends_on_s2_landmarks() {
    let d = tmpdir("morph-dir");
    let ((m1, l1), (m2, l2)) = (face("ict_neutral"), face("ict_pout"));
    let dir = format!("{}/", d.display());
    let rep = tmpdir("morph-dir-report").join("report.json");
    let o = conformap(&[
        "morph",
        s(&m1),
        s(&m2),
        "--landmarks",
        s(&l1),
        s(&l2),
        "--frames",
        "5",
        "-o",
        &dir,
        "--hard",
        "--report",
        s(&rep),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // hard landmarks without a fold (before the landmark warp: 56 folded faces)
    let r = json(&rep);
    assert_eq!(r["morph"]["keys"][1]["registration"]["folded_faces"], 0);
    assert_eq!(r["morph"]["keys"][1]["registration"]["mode"], "hard");
    let s1 = conformap_io::read_mesh(&m1).unwrap().mesh;
    let s2 = conformap_io::read_mesh(&m2).unwrap().mesh;
    let f0 = conformap_io::read_mesh(d.join("frame_0000.obj"))
        .unwrap()
        .mesh;
    assert_eq!(f0.positions(), s1.positions()); // exactly S1
    assert_eq!(f0.faces(), s1.faces());
    let last = conformap_io::read_mesh(d.join("frame_0004.obj"))
        .unwrap()
        .mesh;
    assert_eq!(last.faces(), s1.faces());
    let (v1, v2) = (lm(&l1), lm(&l2));
    let diag = s2.bbox_diagonal();
    for (a, b) in v1.iter().zip(&v2) {
        let (p, q) = (last.positions()[*a], s2.positions()[*b]);
        let dist = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        assert!(
            dist <= 1e-9 * diag,
            "landmark {a}->{b}: {:.3e} of the diagonal",
            dist / diag
        );
    }
    assert!(!d.join("frame_0005.obj").exists());
}

fn lm(path: &PathBuf) -> Vec<usize> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().next().unwrap().parse().unwrap())
        .collect()
}

/// Runs a morph that must fail with `code` and a message containing `needle`, writing
/// nothing.
fn refused(tag: &str, surfaces: &[PathBuf], landmarks: &[PathBuf], code: i32, needle: &str) {
    let d = tmpdir(tag);
    let out = d.join("m.glb");
    let mut args = vec!["morph".to_string()];
    args.extend(surfaces.iter().map(|p| s(p).to_string()));
    args.push("--landmarks".into());
    args.extend(landmarks.iter().map(|p| s(p).to_string()));
    args.extend(["--frames", "4", "-o"].map(String::from));
    args.push(s(&out).to_string());
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = conformap(&argv);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{tag}: {err}");
    assert!(err.contains(needle), "{tag}: {err:?} lacks {needle:?}");
    assert!(!out.exists(), "{tag}: wrote output");
}

#[test]
fn every_bad_input_class_gets_its_message() {
    let d = tmpdir("morph-bad");
    let ((m1, l1), (m2, l2)) = (face("ict_neutral"), face("ict_pout"));
    let write = |name: &str, text: &str| {
        let p = d.join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let text = std::fs::read_to_string(&l2).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let short = write("short.txt", &(lines[..8].join("\n") + "\n"));
    let renamed = write("renamed.txt", &text.replace("chin", "jaw"));
    let out_of_range = write("range.txt", &text.replace("968 chin", "7432 chin"));
    let repeated = write("repeated.txt", &text.replace("968 chin", "6213 chin"));
    let syntax = write("syntax.txt", &text.replace("968 chin", "nine chin"));
    refused(
        "one",
        std::slice::from_ref(&m1),
        std::slice::from_ref(&l1),
        2,
        "at least two surfaces",
    );
    refused(
        "count",
        &[m1.clone(), m2.clone()],
        std::slice::from_ref(&l1),
        2,
        "2 surfaces but 1 landmark files",
    );
    refused(
        "short",
        &[m1.clone(), m2.clone()],
        &[l1.clone(), short],
        1,
        "landmark 8 is \"<none>\", but surface 0 has \"upper_lip\"",
    );
    refused(
        "renamed",
        &[m1.clone(), m2.clone()],
        &[l1.clone(), renamed],
        1,
        "landmark 7 is \"jaw\", but surface 0 has \"chin\"",
    );
    refused(
        "range",
        &[m1.clone(), m2.clone()],
        &[l1.clone(), out_of_range],
        1,
        "landmark \"chin\" is vertex 7432, but the mesh has 7432 vertices",
    );
    refused(
        "repeated",
        &[m1.clone(), m2.clone()],
        &[l1.clone(), repeated],
        1,
        "landmarks 5 and 7 (same vertex) repeat each other",
    );
    refused(
        "syntax",
        &[m1.clone(), m2.clone()],
        &[l1.clone(), syntax],
        1,
        "syntax.txt:8: \"nine\" is not a 0-based vertex index",
    );
    // not a disk: the disk map's own refusal, naming the file
    let torus = fixture("punctured_torus.obj");
    let tl = write("torus.txt", "0 nose_tip\n1 left_eye_inner\n");
    let two = write("two.txt", "4857 nose_tip\n3742 left_eye_inner\n");
    refused(
        "torus",
        &[m1.clone(), torus],
        &[two, tl],
        1,
        "punctured_torus.obj",
    );
    // interior vertices the maze's disk map crowds against the circle: not called boundary
    // vertices (they are not), and the hint says where to put landmarks instead
    let maze = fixture("maze.obj");
    let ml = write("maze.txt", "100 a\n200 b\n");
    refused(
        "maze",
        &[maze.clone(), maze],
        &[ml.clone(), ml],
        1,
        "landmark 0 (vertex 100) is an interior vertex, but the disk map puts it at |z| = 0.99999",
    );
}

/// `--max-memory` holds the morph as it holds `disk`: refused before reading when the
/// surfaces' files alone would not fit, refused after reading and before solving when the
/// morph's estimate (every surface's disk problem kept at once) would not, with the
/// estimate, the limit and a hint, exit 1 and nothing written; the report of a run that
/// fits carries the estimate and the limit.
#[test]
fn max_memory_refuses_before_reading_and_before_solving() {
    let d = tmpdir("morph-memory");
    let ((m1, l1), (m2, l2)) = (face("ict_neutral"), face("ict_pout"));
    let (out, rep) = (d.join("m.glb"), d.join("r.json"));
    let run = |limit: &str| {
        conformap(&[
            "morph",
            s(&m1),
            s(&m2),
            "--landmarks",
            s(&l1),
            s(&l2),
            "--frames",
            "3",
            "-o",
            s(&out),
            "--report",
            s(&rep),
            "--max-memory",
            limit,
        ])
    };
    let file_bytes = std::fs::metadata(&m1).unwrap().len() + std::fs::metadata(&m2).unwrap().len();
    // below the read estimate (8 bytes per file byte)
    let o = run(&(file_bytes * 4).to_string());
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("reading these 2 files"), "{e}");
    assert!(e.contains("hint:"), "{e}");
    assert!(!out.exists() && !rep.exists());
    // above the read estimate, below the solve's
    let o = run(&(file_bytes * 8 + 1024).to_string());
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("the morph through these 2 surfaces needs an estimated"),
        "{e}"
    );
    assert!(e.contains("(--max-memory); nothing was computed"), "{e}");
    assert!(!out.exists() && !rep.exists());
    // enough
    let o = run("4G");
    assert!(o.status.success(), "{}", stderr(&o));
    let r = json(&rep);
    let est = r["memory"]["estimated_peak_bytes"].as_u64().unwrap();
    assert!(est > file_bytes * 8, "estimate {est}");
    assert_eq!(r["memory"]["limit_source"], "--max-memory");
    // the measured peak is below the estimate (the model is cautious, not wild: within 20×)
    let peak = r["memory"]["peak_rss_bytes"].as_u64().unwrap();
    assert!(peak > 0 && est < 20 * peak, "estimate {est}, peak {peak}");
}
