//! End-to-end runs of `conformap sphere` and `conformap mobius` on the fixtures.

mod support;

use support::{conformap, conformap_ok, fixture, json, map_report, mobius, s, stderr, tmpdir};

#[test]
fn sphere_then_mobius_on_spot() {
    let d = tmpdir("spot");
    let (out, flat, rep) = (d.join("uv.obj"), d.join("sphere.obj"), d.join("r.json"));
    let spot = fixture("spot.obj");
    let args = ["sphere", s(&spot), "--mobius", "uniform"];
    let r = map_report(&args, &out, Some(&flat), &rep);
    for key in [
        "conformap_version",
        "command",
        "method",
        "input",
        "solver",
        "metrics",
        "timings_ms",
    ] {
        assert!(r.get(key).is_some(), "report lacks {key}");
    }
    assert_eq!(r["command"], "sphere");
    assert_eq!(r["input"]["vertices"], 2930);
    let m = &r["metrics"];
    assert_eq!(m["flipped_faces"], 0);
    assert!(m["radius_residual_max"].as_f64().unwrap() <= 1e-12);
    assert!(m["angle_distortion_deg"]["mean"].as_f64().unwrap() < 3.1);
    let (before, after) = (
        m["uniformity_energy_before_mobius"].as_f64().unwrap(),
        m["uniformity_energy"].as_f64().unwrap(),
    );
    assert!(after < before);
    // the flat output is the sphere map: every point on the unit sphere
    let text = std::fs::read_to_string(&flat).unwrap();
    for line in text.lines().filter(|l| l.starts_with("v ")) {
        let v: Vec<f64> = line[2..]
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        assert!(((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 1.0).abs() <= 1e-12);
    }

    // emphasize the faces listed in a region file
    let region = d.join("region.txt");
    let faces: String = (0..5856)
        .filter(|f| f % 2 == 0)
        .map(|f| format!("{f}\n"))
        .collect();
    std::fs::write(&region, format!("# every other face\n{faces}")).unwrap();
    let (out2, rep2) = (d.join("emph.obj"), d.join("e.json"));
    let o = mobius(
        &spot,
        &flat,
        "sphere",
        "emphasize",
        &["--region", s(&region), "--report", s(&rep2)],
        &out2,
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let e = json(&rep2);
    assert_eq!(e["command"], "mobius");
    let mob = &e["solver"]["mobius"];
    assert!(
        mob["region_share_after"].as_f64().unwrap() >= mob["region_share_before"].as_f64().unwrap()
    );
    // the sphere map may also be given as its equirectangular texture coordinates
    let o = mobius(&spot, &out, "sphere", "uniform", &[], &d.join("u.obj"));
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn bad_inputs_and_usage() {
    let d = tmpdir("bad");
    let out = d.join("o.obj");
    // a disk is not a sphere: exit 1, naming the file
    let o = conformap(&["sphere", s(&fixture("woody.obj")), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("woody.obj"));
    assert!(!out.exists(), "nothing is written on failure");
    // a region index out of range: exit 1, naming the file and line
    let region = d.join("r.txt");
    std::fs::write(&region, "0\n1\n99999\n").unwrap();
    let spot = fixture("spot.obj");
    let o = mobius(
        &spot,
        &spot,
        "sphere",
        "emphasize",
        &["--region", s(&region)],
        &out,
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("r.txt line 3"), "{}", stderr(&o));
    // emphasize without a region: usage, exit 2
    let o = mobius(&spot, &spot, "sphere", "emphasize", &[], &out);
    assert_eq!(o.status.code(), Some(2));
    // the mesh itself is no sphere map
    let o = mobius(&spot, &spot, "sphere", "uniform", &[], &out);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn disk_mobius_of_a_cem_map() {
    let d = tmpdir("disk");
    let (uv, out, rep) = (d.join("uv.obj"), d.join("m.obj"), d.join("m.json"));
    let woody = fixture("woody.obj");
    conformap_ok(&["disk", s(&woody), "-o", s(&uv)]);
    let o = mobius(&woody, &uv, "disk", "uniform", &["--report", s(&rep)], &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let m = &json(&rep)["metrics"];
    assert!(
        m["uniformity_energy"].as_f64().unwrap() < m["uniformity_energy_before"].as_f64().unwrap()
    );
    assert_eq!(m["flipped_faces"], 0);
    let cr = (
        m["cross_ratio_log_before"]["mean_abs"].as_f64().unwrap(),
        m["cross_ratio_log"]["mean_abs"].as_f64().unwrap(),
    );
    // vt stored with 17 digits: the cross-ratios survive the file round trip to ~1e-12
    assert!((cr.0 - cr.1).abs() < 1e-9, "{cr:?}");
}

#[test]
fn mobius_reads_a_crowded_flat_map_and_keeps_it_flip_free() {
    // alligator's default disk map holds boundary gaps at the 1e-13 floor: its flat mesh
    // has triangles of area 1e-28, which a 3D mesh reader refuses as degenerate; as a map
    // it is valid, and `mobius` must take it (as `metrics` does) and add no inverted face
    let d = tmpdir("crowded");
    let (uv, flat) = (d.join("uv.obj"), d.join("flat.obj"));
    let mesh = fixture("alligator.obj");
    conformap_ok(&["disk", s(&mesh), "-o", s(&uv), "--flat", s(&flat)]);
    let info = conformap(&["info", s(&flat)]);
    assert_eq!(
        info.status.code(),
        Some(1),
        "the flat mesh is degenerate as a 3D mesh"
    );
    for param in [&flat, &uv] {
        let (out, rep) = (d.join("moved.obj"), d.join("r.json"));
        let o = mobius(
            &mesh,
            param,
            "disk",
            "uniform",
            &["--report", s(&rep)],
            &out,
        );
        assert!(o.status.success(), "{}: {}", param.display(), stderr(&o));
        let r = json(&rep);
        let m = &r["metrics"];
        assert_eq!(m["flipped_faces"], 0, "{}", param.display());
        let (before, after) = (
            m["uniformity_energy_before"].as_f64().expect("number"),
            m["uniformity_energy"].as_f64().expect("number"),
        );
        assert!(after < before, "{before} -> {after}");
    }
}
