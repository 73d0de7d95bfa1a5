//! End-to-end runs of `conformap flatten` on the fixtures: the free boundary (lengths kept,
//! no fold), a rectangle of a given aspect with four right angles, a given boundary scale,
//! boundary files with their errors, topology refusals that name the command to use, and
//! `batch --command flatten`.

mod support;

use support::*;

fn read_vt(path: &std::path::Path) -> Vec<[f64; 2]> {
    std::fs::read_to_string(path)
        .expect("read output")
        .lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("number"))
                .collect();
            [v[0], v[1]]
        })
        .collect()
}

#[test]
fn free_boundary_of_spothead_keeps_its_lengths_and_folds_nothing() {
    let d = tmpdir("flatten-free");
    let (out, flat, rep) = (d.join("uv.obj"), d.join("flat.obj"), d.join("r.json"));
    conformap_ok(&[
        "flatten",
        s(&fixture("spothead.obj")),
        "-o",
        s(&out),
        "--flat",
        s(&flat),
        "--report",
        s(&rep),
    ]);
    let r = json(&rep);
    assert_eq!(r["command"], "flatten");
    assert_eq!(r["method"], "bff-free");
    let f = &r["flatten"];
    assert_eq!(f["boundary"], "free");
    assert_eq!(f["overlap_free"], true);
    assert_eq!(r["metrics"]["flipped_faces"], 0);
    assert!(f["closure_residual"].as_f64().expect("number") < 1e-12);
    // u = 0 on the boundary: the lengths are kept (only the closing touches them)
    assert_eq!(f["boundary_u_min"], 0.0);
    assert_eq!(f["boundary_u_max"], 0.0);
    assert!(f["closure_max_length_change"].as_f64().expect("number") < 1e-3);
    assert_eq!(r["solver"]["converged"], true);
    // one vt per vertex, the layout's box scaled into the unit square
    let vt = read_vt(&out);
    assert_eq!(vt.len(), 4537);
    assert!(vt
        .iter()
        .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
    assert!(vt.iter().any(|p| p[0] == 0.0) && vt.iter().any(|p| p[1] == 0.0));
    // the flat mesh is the raw layout: metrics judges it as flatten did
    let m = &metrics_json(&fixture("spothead.obj"), &flat)["metrics"];
    assert_eq!(m["flipped_faces"], 0);
    let spread = r["metrics"]["area_distortion_log"]["sd"]
        .as_f64()
        .expect("number");
    assert!((m["area_distortion_log"]["sd"].as_f64().expect("number") - spread).abs() < 1e-9);
}

#[test]
fn a_rectangle_of_aspect_two_has_four_right_angles_and_that_aspect() {
    let d = tmpdir("flatten-rect");
    let (out, rep) = (d.join("uv.obj"), d.join("r.json"));
    conformap_ok(&[
        "flatten",
        s(&fixture("spothead.obj")),
        "-o",
        s(&out),
        "--boundary",
        "rectangle",
        "--aspect",
        "2/1",
        "--report",
        s(&rep),
    ]);
    let r = json(&rep);
    let f = &r["flatten"];
    assert_eq!(f["boundary"], "rectangle");
    assert_eq!(f["corners"].as_array().expect("corners").len(), 4);
    assert!((f["aspect"].as_f64().expect("aspect") - 2.0).abs() < 1e-12);
    assert!(f["aspect_dilatation"].as_f64().expect("dilatation") >= 1.0);
    assert_eq!(r["metrics"]["flipped_faces"], 0);
    // the texture is the rectangle: its box fills u ∈ [0, 1], v ∈ [0, ½]
    let vt = read_vt(&out);
    let max_v = vt.iter().map(|p| p[1]).fold(0.0, f64::max);
    assert!((max_v - 0.5).abs() < 1e-9, "{max_v}");
}

#[test]
fn a_given_constant_scale_only_scales_the_free_boundary() {
    let d = tmpdir("flatten-scale");
    let mesh = conformap_io::read_mesh(fixture("woody.obj"))
        .expect("fixture")
        .mesh;
    let lines: String = mesh.boundary_loops()[0]
        .iter()
        .map(|v| format!("{v} 0.25\n"))
        .collect();
    let file = d.join("scale.txt");
    std::fs::write(&file, lines).expect("write");
    let (free, scaled) = (d.join("free.json"), d.join("scaled.json"));
    let spec = format!("scale:{}", s(&file));
    conformap_ok(&[
        "flatten",
        s(&fixture("woody.obj")),
        "-o",
        s(&d.join("a.obj")),
        "--report",
        s(&free),
    ]);
    conformap_ok(&[
        "flatten",
        s(&fixture("woody.obj")),
        "-o",
        s(&d.join("b.obj")),
        "--boundary",
        &spec,
        "--report",
        s(&scaled),
    ]);
    let (a, b) = (json(&free), json(&scaled));
    assert_eq!(b["flatten"]["boundary"], "scale");
    assert_eq!(b["flatten"]["boundary_u_min"], 0.25);
    // a constant u is a similarity: the same angles and the same area spread
    for key in [
        ("angle_distortion_deg", "mean"),
        ("area_distortion_log", "sd"),
    ] {
        let (x, y) = (
            a["metrics"][key.0][key.1].as_f64().expect("number"),
            b["metrics"][key.0][key.1].as_f64().expect("number"),
        );
        assert!((x - y).abs() < 1e-9, "{key:?}: {x} vs {y}");
    }
}

/// `conformap flatten woody.obj -o OUT EXTRA…`, expected to fail with `code` and a message
/// holding `needle`; returns its stderr.
fn flatten_fails(out: &std::path::Path, extra: &[&str], code: i32, needle: &str) -> String {
    let mesh = fixture("woody.obj");
    let mut args = vec!["flatten", s(&mesh), "-o", s(out)];
    args.extend_from_slice(extra);
    let o = conformap(&args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(code), "{extra:?}: {err}");
    assert!(err.contains(needle), "{extra:?}: `{needle}` not in {err}");
    assert!(!out.exists(), "{extra:?}: nothing written on error");
    err
}

#[test]
fn bad_boundaries_and_topologies_are_refused_with_what_to_do() {
    let d = tmpdir("flatten-bad");
    let out = d.join("uv.obj");
    // corners or an aspect without a rectangle, an unknown boundary: usage
    flatten_fails(&out, &["--corners", "1,2,3,4"], 2, "--boundary rectangle");
    flatten_fails(
        &out,
        &["--boundary", "rectangle", "--aspect=-1"],
        2,
        "aspect",
    );
    flatten_fails(&out, &["--boundary", "square"], 2, "square");
    // a missing boundary file: bad input with a hint
    let missing = format!("polygon:{}", s(&d.join("none.txt")));
    let err = flatten_fails(&out, &["--boundary", &missing], 1, "none.txt");
    assert!(err.lines().any(|l| l.starts_with("hint:")), "{err}");
    // a polygon file with a bad line: the file and its line, the hint on its own line
    let bad = d.join("bad.txt");
    std::fs::write(&bad, "0 120\n17 x\n").expect("write");
    let spec = format!("polygon:{}", s(&bad));
    let err = flatten_fails(&out, &["--boundary", &spec], 1, "bad.txt:2:");
    assert!(err.lines().any(|l| l.starts_with("hint:")), "{err}");
    // a closed surface: the hint names `conformap sphere`; genus 2: `conformap global`
    for (mesh, command) in [
        ("spot.obj", "conformap sphere"),
        ("eightsim.obj", "conformap global"),
    ] {
        let o = conformap(&["flatten", s(&fixture(mesh)), "-o", s(&out)]);
        assert_eq!(o.status.code(), Some(1));
        assert!(stderr(&o).contains(command), "{}", stderr(&o));
    }
    assert!(!out.exists(), "nothing written on error");
}

#[test]
fn batch_runs_flatten_as_the_single_command_does() {
    let d = tmpdir("flatten-batch");
    let dir = d.join("out");
    conformap_ok(&[
        "batch",
        "--command",
        "flatten",
        "--out-dir",
        s(&dir),
        s(&fixture("woody.obj")),
        s(&fixture("halftunnel.obj")),
    ]);
    let single = d.join("woody.obj");
    conformap_ok(&["flatten", s(&fixture("woody.obj")), "-o", s(&single)]);
    assert_eq!(
        std::fs::read(dir.join("woody.obj")).expect("batch output"),
        std::fs::read(&single).expect("single output")
    );
    // the holed surface: its holes filled and left free
    let r = json(&dir.join("halftunnel.json"));
    assert_eq!(r["flatten"]["filled_holes"], 2);
    assert_eq!(r["metrics"]["flipped_faces"], 0);
}
