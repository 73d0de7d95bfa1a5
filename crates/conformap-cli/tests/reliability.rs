//! Wrong domains, maps `metrics` must read, staging under signals, morph's frame
//! directory, topology hints and broken map files, through the binary.

#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::{conformap, conformap_ok, fixture, s, stderr, tmpdir};

/// Writes an OBJ of `points` and 0-based `faces`.
fn write_obj(path: &Path, points: &[[f64; 3]], faces: &[[usize; 3]]) {
    let mut text = String::new();
    for p in points {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for f in faces {
        text += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(path, text).unwrap();
}

/// An annulus one triangle wide: `n` inner and `n` outer vertices, `2n` faces, every edge
/// between the circles a chord joining two boundary vertices.
fn thin_annulus(path: &Path, n: usize) {
    let ring = |r: f64| {
        (0..n)
            .map(move |i| TAU * i as f64 / n as f64)
            .map(move |t| [r * t.cos(), r * t.sin(), 0.0])
    };
    let points: Vec<[f64; 3]> = ring(1.0).chain(ring(2.0)).collect();
    let faces: Vec<[usize; 3]> = (0..n)
        .flat_map(|i| {
            let (a, b) = (i, (i + 1) % n);
            [[a, n + b, b], [a, n + a, n + b]]
        })
        .collect();
    write_obj(path, &points, &faces);
}

/// A closed torus of revolution (genus 1), `n × m` quads split in two.
fn torus(path: &Path, n: usize, m: usize) {
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..m {
            let (u, v) = (TAU * i as f64 / n as f64, TAU * j as f64 / m as f64);
            let r = 2.0 + 0.7 * v.cos();
            points.push([r * u.cos(), r * u.sin(), 0.7 * v.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % n) * m + j % m;
    let faces: Vec<[usize; 3]> = (0..n)
        .flat_map(|i| (0..m).map(move |j| (i, j)))
        .flat_map(|(i, j)| {
            [
                [id(i, j), id(i + 1, j), id(i + 1, j + 1)],
                [id(i, j), id(i + 1, j + 1), id(i, j + 1)],
            ]
        })
        .collect();
    write_obj(path, &points, &faces);
}

/// Runs `args`, asserts exit 1 with every needle in stderr and a `hint:` line.
fn refused_with(args: &[&str], needles: &[&str]) {
    let o = conformap(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert!(err.contains("\nhint: "), "{args:?}: no hint in\n{err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: expected `{n}` in\n{err}");
    }
}

fn metrics_json(mesh: &Path, map: &Path) -> serde_json::Value {
    let o = conformap_ok(&["metrics", s(mesh), s(map), "--json"]);
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn mobius_refuses_a_domain_the_mesh_has_no_map_onto() {
    let d = tmpdir("wrong-domain");
    let (woody, spot) = (fixture("woody.obj"), fixture("spot.obj"));
    let (disk, sphere, out) = (d.join("disk.obj"), d.join("sphere.obj"), d.join("out.obj"));
    conformap_ok(&["disk", s(&woody), "-o", s(&disk)]);
    conformap_ok(&["sphere", s(&spot), "-o", s(&sphere)]);
    // before: exit 0 with thousands of flipped faces
    for extra in [&[][..], &["--strict"][..]] {
        let mut args = vec!["mobius", s(&woody), s(&disk), "--domain", "sphere"];
        args.extend(["--objective", "uniform", "-o", s(&out)]);
        args.extend(extra);
        refused_with(
            &args,
            &[
                "has 1 boundary loop(s)",
                "hint: a map of a mesh with boundary is a disk map: rerun with --domain disk",
            ],
        );
    }
    refused_with(
        &[
            "mobius",
            s(&spot),
            s(&sphere),
            "--domain",
            "disk",
            "--objective",
            "uniform",
            "-o",
            s(&out),
        ],
        &[
            "is closed (no boundary loop)",
            "hint: rerun with --domain sphere",
        ],
    );
    assert!(!out.exists(), "nothing is written");
}

#[test]
fn metrics_measures_sphere_maps_on_the_sphere() {
    let d = tmpdir("sphere-metrics");
    let spot = fixture("spot.obj");
    let (out, flat) = (d.join("s.obj"), d.join("flat.obj"));
    conformap_ok(&["sphere", s(&spot), "-o", s(&out), "--flat", s(&flat)]);
    // before: judged as planar maps (121 flipped faces, E_C 138, image area 1e-15)
    let mut means = Vec::new();
    for (map, from) in [
        (&flat, "unit-sphere positions"),
        (&out, "equirectangular texture coordinates per corner"),
    ] {
        let m = metrics_json(&spot, map);
        assert_eq!(m["domain"], "sphere", "{}", map.display());
        assert_eq!(m["param"]["map_from"], from);
        let q = &m["metrics"];
        assert_eq!(q["flipped_faces"], 0, "{}", map.display());
        assert_eq!(q["degenerate_faces"], 0);
        // spot's sphere map: mean angle distortion 2.95° from the exact points; the texture
        // per corner gives the vertices within a face of a pole their faces' mean longitude
        // (so that no face spans the texture), which the reading takes back only
        // approximately: 3.08° there
        let mean = q["angle_distortion_deg"]["mean"].as_f64().unwrap();
        means.push(mean);
        assert!(mean > 0.0 && mean < 3.2, "{mean}");
        assert!(q["radius_residual_max"].as_f64().unwrap() < 1e-9);
    }
    assert!(
        means[0] < 3.0 && (means[1] - means[0]).abs() < 0.2,
        "{means:?}"
    );
    let text = conformap_ok(&["metrics", s(&spot), s(&flat)]);
    let text = String::from_utf8_lossy(&text.stdout).to_string();
    assert!(text.starts_with("sphere map of"), "{text}");
    assert!(text.contains("flipped_faces          0"), "{text}");
}

#[test]
fn global_says_it_refined_and_metrics_and_render_read_what_it_wrote() {
    let d = tmpdir("global-chords");
    let (mesh, out, png) = (d.join("annulus.obj"), d.join("g.obj"), d.join("g.png"));
    thin_annulus(&mesh, 24);
    let o = conformap_ok(&["global", s(&mesh), "-o", s(&out)]);
    let err = stderr(&o);
    // before: "48 vertices, 48 faces" and nothing about the 96 and 144 written
    assert!(
        err.contains("written on a refinement of the input")
            && err.contains("96 vertices, 144 faces"),
        "{err}"
    );
    // before: refused ("has 96 vertices and 144 faces but … has 48 and 48")
    let m = metrics_json(&mesh, &out);
    assert_eq!(m["param"]["own_mesh"]["vertices"], 96);
    assert_eq!(m["param"]["own_mesh"]["faces"], 144);
    assert_eq!(m["param"]["own_mesh"]["refines"]["faces"], 48);
    assert_eq!(m["metrics"]["degenerate_faces"], 0);
    let mean = m["metrics"]["angle_distortion_deg"]["mean"]
        .as_f64()
        .unwrap();
    assert!(mean.is_finite() && mean < 30.0, "{mean}");
    conformap_ok(&["render", s(&mesh), s(&out), "-o", s(&png)]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    // a map that does not refine the mesh is still refused
    let other = d.join("other.obj");
    thin_annulus(&other, 30);
    refused_with(
        &["metrics", s(&mesh), s(&other)],
        &["the map must have the mesh's vertices"],
    );
}

/// Files in `dir` whose names mark them as staging files (ours or a writer's temporary).
fn staging_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("cmstage-") || n.contains("conformap-stage-"))
        .collect()
}

fn landmarks(dir: &Path) -> PathBuf {
    let lm = dir.join("lm.txt");
    std::fs::write(&lm, "400 a\n401 b\n").unwrap();
    lm
}

#[test]
fn sigterm_while_writing_leaves_no_staging_file_and_exits_143() {
    let d = tmpdir("sigterm");
    let (woody, lm) = (fixture("woody.obj"), landmarks(&d));
    let frames = d.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_conformap"))
        .args(["morph", s(&woody), s(&woody), "--landmarks", s(&lm), s(&lm)])
        .args(["--frames", "800", "-o", &format!("{}/", s(&frames))])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t = Instant::now();
    while staging_files(&frames).is_empty() {
        assert!(
            t.elapsed() < Duration::from_secs(300),
            "no staging file appeared"
        );
        assert!(child.try_wait().unwrap().is_none(), "ended before writing");
        std::thread::sleep(Duration::from_millis(2));
    }
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(143), "{err}");
    assert!(err.contains("interrupted by SIGTERM"), "{err}");
    assert_eq!(staging_files(&frames), Vec::<String>::new());
    // all or nothing: no frame was renamed into place
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), 0);
}

#[test]
fn stale_staging_files_of_dead_runs_are_removed_at_start_and_long_names_work() {
    let d = tmpdir("stale");
    // pid_max is at most 2^22 on Linux: process 999999999 never runs
    let stale = [
        ".cmstage-999999999-0.obj",
        "..cmstage-999999999-0.obj.conformap-999999999-1.tmp",
        ".conformap-stage-999999999-2-out.obj",
    ];
    for n in stale {
        std::fs::write(d.join(n), "partial").unwrap();
    }
    let live = format!(".cmstage-{}-0.obj", std::process::id());
    std::fs::write(d.join(&live), "a running process's").unwrap();
    // a legal 210-byte name (before: "File name too long" from the staging name)
    let out = d.join(format!("{}.obj", "n".repeat(206)));
    let o = conformap_ok(&["disk", s(&fixture("woody.obj")), "-o", s(&out)]);
    let err = stderr(&o);
    assert!(
        err.contains("removed 3 staging file(s) left by an interrupted earlier run"),
        "{err}"
    );
    assert!(out.is_file());
    assert_eq!(staging_files(&d), vec![live]);
}

#[test]
fn morph_frame_directory_is_created_and_cleared_of_stale_frames() {
    let d = tmpdir("morph-dir");
    let (woody, lm) = (fixture("woody.obj"), landmarks(&d));
    let dir = d.join("new").join("frames");
    let run = |frames: &str| {
        conformap(&[
            "morph",
            s(&woody),
            s(&woody),
            "--landmarks",
            s(&lm),
            s(&lm),
            "--frames",
            frames,
            "-o",
            &format!("{}/", s(&dir)),
        ])
    };
    // before: "the directory … does not exist"
    let o = run("5");
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let o = run("3");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("removed 2 frame file(s) of an earlier run that this run did not write (frame_0003.obj … frame_0004.obj)"),
        "{}",
        stderr(&o)
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "frame_0000.obj",
            "frame_0001.obj",
            "frame_0002.obj",
            "notes.txt"
        ]
    );
}

