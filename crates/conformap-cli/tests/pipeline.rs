//! The shared command pipeline through the binary: every output path checked before
//! anything is computed, all outputs or none, and the shared flags (`--repair`,
//! `--max-memory`, `--strict`) on every map command.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use support::{conformap, fixture, json, map_report, mobius, s, stderr, tmpdir};

#[test]
fn an_output_that_names_an_input_or_another_output_is_a_usage_error() {
    let d = tmpdir("pipeline-same");
    let mesh = d.join("woody.obj");
    std::fs::copy(fixture("woody.obj"), &mesh).unwrap();
    let before = std::fs::read(&mesh).unwrap();
    // -o = the input, also through another spelling of the same path
    let other = d.join(".").join("woody.obj");
    for out in [&mesh, &other] {
        let o = conformap(&["disk", s(&mesh), "-o", s(out)]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains("names the input file"),
            "{}",
            stderr(&o)
        );
    }
    assert_eq!(
        std::fs::read(&mesh).unwrap(),
        before,
        "the input was touched"
    );
    // --flat = -o, and --report = -o
    let out = d.join("uv.obj");
    for flag in ["--flat", "--report"] {
        let o = conformap(&["disk", s(&mesh), "-o", s(&out), flag, s(&out)]);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("-o and {flag} both name")),
            "{}",
            stderr(&o)
        );
        assert!(!out.exists());
    }
    // mobius: the output may not overwrite the map file it reads
    let uv = d.join("map.obj");
    assert!(conformap(&["disk", s(&mesh), "-o", s(&uv)])
        .status
        .success());
    let o = conformap(&[
        "mobius",
        s(&mesh),
        s(&uv),
        "--domain",
        "disk",
        "--objective",
        "uniform",
        "-o",
        s(&uv),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("names the input file"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_missing_report_directory_refuses_before_computing_and_writes_nothing() {
    let d = tmpdir("pipeline-missing");
    for cmd in [
        vec!["disk", "woody.obj"],
        vec!["sphere", "spot.obj"],
        vec!["disk", "halftunnel.obj"],
    ] {
        let out = d.join(format!("{}-{}", cmd[0], cmd[1]));
        let report = d.join("no-such-dir").join("r.json");
        let mesh = fixture(cmd[1]);
        let o = conformap(&[cmd[0], s(&mesh), "-o", s(&out), "--report", s(&report)]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains("does not exist") && err.contains("hint: "),
            "{err}"
        );
        assert!(!out.exists(), "{} wrote {}", cmd[0], out.display());
    }
    // and no staging file is left behind
    let left: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn sphere_and_mobius_take_repair_max_memory_and_report_real_convergence() {
    let d = tmpdir("pipeline-shared-flags");
    let (out, rep) = (d.join("s.obj"), d.join("s.json"));
    let spot = fixture("spot.obj");
    let o = conformap(&["sphere", s(&spot), "-o", s(&out), "--max-memory", "1M"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--max-memory"), "{}", stderr(&o));
    assert!(!out.exists());
    let args = ["sphere", s(&spot), "--repair", "--max-memory", "2G"];
    let r = map_report(&args, &out, None, &rep);
    assert_eq!(r["solver"]["converged"], true);
    assert!(r["solver"]["residual"].as_f64().unwrap() < 1e-12);
    assert_eq!(r["repairs"]["applied"].as_array().unwrap().len(), 0);
    assert_eq!(r["memory"]["limit_source"], "--max-memory");
    // mobius of that map: its residual is the gradient norm at the optimum, not a constant
    let (moved, mrep) = (d.join("m.obj"), d.join("m.json"));
    let extra = ["--report", s(&mrep), "--repair"];
    let o = mobius(&spot, &out, "sphere", "uniform", &extra, &moved);
    assert!(o.status.success(), "{}", stderr(&o));
    let m = json(&mrep);
    assert_eq!(m["solver"]["converged"], true);
    let g = m["solver"]["residual"].as_f64().unwrap();
    assert!(g.is_finite() && g < 1e-6, "gradient norm {g}");
    assert_eq!(
        m["solver"]["residual"],
        m["solver"]["mobius"]["gradient_norm"]
    );
}

#[test]
fn double_cover_is_a_disk_method() {
    let d = tmpdir("pipeline-double-cover");
    let (out, rep) = (d.join("dc.obj"), d.join("dc.json"));
    let spothead = fixture("spothead.obj");
    let args = ["disk", s(&spothead), "--method", "double-cover"];
    let r = map_report(&args, &out, None, &rep);
    assert_eq!(r["method"], "double-cover");
    let m = &r["metrics"];
    assert_eq!(m["flipped_faces"], 0);
    assert!(m["circle_residual_max"].as_f64().unwrap() < 1e-12);
    // a conformal map, without boundary optimization: measured E_C 0.01359 on spothead,
    // 7 % above the default method's 0.01265 and well below the harmonic map's 0.0202
    let ec = m["conformal_energy"].as_f64().unwrap();
    assert!(ec > 0.0126 && ec < 0.0140, "E_C {ec}");
    assert!(r["solver"]["detail"].is_null(), "the solver object is flat");
    assert!(r["solver"]["cover_vertices"].as_u64().unwrap() > 4537);
}

#[test]
fn the_default_method_falls_back_on_a_stretched_disk_and_strict_refuses_that() {
    let d = tmpdir("pipeline-stretched");
    // woody stretched 3× along x: valid, but CCEM's map would fold
    let text = std::fs::read_to_string(fixture("woody.obj")).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        match line.strip_prefix("v ") {
            Some(rest) => {
                let c: Vec<f64> = rest
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                out.push_str(&format!("v {} {} {}\n", 3.0 * c[0], c[1], c[2]));
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    let mesh = d.join("stretched.obj");
    std::fs::write(&mesh, out).unwrap();
    let (uv, rep) = (d.join("uv.obj"), d.join("r.json"));
    let o = conformap(&["disk", s(&mesh), "-o", s(&uv), "--report", s(&rep)]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("fallback: ccem-qn would fold"),
        "{}",
        stderr(&o)
    );
    let r = json(&rep);
    assert_eq!(r["solver"]["fallback_from"], "ccem-qn");
    assert_eq!(r["metrics"]["flipped_faces"], 0);
    assert!(
        r["method"] == "cem" || r["method"] == "harmonic",
        "{}",
        r["method"]
    );
    // --strict: the answer is not the method asked for
    let (uv2, rep2) = (d.join("uv2.obj"), d.join("r2.json"));
    let o = conformap(&[
        "disk",
        s(&mesh),
        "-o",
        s(&uv2),
        "--report",
        s(&rep2),
        "--strict",
    ]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(stderr(&o).contains("ccem-qn would fold"), "{}", stderr(&o));
    assert!(!uv2.exists() && !rep2.exists());
}

#[test]
fn an_obj_triangle_soup_is_welded_by_repair_as_gltf_is_on_reading() {
    let d = tmpdir("pipeline-soup");
    // woody as a triangle soup: every face with its own three vertices
    let text = std::fs::read_to_string(fixture("woody.obj")).unwrap();
    let mut v: Vec<&str> = Vec::new();
    let mut soup = String::new();
    let mut faces = String::new();
    let mut n = 0;
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("v ") {
            v.push(rest);
        } else if let Some(rest) = line.strip_prefix("f ") {
            for idx in rest.split_whitespace() {
                let i: usize = idx.split('/').next().unwrap().parse().unwrap();
                soup.push_str(&format!("v {}\n", v[i - 1]));
            }
            faces.push_str(&format!("f {} {} {}\n", n + 1, n + 2, n + 3));
            n += 3;
        }
    }
    let mesh = d.join("soup.obj");
    std::fs::write(&mesh, soup + &faces).unwrap();
    // info says so; a plain disk map refuses the many components
    let o = conformap(&["info", s(&mesh)]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout).to_string();
    assert!(out.contains("coincident vertices"), "{out}");
    let uv = d.join("uv.obj");
    let o = conformap(&["disk", s(&mesh), "-o", s(&uv)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!uv.exists());
    // --repair welds, then maps the same surface as woody's
    let rep = d.join("r.json");
    let o = conformap(&[
        "disk",
        s(&mesh),
        "--repair",
        "-o",
        s(&uv),
        "--report",
        s(&rep),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("coincident vertices welded"),
        "{}",
        stderr(&o)
    );
    let r = json(&rep);
    assert_eq!(r["input"]["vertices"], 694);
    let (wuv, wrep) = (d.join("w.obj"), d.join("w.json"));
    let w = map_report(&["disk", s(&fixture("woody.obj"))], &wuv, None, &wrep);
    let (a, b) = (
        r["metrics"]["conformal_energy"].as_f64().unwrap(),
        w["metrics"]["conformal_energy"].as_f64().unwrap(),
    );
    assert!((a - b).abs() < 1e-9 * b, "{a} vs {b}");
}
