//! Usability (issue 38): map files matched as other tools write them, tiny disks, batch
//! inputs listed twice, a file where a directory is expected, option messages that name
//! what the user typed, options that would be ignored said aloud, and help texts that say
//! how the map becomes texture coordinates.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use support::{conformap, conformap_ok, fixture, json, metrics_json, s, stderr, tmpdir};

/// `text` (an OBJ) with its `f` lines reversed in order and each face rotated by one corner.
fn reorder_faces(text: &str) -> String {
    let (faces, rest): (Vec<&str>, Vec<&str>) = text.lines().partition(|l| l.starts_with("f "));
    let mut out: Vec<String> = rest.iter().map(|l| l.to_string()).collect();
    for f in faces.iter().rev() {
        let c: Vec<&str> = f.split_whitespace().skip(1).collect();
        out.push(format!("f {} {} {}", c[1], c[2], c[0]));
    }
    out.join("\n") + "\n"
}

#[test]
fn per_vertex_map_with_faces_reordered_and_rotated_is_judged() {
    let d = tmpdir("reorder");
    let (out, flat) = (d.join("o.obj"), d.join("flat.obj"));
    let woody = fixture("woody.obj");
    conformap_ok(&["disk", s(&woody), "-o", s(&out), "--flat", s(&flat), "-q"]);
    let before = metrics_json(&woody, &flat)["metrics"]["conformal_energy"]
        .as_f64()
        .unwrap();
    for (name, map) in [("flat", &flat), ("vt", &out)] {
        let moved = d.join(format!("moved_{name}.obj"));
        std::fs::write(
            &moved,
            reorder_faces(&std::fs::read_to_string(map).unwrap()),
        )
        .unwrap();
        let after = metrics_json(&woody, &moved)["metrics"]["conformal_energy"]
            .as_f64()
            .unwrap();
        assert!(
            (after - before).abs() <= 1e-9 * before,
            "{name}: {after} vs {before}"
        );
    }
    // a face that is not the mesh's is still refused, naming it
    let text = std::fs::read_to_string(&flat).unwrap();
    let first = text.lines().find(|l| l.starts_with("f ")).unwrap();
    let c: Vec<&str> = first.split_whitespace().skip(1).collect();
    let flipped = text.replacen(first, &format!("f {} {} {}", c[0], c[2], c[1]), 1);
    let bad = d.join("flipped.obj");
    std::fs::write(&bad, flipped).unwrap();
    let o = conformap(&["metrics", s(&woody), s(&bad)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("is not a face of"), "{}", stderr(&o));
}

#[test]
fn metrics_and_render_read_global_flat() {
    let d = tmpdir("global-flat");
    let (out, flat) = (d.join("o.obj"), d.join("flat.obj"));
    let eight = fixture("eightsim.obj");
    conformap_ok(&["global", s(&eight), "-o", s(&out), "--flat", s(&flat), "-q"]);
    let from_vt = metrics_json(&eight, &out);
    let from_flat = metrics_json(&eight, &flat);
    let mean = |m: &serde_json::Value| {
        m["metrics"]["angle_distortion_deg"]["mean"]
            .as_f64()
            .unwrap()
    };
    // the same layout up to a uniform scale and a translation: the same angles
    assert!(
        (mean(&from_vt) - mean(&from_flat)).abs() < 1e-6,
        "{} vs {}",
        mean(&from_vt),
        mean(&from_flat)
    );
    assert_eq!(
        from_flat["metrics"]["flipped_faces"],
        from_vt["metrics"]["flipped_faces"]
    );
    let png = d.join("r.png");
    conformap_ok(&["render", s(&eight), s(&flat), "-o", s(&png), "-q"]);
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
}

#[test]
fn disks_of_one_and_two_triangles_map_exactly() {
    let d = tmpdir("tiny");
    let one = d.join("tri1.obj");
    std::fs::write(&one, "v 0 0 0\nv 3 0 0\nv 0.5 2 0\nf 1 2 3\n").unwrap();
    let two = d.join("tri2.obj");
    std::fs::write(
        &two,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    )
    .unwrap();
    for (mesh, method) in [(&one, "ccem-qn"), (&one, "double-cover"), (&two, "cem")] {
        let (out, report) = (d.join("o.obj"), d.join("r.json"));
        let o = conformap(&[
            "disk",
            s(mesh),
            "-o",
            s(&out),
            "--method",
            method,
            "--report",
            s(&report),
        ]);
        assert!(o.status.success(), "{method}: {}", stderr(&o));
        let r = json(&report);
        let m = &r["metrics"];
        assert_eq!(m["flipped_faces"], 0);
        // both a triangle and a square are inscribed in a circle: no angle distortion
        assert!(
            m["angle_distortion_deg"]["max"].as_f64().unwrap() < 1e-9,
            "{m}"
        );
        assert!(
            m["circle_residual_max"].as_f64().unwrap_or(0.0) < 1e-12,
            "{m}"
        );
    }
}

#[test]
fn batch_input_listed_twice_is_named_so() {
    let d = tmpdir("twice");
    let woody = fixture("woody.obj");
    let o = conformap(&[
        "batch",
        "--command",
        "disk",
        "--out-dir",
        s(&d),
        s(&woody),
        s(&woody),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("is listed twice"), "{}", stderr(&o));
}

#[test]
fn a_file_where_a_directory_is_expected_is_named() {
    let d = tmpdir("file-dir");
    let file = d.join("file.obj");
    std::fs::write(&file, "x").unwrap();
    let out = file.join("x.obj");
    let o = conformap(&["disk", s(&fixture("woody.obj")), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("is a file, not a directory"),
        "{}",
        stderr(&o)
    );
}

/// Runs `args` expecting exit `code`; returns stderr.
fn fails(args: &[&str], code: i32) -> String {
    let o = conformap(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{args:?}: {err}");
    err
}

#[test]
fn option_messages_name_the_flags_typed() {
    let d = tmpdir("flags");
    let out = d.join("o.obj");
    // an internal option name never reaches the user
    let err = fails(
        &[
            "disk",
            s(&fixture("halftunnel.obj")),
            "-o",
            s(&out),
            "--max-iter",
            "0",
        ],
        2,
    );
    assert!(
        err.contains("--max-iter") && !err.contains("max_sweeps"),
        "{err}"
    );
    let png = d.join("r.png");
    let woody = fixture("woody.obj");
    conformap_ok(&["disk", s(&woody), "-o", s(&out), "-q"]);
    let err = fails(
        &[
            "render",
            s(&woody),
            s(&out),
            "-o",
            s(&png),
            "--azimuth",
            "nan",
        ],
        2,
    );
    assert!(
        err.contains("--azimuth") && !err.contains("azimuth_deg"),
        "{err}"
    );
    // --form out of range: a usage error with the number given
    let err = fails(
        &[
            "global",
            s(&fixture("eightsim.obj")),
            "-o",
            s(&out),
            "--form",
            "99",
        ],
        2,
    );
    assert!(err.contains("--form 99"), "{err}");
    // a limit below a KiB is printed in bytes, not as "0 KiB"
    let err = fails(&["disk", s(&woody), "-o", s(&out), "--max-memory", "1"], 1);
    assert!(
        err.contains("1 B allowed") && !err.contains("0 KiB"),
        "{err}"
    );
    // a negative value is refused by the flag's own check, with no tip about `-- -1`
    let err = fails(&["disk", s(&woody), "-o", s(&out), "--max-iter", "-1"], 2);
    assert!(
        err.contains("--max-iter") && !err.contains("'-- -1'"),
        "{err}"
    );
}

#[test]
fn ignored_options_are_said_on_stderr_and_in_the_report() {
    let d = tmpdir("ignored");
    let (out, report) = (d.join("o.obj"), d.join("r.json"));
    let cases: [(&str, &[&str], &str); 4] = [
        (
            "halftunnel.obj",
            &["--method", "harmonic"],
            "--method harmonic",
        ),
        ("halftunnel.obj", &["--ordering", "nd"], "--ordering"),
        ("woody.obj", &["--keep-folds"], "--keep-folds"),
        (
            "woody.obj",
            &["--method", "harmonic", "--max-iter", "5"],
            "--max-iter",
        ),
    ];
    for (mesh, extra, needle) in cases {
        let mesh_path = fixture(mesh);
        let mut argv = vec!["disk", s(&mesh_path), "-o", s(&out), "--report", s(&report)];
        argv.extend(extra);
        let o = conformap(&argv);
        assert!(o.status.success(), "{argv:?}: {}", stderr(&o));
        assert!(
            stderr(&o).contains("ignored: ") && stderr(&o).contains(needle),
            "{}",
            stderr(&o)
        );
        let listed = json(&report)["solver"]["ignored_options"].to_string();
        assert!(listed.contains(needle), "{listed}");
    }
    // render: a colour the histogram does not draw is refused
    let png = d.join("h.svg");
    conformap_ok(&["disk", s(&fixture("woody.obj")), "-o", s(&out), "-q"]);
    let err = fails(
        &[
            "render",
            s(&fixture("woody.obj")),
            s(&out),
            "-o",
            s(&png),
            "--view",
            "histogram",
            "--color",
            "beltrami",
        ],
        2,
    );
    assert!(err.contains("--color beltrami"), "{err}");
}

#[test]
fn every_map_command_help_says_how_the_map_becomes_texture_coordinates() {
    for command in ["disk", "sphere", "mobius", "global", "flatten", "atlas"] {
        let o = conformap_ok(&[command, "--help"]);
        let help = String::from_utf8_lossy(&o.stdout);
        assert!(
            help.contains("Texture coordinates (-o):"),
            "{command}:\n{help}"
        );
        assert!(
            help.contains("Texture coordinates\" at the end"),
            "{command}:\n{help}"
        );
    }
}

#[test]
fn triangle_soup_prediction_is_the_repair() {
    let d = tmpdir("soup");
    let text = std::fs::read_to_string(fixture("woody.obj")).unwrap();
    let v: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
    let mut soup = String::new();
    let mut k = 0;
    for f in text.lines().filter(|l| l.starts_with("f ")) {
        for i in f.split_whitespace().skip(1) {
            soup.push_str(v[i.parse::<usize>().unwrap() - 1]);
            soup.push('\n');
        }
        soup.push_str(&format!("f {} {} {}\n", k + 1, k + 2, k + 3));
        k += 3;
    }
    let path = d.join("soup.obj");
    std::fs::write(&path, soup).unwrap();
    let out = d.join("o.obj");
    let err = fails(&["disk", s(&path), "-o", s(&out)], 1);
    assert!(
        err.contains("coincident vertices") && !err.contains("dropped"),
        "{err}"
    );
    let info =
        String::from_utf8_lossy(&conformap_ok(&["info", s(&path), "--json"]).stdout).to_string();
    let info: serde_json::Value = serde_json::from_str(&info).unwrap();
    let predicted = info["repairs_available"].to_string();
    assert!(
        predicted.contains("coincident") && !predicted.contains("dropped"),
        "{predicted}"
    );
    let report = d.join("r.json");
    conformap_ok(&[
        "disk",
        s(&path),
        "--repair",
        "-o",
        s(&out),
        "--report",
        s(&report),
        "-q",
    ]);
    assert_eq!(json(&report)["input"]["faces"], 1267);
}

#[test]
fn batch_summary_names_inputs_stopped_at_the_cap() {
    let d = tmpdir("cap");
    let woody = fixture("woody.obj");
    let o = conformap(&[
        "batch",
        "--command",
        "disk",
        "--out-dir",
        s(&d),
        s(&woody),
        "--",
        "--method",
        "ccem",
        "--max-iter",
        "2",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // the input's line says it (converged: false); the summary JSON line keeps its keys
    // (examples/python/cohort.py writes the same), the stderr summary names the input
    let stdout = String::from_utf8_lossy(&o.stdout).to_string();
    let line: serde_json::Value = serde_json::from_str(stdout.lines().next().unwrap()).unwrap();
    assert_eq!(line["converged"], false, "{line}");
    let err = stderr(&o);
    let last = err.lines().last().unwrap_or_default();
    assert!(
        last.contains(&format!("(not converged): {}", s(&woody))),
        "{last}"
    );
    assert!(
        stderr(&o).contains("stopped at the iteration cap"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_duplicated_vertex_that_splits_a_fan_is_hinted_to_repair() {
    // woody with vertex 2 (1-based) copied to a new last line, every other face around it
    // using the copy: the copy's faces form two fans (non-manifold), welding undoes it
    let d = tmpdir("dup-vertex");
    let text = std::fs::read_to_string(fixture("woody.obj")).unwrap();
    let v: Vec<&str> = text.lines().filter(|l| l.starts_with("v ")).collect();
    let copy = v.len() + 1;
    let mut out: String = v.iter().map(|l| format!("{l}\n")).collect();
    out.push_str(v[1]);
    out.push('\n');
    let mut around = 0;
    for f in text.lines().filter(|l| l.starts_with("f ")) {
        let c: Vec<usize> = f
            .split_whitespace()
            .skip(1)
            .map(|i| i.split('/').next().unwrap().parse().unwrap())
            .collect();
        let c = if c.contains(&2) {
            around += 1;
            let moved = around % 2 == 1;
            c.iter()
                .map(|&i| if i == 2 && moved { copy } else { i })
                .collect()
        } else {
            c
        };
        out.push_str(&format!("f {} {} {}\n", c[0], c[1], c[2]));
    }
    let path = d.join("dup.obj");
    std::fs::write(&path, out).unwrap();
    let o = d.join("o.obj");
    let err = fails(&["disk", s(&path), "-o", s(&o)], 1);
    assert!(err.contains("non-manifold"), "{err}");
    assert!(
        err.contains("rerun with --repair: it welds 1 coincident"),
        "{err}"
    );
    assert!(!err.contains("no automatic repair is safe"), "{err}");
    assert!(!o.exists());
    let report = d.join("r.json");
    conformap_ok(&[
        "disk",
        s(&path),
        "--repair",
        "-o",
        s(&o),
        "--report",
        s(&report),
        "-q",
    ]);
    let r = json(&report);
    assert_eq!(r["input"]["faces"], 1267);
    assert_eq!(r["input"]["vertices"], 694, "{}", r["input"]);
}