#[test]
fn every_topology_refusal_names_the_command_that_maps_it() {
    let d = tmpdir("hints");
    let (torus_obj, annulus, out) = (d.join("torus.obj"), d.join("annulus.obj"), d.join("o.obj"));
    torus(&torus_obj, 16, 8);
    thin_annulus(&annulus, 24);
    let (spot, woody) = (fixture("spot.obj"), fixture("woody.obj"));
    let two = fixture("bad/two_components.obj");
    let global = "hint: `conformap global` maps a closed surface of genus 1";
    let sphere = "hint: `conformap sphere` maps a closed genus-0 surface onto the unit sphere";
    let disk = "hint: `conformap disk` maps a disk onto the unit disk";
    let atlas = "hint: `conformap atlas` charts all 2 components";
    // before: "cut the surface along its handle loops into a disk first"
    let cases: [(&str, &Path, &str); 9] = [
        ("disk", &torus_obj, global),
        ("flatten", &torus_obj, global),
        ("sphere", &torus_obj, global),
        ("disk", &spot, sphere),
        ("flatten", &spot, sphere),
        ("sphere", &woody, disk),
        ("global", &woody, disk),
        ("disk", &two, atlas),
        ("sphere", &two, atlas),
    ];
    for (command, mesh, hint) in cases {
        refused_with(&[command, s(mesh), "-o", s(&out)], &[hint]);
    }
    let help = conformap_ok(&["batch", "--help"]);
    let help = String::from_utf8_lossy(&help.stdout);
    for c in ["disk", "sphere", "global", "flatten", "atlas"] {
        assert!(help.contains(&format!("- {c}:")), "{c} missing in\n{help}");
    }
}

#[test]
fn a_nan_in_a_map_file_is_refused_with_its_vertex_and_a_hint() {
    let d = tmpdir("nan-map");
    let woody = fixture("woody.obj");
    let (flat, out) = (d.join("flat.obj"), d.join("o.obj"));
    conformap_ok(&["disk", s(&woody), "-o", s(&out), "--flat", s(&flat)]);
    let text = std::fs::read_to_string(&flat).unwrap();
    let mut k = 0;
    let broken: String = text
        .lines()
        .map(|l| {
            let l = if l.starts_with("v ") {
                k += 1;
                if k == 8 {
                    "v nan 0 0"
                } else {
                    l
                }
            } else {
                l
            };
            format!("{l}\n")
        })
        .collect();
    let bad = d.join("bad.obj");
    std::fs::write(&bad, broken).unwrap();
    let needles = [
        "bad.obj: the position of vertex 7 is not finite",
        "hint: the map is broken at that vertex",
    ];
    refused_with(&["metrics", s(&woody), s(&bad)], &needles);
    refused_with(
        &[
            "mobius",
            s(&woody),
            s(&bad),
            "--domain",
            "disk",
            "--objective",
            "uniform",
            "-o",
            s(&d.join("m.obj")),
        ],
        &needles,
    );
}
