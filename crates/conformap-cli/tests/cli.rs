//! End-to-end runs of the `conformap` binary on the fixtures.

mod support;

use support::{conformap, fixture, map_report, metrics_json, s, stderr, tmpdir};

#[test]
fn disk_maps_spothead_and_metrics_agree_with_the_report() {
    let d = tmpdir("spothead");
    let (out, flat, rep) = (d.join("uv.obj"), d.join("flat.obj"), d.join("r.json"));
    let r = map_report(
        &["disk", s(&fixture("spothead.obj"))],
        &out,
        Some(&flat),
        &rep,
    );
    assert_eq!(r["command"], "disk");
    assert_eq!(r["method"], "ccem-qn");
    assert_eq!(r["input"]["vertices"], 4537);
    assert_eq!(r["input"]["boundaries"], 1);
    let m = &r["metrics"];
    let ec = m["conformal_energy"].as_f64().unwrap();
    // CCEM-QN on spothead: 0.01265; CEM 0.01303; the arc-length harmonic map: 0.0202;
    // best other tool 0.0130
    assert!(ec <= 0.0130, "E_C {ec}");
    assert_eq!(m["flipped_faces"], 0);
    assert!(m["circle_residual_max"].as_f64().unwrap() < 1e-12);
    let history = r["solver"]["energy_history"].as_array().unwrap();
    let best = r["solver"]["best_iteration"].as_u64().unwrap() as usize;
    let min = history
        .iter()
        .map(|v| v.as_f64().unwrap())
        .fold(f64::INFINITY, f64::min);
    assert_eq!(history[best].as_f64().unwrap(), min);
    assert!(
        (ec - min).abs() <= 1e-9 * min,
        "report E_C {ec} vs solver {min}"
    );
    for key in [
        "read", "assemble", "factor", "solve", "metrics", "write", "total",
    ] {
        assert!(
            r["timings_ms"][key].as_f64().unwrap() >= 0.0,
            "timing {key}"
        );
    }
    // the bench's `analyse` stage is part of `factor`
    let t = &r["timings_ms"];
    let analyse = t["analyse"].as_f64().unwrap();
    assert!(analyse > 0.0 && analyse <= t["factor"].as_f64().unwrap());
    // judge the written files: both agree with the report to 1e-9 relative
    for param in [&out, &flat] {
        let v = metrics_json(&fixture("spothead.obj"), param);
        let e = v["metrics"]["conformal_energy"].as_f64().unwrap();
        assert!(
            (e - ec).abs() <= 1e-9 * ec,
            "{}: {e} vs {ec}",
            param.display()
        );
    }
}

#[test]
fn methods_rank_as_expected_on_woody() {
    let d = tmpdir("methods");
    let (out, rep) = (d.join("h.obj"), d.join("h.json"));
    let mut ec = std::collections::BTreeMap::new();
    for method in ["harmonic", "cem", "ccem", "ccem-qn"] {
        let r = map_report(
            &["disk", s(&fixture("woody.obj")), "--method", method],
            &out,
            None,
            &rep,
        );
        assert_eq!(r["method"], method);
        assert_eq!(r["metrics"]["flipped_faces"], 0, "{method}");
        ec.insert(method, r["metrics"]["conformal_energy"].as_f64().unwrap());
    }
    // woody: harmonic 1.237, CEM 0.0691, CCEM 0.0624, CCEM-QN 0.0615 (best other tool 0.0670)
    assert!(ec["cem"] < ec["harmonic"] / 10.0, "{ec:?}");
    assert!(ec["cem"] <= 0.0670 * 1.10, "{ec:?}");
    assert!(
        ec["ccem"] < ec["cem"] && ec["ccem-qn"] <= ec["ccem"] * (1.0 + 1e-9),
        "{ec:?}"
    );
    assert!(ec["ccem-qn"] <= 0.0670, "{ec:?}");
}

#[test]
fn wrong_topology_is_bad_input_and_writes_nothing() {
    let d = tmpdir("torus");
    let out = d.join("t.obj");
    let o = conformap(&["disk", s(&fixture("punctured_torus.obj")), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(
        err.contains("genus 1") && err.contains("1 boundary loop"),
        "{err}"
    );
    assert!(!out.exists());
    let o = conformap(&["disk", s(&fixture("spot.obj")), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("closed genus-0"));
    assert!(!out.exists());
    // several boundary loops are no longer refused: the disk with circular holes
    let rep = d.join("h.json");
    let r = map_report(&["disk", s(&fixture("halftunnel.obj"))], &out, None, &rep);
    assert!(out.exists());
    assert_eq!(r["method"], "koebe");
    assert!(r["metrics"]["circle_residual_max"].as_f64().unwrap() < 1e-6);
}

#[test]
fn several_loops_map_onto_a_disk_with_circular_holes() {
    let d = tmpdir("holes");
    let (out, flat, rep) = (d.join("uv.obj"), d.join("flat.obj"), d.join("r.json"));
    let halftunnel = fixture("halftunnel.obj");
    let r = map_report(&["disk", s(&halftunnel)], &out, Some(&flat), &rep);
    assert_eq!(r["input"]["boundaries"], 3);
    let solver = &r["solver"];
    assert_eq!(solver["converged"], true);
    assert!(solver["iterations"].as_u64().unwrap() >= 1);
    let history = solver["residual_history"].as_array().unwrap();
    assert_eq!(history.len() as u64, solver["sweeps"].as_u64().unwrap() + 1);
    assert!(solver["step_history"].as_array().unwrap().len() >= 3);
    assert!(solver["polish"]["energy_history"].as_array().unwrap().len() >= 2);
    // every loop on its circle; the outer one (the longest, 48 vertices) the unit circle
    let domain = &r["circle_domain"];
    assert_eq!(domain["outer_loop"], 0);
    assert!(domain["modulus"].is_null());
    let circles = domain["circles"].as_array().unwrap();
    assert_eq!(circles.len(), 3);
    for c in circles {
        assert!(c["residual_max"].as_f64().unwrap() < 1e-6, "{c}");
        assert!(c["radius"].as_f64().unwrap() > 0.0);
    }
    assert_eq!(circles[0]["outer"], true);
    assert_eq!(circles[0]["vertices"], 48);
    let m = &r["metrics"];
    assert!(m["circle_residual_max"].as_f64().unwrap() < 1e-6);
    assert!(m["conformal_energy"].as_f64().unwrap() > 0.0);
    assert!(m["angle_distortion_deg"]["mean"].as_f64().unwrap() > 0.0);
    // the metrics command agrees on the flat mesh (the outer loop given explicitly)
    metrics_json(&halftunnel, &flat);
    // --outer picks another loop; a loop that does not exist is a usage error
    let rep2 = d.join("r2.json");
    let r2 = map_report(&["disk", s(&halftunnel), "--outer", "2"], &out, None, &rep2);
    assert_eq!(r2["circle_domain"]["outer_loop"], 2);
    assert_eq!(r2["circle_domain"]["circles"][2]["outer"], true);
    let o = conformap(&["disk", s(&halftunnel), "-o", s(&out), "--outer", "3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--outer 3"));
}

#[test]
fn broken_files_name_the_line_and_write_nothing() {
    let d = tmpdir("bad");
    let out = d.join("o.obj");
    for (file, needle) in [
        (
            "bad/nan_coordinate.obj",
            "nan_coordinate.obj:3: vertex 1 has a non-finite coordinate",
        ),
        ("bad/bad_number.obj", "bad_number.obj:3:"),
        (
            "bad/index_out_of_range.obj",
            "index_out_of_range.obj:5: vertex index 4 is out of range",
        ),
        ("bad/index_zero.obj", "index_zero.obj:5:"),
        ("bad/too_few_corners.obj", "too_few_corners.obj:5:"),
        (
            "bad/degenerate_face.obj",
            "degenerate_face.obj:7: face 1 is degenerate",
        ),
        (
            "bad/duplicate_face.obj",
            "duplicate_face.obj:6: face 1 duplicates face 0",
        ),
        (
            "bad/unreferenced_vertex.obj",
            "unreferenced_vertex.obj:4: vertex 2 is not used",
        ),
        (
            "bad/nonmanifold_edge.obj",
            "nonmanifold_edge.obj:9: edge (0, 1) is non-manifold",
        ),
        (
            "bad/bowtie_vertex.obj",
            "bowtie_vertex.obj:2: vertex 0 is non-manifold",
        ),
        (
            "bad/inconsistent_orientation.obj",
            "inconsistent_orientation.obj:7: faces 1 and 0",
        ),
        ("bad/empty.obj", "empty.obj: the mesh has no vertices"),
        (
            "bad/no_faces.obj",
            "no_faces.obj: the mesh has 3 vertices but no faces",
        ),
        ("bad/garbage_line.obj", "garbage_line.obj:4:"),
    ] {
        let o = conformap(&["disk", s(&fixture(file)), "-o", s(&out)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{file}: {err}");
        assert!(
            err.contains(needle),
            "{file}: expected `{needle}` in: {err}"
        );
        assert!(!err.contains("panicked"), "{file}: {err}");
        assert!(!out.exists(), "{file} left an output");
    }
    let o = conformap(&["disk", s(&d.join("missing.obj")), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn usage_errors_exit_2() {
    let d = tmpdir("usage");
    let o = conformap(&["disk", s(&fixture("woody.obj")), "-o", s(&d.join("o.stl"))]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = conformap(&["disk", s(&fixture("woody.obj"))]);
    assert_eq!(o.status.code(), Some(2));
    let o = conformap(&[
        "disk",
        s(&fixture("woody.obj")),
        "-o",
        s(&d.join("o.obj")),
        "--tol",
        "nan",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!d.join("o.obj").exists());
}

#[test]
fn strict_without_convergence_exits_3_and_writes_nothing() {
    let d = tmpdir("strict");
    let out = d.join("o.obj");
    let o = conformap(&[
        "disk",
        s(&fixture("woody.obj")),
        "-o",
        s(&out),
        "--max-iter",
        "1",
        "--strict",
    ]);
    assert_eq!(o.status.code(), Some(3), "{}", stderr(&o));
    assert!(!out.exists());
}

/// A run stopped by the iteration cap says so on its summary line, with the option that
/// raises the cap (and, for the plain gradient method, the default that converges).
#[test]
fn the_summary_says_when_the_iteration_cap_stopped_the_run() {
    let d = tmpdir("cap");
    let out = d.join("o.obj");
    let run = |method: &str| {
        let o = conformap(&[
            "disk",
            s(&fixture("woody.obj")),
            "-o",
            s(&out),
            "--method",
            method,
            "--max-iter",
            "3",
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        stderr(&o)
    };
    let e = run("ccem");
    assert!(
        e.contains("ccem in 3 iterations (stopped at the iteration cap: --max-iter raises it; the default ccem-qn"),
        "{e}"
    );
    let e = run("ccem-qn");
    assert!(
        e.contains("(stopped at the iteration cap: --max-iter raises it)"),
        "{e}"
    );
}

#[test]
fn gltf_and_glb_outputs_round_trip_through_metrics() {
    let d = tmpdir("gltf");
    let rep = d.join("r.json");
    for ext in ["glb", "gltf"] {
        let out = d.join(format!("o.{ext}"));
        let woody = fixture("woody.obj");
        let r = map_report(&["disk", s(&woody)], &out, None, &rep);
        let ec = r["metrics"]["conformal_energy"].as_f64().unwrap();
        let e = metrics_json(&woody, &out)["metrics"]["conformal_energy"]
            .as_f64()
            .unwrap();
        // glTF stores texture coordinates as f32
        assert!((e - ec).abs() < 1e-4 * ec.max(1e-3), "{ext}: {e} vs {ec}");
    }
}

#[test]
fn info_reports_topology() {
    let o = conformap(&["info", s(&fixture("halftunnel.obj")), "--json"]);
    assert!(o.status.success());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["vertices"], 831);
    assert_eq!(v["boundaries"], 3);
    assert_eq!(v["genus"], 0);
    let mut sizes: Vec<u64> = v["boundary_loop_sizes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_u64().unwrap())
        .collect();
    sizes.sort_unstable();
    assert_eq!(sizes, vec![16, 32, 48]);
    let o = conformap(&["info", s(&fixture("punctured_torus.obj"))]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("genus 1"));
}

#[test]
fn orderings_give_the_same_map() {
    // the ordering of the factorization changes its cost, not the map: the same E_C to
    // 1e-9 relative and the same iterations on spothead (4.5k vertices, 48 on the
    // boundary); `auto` is AMD at this size and the report says which ran
    let d = tmpdir("orderings");
    let mut runs = Vec::new();
    for ordering in ["auto", "amd", "nd"] {
        let (out, rep) = (
            d.join(format!("{ordering}.obj")),
            d.join(format!("{ordering}.json")),
        );
        let spothead = fixture("spothead.obj");
        let args = ["disk", s(&spothead), "--ordering", ordering];
        let r = map_report(&args, &out, None, &rep);
        runs.push((
            r["factorization"]["ordering"].as_str().unwrap().to_string(),
            r["metrics"]["conformal_energy"].as_f64().unwrap(),
            r["solver"]["iterations"].as_u64().unwrap(),
            r["metrics"]["flipped_faces"].as_u64().unwrap(),
        ));
    }
    assert_eq!(runs[0].0, "amd");
    assert_eq!(runs[1].0, "amd");
    assert_eq!(runs[2].0, "nested-dissection");
    for (name, e, its, flipped) in &runs {
        assert!(
            (e - runs[1].1).abs() <= 1e-9 * runs[1].1,
            "{name}: E_C {e} vs {}",
            runs[1].1
        );
        assert_eq!(*its, runs[1].2, "{name}");
        assert_eq!(*flipped, 0, "{name}");
    }
    let o = conformap(&[
        "disk",
        s(&fixture("spothead.obj")),
        "-o",
        "x.obj",
        "--ordering",
        "metis",
    ]);
    assert_eq!(
        o.status.code(),
        Some(2),
        "an unknown ordering is a usage error"
    );
}
