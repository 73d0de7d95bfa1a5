//! End-to-end runs of `conformap atlas`: a closed genus-0 fixture through 8 cones, and a
//! file of two components (a disk and a closed surface), each packed into the unit square
//! with no flipped face and no texel covered twice.

mod support;

use support::*;

/// The `vt` lines and the faces' `vt` indices of an OBJ written by the atlas.
fn corners(path: &std::path::Path) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let text = std::fs::read_to_string(path).expect("read output");
    let vt = text
        .lines()
        .filter_map(|l| l.strip_prefix("vt "))
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("number"))
                .collect();
            [v[0], v[1]]
        })
        .collect();
    let faces = text
        .lines()
        .filter_map(|l| l.strip_prefix("f "))
        .map(|l| {
            let t: Vec<usize> = l
                .split_whitespace()
                .map(|c| {
                    c.split('/')
                        .nth(1)
                        .expect("v/vt")
                        .parse::<usize>()
                        .expect("index")
                        - 1
                })
                .collect();
            [t[0], t[1], t[2]]
        })
        .collect();
    (vt, faces)
}

fn check_atlas(report: &serde_json::Value, out: &std::path::Path, faces: usize) {
    check_atlas_spans(report, out, faces, 0.1);
}

/// [`check_atlas`] with no face spanning more than `max_span` of the texture in u or v.
fn check_atlas_spans(
    report: &serde_json::Value,
    out: &std::path::Path,
    faces: usize,
    max_span: f64,
) {
    let a = &report["atlas"];
    assert_eq!(a["flipped"], 0, "{a}");
    assert_eq!(a["overlap"]["covered_twice"], 0, "{a}");
    assert!(
        a["seam_log_ratio_max"].as_f64().expect("number") < 1e-10,
        "{a}"
    );
    assert_eq!(report["metrics"]["flipped_faces"], 0);
    let (vt, f) = corners(out);
    assert_eq!(f.len(), faces, "every face kept");
    assert!(vt
        .iter()
        .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
    // measured on the written file: no texel of a 1024² texture covered twice, no face
    // spread across the texture
    let tris: Vec<[[f64; 2]; 3]> = f.iter().map(|t| [vt[t[0]], vt[t[1]], vt[t[2]]]).collect();
    let o = conformap_metrics::raster_overlap(
        tris.iter().copied(),
        1024,
        conformap_metrics::RasterFrame::UnitSquare,
    );
    assert_eq!(o.covered_twice, 0, "{o:?}");
    assert!(o.covered > 100_000, "{o:?}");
    for t in &tris {
        for k in 0..2 {
            let (lo, hi) = t
                .iter()
                .fold((1.0f64, 0.0f64), |(a, b), p| (a.min(p[k]), b.max(p[k])));
            assert!(
                hi - lo < max_span,
                "a face spans {} of the texture",
                hi - lo
            );
        }
    }
    // every face counter-clockwise in the texture
    for t in &f {
        let (a, b, c) = (vt[t[0]], vt[t[1]], vt[t[2]]);
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        assert!(area > 0.0, "a flipped face in the texture");
    }
}

#[test]
fn spot_through_eight_cones_is_an_overlap_free_atlas() {
    let d = tmpdir("atlas-spot");
    let (out, rep) = (d.join("atlas.obj"), d.join("r.json"));
    conformap_ok(&[
        "atlas",
        s(&fixture("spot.obj")),
        "-o",
        s(&out),
        "--report",
        s(&rep),
    ]);
    let r = json(&rep);
    assert_eq!(r["command"], "atlas");
    assert_eq!(r["atlas"]["components"], 1);
    assert_eq!(r["atlas"]["cones"], 8);
    // BFF's tool at 8 cones: 1.01; the default polish (spot's cone metric spreads 0.82)
    // brings the layout under 0.8 of that
    assert!(
        r["atlas"]["area_spread"].as_f64().expect("number") < 0.8 * 1.0131,
        "{}",
        r["atlas"]
    );
    assert_eq!(r["atlas"]["polish"], "auto");
    assert_eq!(r["atlas"]["polished_components"], 1);
    check_atlas(&r, &out, 5856);
    // `--polish=never` keeps the flattened layout; a bare `--polish` before the mesh takes
    // no value and polishes as the default does here
    let (never, rep_never) = (d.join("never.obj"), d.join("never.json"));
    conformap_ok(&[
        "atlas",
        s(&fixture("spot.obj")),
        "-o",
        s(&never),
        "--polish=never",
        "--report",
        s(&rep_never),
    ]);
    let n = json(&rep_never);
    assert_eq!(n["atlas"]["polished_components"], 0);
    assert!(n["atlas"]["polish_energy"].is_null());
    let plain = n["atlas"]["area_spread"].as_f64().expect("number");
    assert!(plain > r["atlas"]["area_spread"].as_f64().expect("number") + 0.03);
    check_atlas(&n, &never, 5856);
    let always = d.join("always.obj");
    conformap_ok(&[
        "atlas",
        "--polish",
        s(&fixture("spot.obj")),
        "-o",
        s(&always),
    ]);
    assert_eq!(
        std::fs::read(&always).expect("read"),
        std::fs::read(&out).expect("read")
    );
}

/// woody (a disk) and spot (closed) in one file under `d`.
fn two_components(d: &std::path::Path) -> std::path::PathBuf {
    let mut text = String::new();
    let mut offset = 0;
    for name in ["woody.obj", "spot.obj"] {
        let src = std::fs::read_to_string(fixture(name)).expect("fixture");
        let mut count = 0;
        for line in src.lines() {
            if line.starts_with("v ") {
                text.push_str(line);
                text.push('\n');
                count += 1;
            } else if let Some(f) = line.strip_prefix("f ") {
                let idx: Vec<String> = f
                    .split_whitespace()
                    .map(|c| {
                        let v: usize = c.split('/').next().expect("index").parse().expect("int");
                        (v + offset).to_string()
                    })
                    .collect();
                text.push_str(&format!("f {}\n", idx.join(" ")));
            }
        }
        offset += count;
    }
    let input = d.join("two.obj");
    std::fs::write(&input, text).expect("write");
    input
}

#[test]
fn two_components_share_the_square() {
    let d = tmpdir("atlas-two");
    let input = two_components(&d);

    let (out, rep) = (d.join("atlas.obj"), d.join("r.json"));
    conformap_ok(&["atlas", s(&input), "-o", s(&out), "--report", s(&rep)]);
    let r = json(&rep);
    assert_eq!(r["atlas"]["components"], 2);
    // 8 cones on the closed component, none on the disk
    assert_eq!(r["atlas"]["cones"], 8);
    check_atlas(&r, &out, 1267 + 5856);
}

#[test]
fn batch_runs_atlas_as_the_single_command_does() {
    let d = tmpdir("atlas-batch");
    let dir = d.join("out");
    conformap_ok(&[
        "batch",
        "--command",
        "atlas",
        "--out-dir",
        s(&dir),
        s(&fixture("spot.obj")),
        s(&fixture("eightsim.obj")),
    ]);
    let single = d.join("spot.obj");
    conformap_ok(&["atlas", s(&fixture("spot.obj")), "-o", s(&single)]);
    assert_eq!(
        std::fs::read(dir.join("spot.obj")).expect("batch output"),
        std::fs::read(&single).expect("single output")
    );
    let r = json(&dir.join("eightsim.json"));
    assert_eq!(r["atlas"]["flipped"], 0);
    assert_eq!(r["atlas"]["overlap"]["covered_twice"], 0);
}

/// The cone lines of a report's `atlas.cone_list`, as `--cones FILE` reads them.
fn cone_file(report: &serde_json::Value) -> String {
    let mut text = String::from("# vertex  cone angle (degrees)\n");
    for c in report["atlas"]["cone_list"].as_array().expect("cone_list") {
        let v = c["vertex"].as_u64().expect("vertex");
        let a = c["angle_deg"].as_f64().expect("angle");
        text.push_str(&format!("{v} {a:?}\n"));
    }
    text
}

#[test]
fn cones_read_from_a_file_give_the_placed_cones_map() {
    let d = tmpdir("atlas-cone-file");
    let (out1, rep1) = (d.join("placed.obj"), d.join("placed.json"));
    let spot = fixture("spot.obj");
    conformap_ok(&["atlas", s(&spot), "-o", s(&out1), "--report", s(&rep1)]);
    let r1 = json(&rep1);
    assert_eq!(r1["atlas"]["cone_list"].as_array().expect("list").len(), 8);
    let cones = d.join("cones.txt");
    std::fs::write(&cones, cone_file(&r1)).expect("write cones");
    let (out2, rep2) = (d.join("given.obj"), d.join("given.json"));
    let args = ["atlas", s(&spot), "-o", s(&out2), "--report", s(&rep2)];
    conformap_ok(&[&args[..], &["--cones", s(&cones)]].concat());
    let r2 = json(&rep2);
    // the same cones; the angles as given up to the sum's rounding (the placed defects sum
    // to the discrete 720° of the mesh, the given ones are made to sum to 720° exactly)
    let (l1, l2) = (&r1["atlas"]["cone_list"], &r2["atlas"]["cone_list"]);
    for (a, b) in l1
        .as_array()
        .expect("l1")
        .iter()
        .zip(l2.as_array().expect("l2"))
    {
        assert_eq!(a["vertex"], b["vertex"]);
        let (x, y) = (a["angle_deg"].as_f64(), b["angle_deg"].as_f64());
        assert!((x.expect("x") - y.expect("y")).abs() < 1e-9, "{a} {b}");
    }
    let spread = |r: &serde_json::Value| r["atlas"]["area_spread"].as_f64().expect("spread");
    assert!(
        (spread(&r1) - spread(&r2)).abs() < 1e-9,
        "placed {} given {}",
        spread(&r1),
        spread(&r2)
    );
    check_atlas(&r2, &out2, 5856);

    // one angle 10° too large: Σ (360° − angle) = 710°, refused with the sum, nothing written
    let mut lines: Vec<String> = cone_file(&r1).lines().map(String::from).collect();
    let (v, a) = lines[1].split_once(' ').expect("line");
    let a: f64 = a.parse().expect("angle");
    lines[1] = format!("{v} {}", a + 10.0);
    let bad = d.join("bad.txt");
    std::fs::write(&bad, lines.join("\n")).expect("write");
    let out3 = d.join("refused.obj");
    let o = conformap(&["atlas", s(&spot), "-o", s(&out3), "--cones", s(&bad)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("Gauss–Bonnet") && e.contains("720°"), "{e}");
    assert!(e.contains("710"), "{e}");
    assert!(e.contains("hint:"), "{e}");
    assert!(!out3.exists(), "nothing written");
}

#[test]
fn bad_cone_lines_are_refused_with_their_line() {
    let d = tmpdir("atlas-cone-lines");
    let mesh = fixture("spot.obj");
    let out = d.join("x.obj");
    for (text, line, what) in [
        ("0 270\n5856 270\n", ":2:", "out of range"),
        ("# tips\n\n3 0\n", ":3:", "not a cone angle"),
        ("3 nan\n", ":1:", "not a cone angle"),
        ("3 800\n", ":1:", "not a cone angle"),
        ("3 270\n3 270\n", ":2:", "already has a cone"),
        ("3 270 1\n", ":1:", "not 2"),
        ("-3 270\n", ":1:", "not a vertex index"),
    ] {
        let f = d.join("cones.txt");
        std::fs::write(&f, text).expect("write");
        let o = conformap(&["atlas", s(&mesh), "-o", s(&out), "--cones", s(&f)]);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{text:?}: {e}");
        assert!(
            e.contains(&format!("cones.txt{line}")) && e.contains(what),
            "{text:?}: {e}"
        );
        assert!(e.contains("hint:"), "{e}");
        assert!(!out.exists());
    }
    // a cone on the boundary of a disk: the first vertex of an edge of one face only
    let woody = fixture("woody.obj");
    let text = std::fs::read_to_string(&woody).expect("woody");
    let mut edges = std::collections::HashMap::new();
    for f in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let t: Vec<usize> = f
            .split_whitespace()
            .map(|c| {
                c.split('/')
                    .next()
                    .expect("v")
                    .parse::<usize>()
                    .expect("int")
                    - 1
            })
            .collect();
        for k in 0..t.len() {
            let (a, b) = (t[k], t[(k + 1) % t.len()]);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let (&(v, _), _) = edges
        .iter()
        .find(|(_, &n)| n == 1)
        .expect("a boundary edge");
    let f = d.join("cones.txt");
    std::fs::write(&f, format!("{v} 180\n")).expect("write");
    let o = conformap(&["atlas", s(&woody), "-o", s(&out), "--cones", s(&f)]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("cones.txt:1:") && e.contains("on the boundary"),
        "{e}"
    );
    assert!(!out.exists());
}

#[test]
fn auto_cones_reach_the_spread_asked_for() {
    let d = tmpdir("atlas-auto");
    let (out, rep) = (d.join("auto.obj"), d.join("r.json"));
    let spot = fixture("spot.obj");
    conformap_ok(&[
        "atlas",
        s(&spot),
        "-o",
        s(&out),
        "--report",
        s(&rep),
        "--cones",
        "auto",
        "--max-area-spread",
        "1.0",
    ]);
    let r = json(&rep);
    let a = &r["atlas"];
    let spread = a["area_spread"].as_f64().expect("spread");
    assert!(spread <= 1.0, "{a}");
    // the fewest cones: 5 on spot (0.96; 8 placed cones give 0.84)
    assert_eq!(
        a["auto_cones"]["counts"],
        serde_json::json!([a["cones"]]),
        "{a}"
    );
    let n = a["cones"].as_u64().expect("count");
    assert!((3..8).contains(&n), "{a}");
    assert_eq!(a["auto_cones"]["capped"], serde_json::json!([]));
    check_atlas(&r, &out, 5856);

    // eightsim (genus 2) at 0.2: 5 cones give a metric of 0.2 but a layout of 0.203, so
    // the search goes on to 6 (0.181)
    let eight = fixture("eightsim.obj");
    let args = ["atlas", s(&eight), "-o", s(&out), "--report", s(&rep)];
    conformap_ok(&[&args[..], &["--cones", "auto", "--max-area-spread", "0.2"]].concat());
    let r = json(&rep);
    let a = &r["atlas"];
    assert!(a["area_spread"].as_f64().expect("spread") <= 0.2, "{a}");
    assert_eq!(a["cones"], 6, "{a}");
    assert_eq!(a["flipped"], 0, "{a}");
    assert_eq!(a["overlap"]["covered_twice"], 0, "{a}");
}

fn uv_area(vt: &[[f64; 2]], t: [usize; 3]) -> f64 {
    let (a, b, c) = (vt[t[0]], vt[t[1]], vt[t[2]]);
    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
}

#[test]
fn pack_none_keeps_the_layout_and_per_chart_evens_the_charts() {
    let d = tmpdir("atlas-pack-scale");
    let input = two_components(&d);
    let run = |tag: &str, extra: &[&str]| {
        let (out, rep) = (d.join(format!("{tag}.obj")), d.join(format!("{tag}.json")));
        let args = ["atlas", s(&input), "-o", s(&out), "--report", s(&rep)];
        conformap_ok(&[&args[..], extra].concat());
        (json(&rep), corners(&out))
    };
    let (packed, (vt_p, f_p)) = run("packed", &[]);
    let (kept, (vt_k, f_k)) = run("kept", &["--pack", "none"]);
    assert_eq!(kept["atlas"]["packing"], "none");
    assert_eq!(kept["atlas"]["scale"], 1.0);
    assert_eq!(packed["atlas"]["packing"], "unit-square");
    // the charts as laid out: every uv edge is the packed one over the packing's scale
    let scale = packed["atlas"]["scale"].as_f64().expect("scale");
    let mut worst = 0.0f64;
    for (tp, tk) in f_p.iter().zip(&f_k) {
        for k in 0..3 {
            let len = |vt: &[[f64; 2]], t: &[usize; 3]| {
                let (a, b) = (vt[t[k]], vt[t[(k + 1) % 3]]);
                ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
            };
            worst = worst.max((len(&vt_k, tk) * scale / len(&vt_p, tp) - 1.0).abs());
        }
    }
    assert!(worst < 1e-9, "edge length ratio off by {worst}");
    assert!(
        vt_k.iter().any(|p| p[0] > 1.0 || p[1] > 1.0),
        "layout units, not the square"
    );
    // no two charts on one texel: the raster over the layout's bounding box
    let tris: Vec<[[f64; 2]; 3]> = f_k
        .iter()
        .map(|t| [vt_k[t[0]], vt_k[t[1]], vt_k[t[2]]])
        .collect();
    let o = conformap_metrics::raster_overlap(
        tris.iter().copied(),
        1024,
        conformap_metrics::RasterFrame::BoundingBox,
    );
    assert_eq!(o.covered_twice, 0, "{o:?}");
    assert_eq!(kept["atlas"]["overlap"]["covered_twice"], 0);

    // per chart: woody's chart and spot's charts (together) the same texture area, where
    // one density gives spot several times woody's; spot's charts keep one density
    let (even, (vt_e, f_e)) = run("even", &["--scale", "per-chart"]);
    assert_eq!(even["atlas"]["scale_mode"], "per-chart");
    let areas = |vt: &[[f64; 2]], f: &[[usize; 3]]| -> [f64; 2] {
        let woody: f64 = f[..1267].iter().map(|&t| uv_area(vt, t)).sum();
        let spot: f64 = f[1267..].iter().map(|&t| uv_area(vt, t)).sum();
        [woody, spot]
    };
    let (ae, ap) = (areas(&vt_e, &f_e), areas(&vt_p, &f_p));
    assert!((ae[1] / ae[0] - 1.0).abs() < 1e-9, "per-chart areas {ae:?}");
    assert!(
        ap[1] / ap[0] > 3.0 || ap[0] / ap[1] > 3.0,
        "uniform areas {ap:?}"
    );
    let a = &even["atlas"];
    assert_eq!(a["flipped"], 0, "{a}");
    assert_eq!(a["overlap"]["covered_twice"], 0, "{a}");
    assert!(
        a["seam_log_ratio_max"].as_f64().expect("seams") < 1e-10,
        "{a}"
    );
    assert!(vt_e
        .iter()
        .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
}

/// Two subdivided cubes (4 × 4 squares a side) touching at one corner, and a book of three
/// 4 × 4 pages on one spine, the middle page turned the other way: an OBJ of 480 faces,
/// one non-manifold vertex where the cubes meet, a non-manifold spine of 4 edges.
fn cubes_and_book() -> (String, usize) {
    let n = 4i64;
    let mut index: std::collections::HashMap<[i64; 3], usize> = Default::default();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut faces: Vec<[usize; 3]> = Vec::new();
    let mut vertex = |p: [i64; 3], scale: f64, real: Option<[f64; 3]>| -> usize {
        *index.entry(p).or_insert_with(|| {
            points.push(real.unwrap_or([
                p[0] as f64 * scale,
                p[1] as f64 * scale,
                p[2] as f64 * scale,
            ]));
            points.len() - 1
        })
    };
    // a cube [o, o + n]³: every face a grid, counter-clockwise seen from outside
    for o in [0, n] {
        for axis in 0..3 {
            for side in [0, n] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                for i in 0..n {
                    for j in 0..n {
                        let at = |a: i64, b: i64| {
                            let mut p = [o; 3];
                            p[axis] += side;
                            p[u] += a;
                            p[v] += b;
                            p
                        };
                        let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                        let q = q.map(|p| vertex(p, 0.25, None));
                        let t = if side == n {
                            [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
                        } else {
                            [[q[0], q[2], q[1]], [q[0], q[3], q[2]]]
                        };
                        faces.extend(t);
                    }
                }
            }
        }
    }
    // the book, away from the cubes: spine along z at x = 5, pages at 0°, 120°, 240°
    for page in 0..3i64 {
        let angle = 2.0 * std::f64::consts::PI * page as f64 / 3.0;
        for i in 0..n {
            for j in 0..n {
                let at = |a: i64, b: i64| {
                    let key = if a == 0 {
                        [100, 0, b]
                    } else {
                        [100 + page, a, b]
                    };
                    let r = a as f64 * 0.25;
                    let real = [5.0 + r * angle.cos(), r * angle.sin(), b as f64 * 0.25];
                    (key, real)
                };
                let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                let q = q.map(|(k, r)| vertex(k, 1.0, Some(r)));
                if page == 1 {
                    faces.extend([[q[0], q[2], q[1]], [q[0], q[3], q[2]]]);
                } else {
                    faces.extend([[q[0], q[1], q[2]], [q[0], q[2], q[3]]]);
                }
            }
        }
    }
    let mut text = String::new();
    for p in &points {
        text.push_str(&format!("v {} {} {}\n", p[0], p[1], p[2]));
    }
    for t in &faces {
        text.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    (text, faces.len())
}

#[test]
fn non_manifold_vertices_and_edges_are_split_by_atlas_only() {
    let d = tmpdir("atlas-non-manifold");
    let (text, faces) = cubes_and_book();
    assert_eq!(faces, 2 * 6 * 32 + 3 * 32);
    let input = d.join("cubes_book.obj");
    std::fs::write(&input, text).expect("write");
    // other commands keep refusing, now naming atlas
    let out = d.join("disk.obj");
    let o = conformap(&["disk", s(&input), "-o", s(&out)]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("non-manifold") && e.contains("conformap atlas"),
        "{e}"
    );
    assert!(!out.exists());

    let (out, rep, map) = (d.join("atlas.obj"), d.join("r.json"), d.join("map.txt"));
    conformap_ok(&[
        "atlas",
        s(&input),
        "-o",
        s(&out),
        "--report",
        s(&rep),
        "--vertex-map",
        s(&map),
    ]);
    let r = json(&rep);
    let a = &r["atlas"];
    // the cubes' corner once; the spine's 5 vertices (the third page's copies)
    assert_eq!(a["non_manifold"]["vertices_split"], 6, "{a}");
    assert_eq!(a["non_manifold"]["vertices_added"], 6, "{a}");
    assert_eq!(a["non_manifold"]["edges_split"], 4, "{a}");
    // two cubes, the two glued pages, the page cut off
    assert_eq!(a["components"], 4, "{a}");
    check_atlas(&r, &out, faces);
    // the vertex map: one line per written vertex, the copies naming their input vertex
    let text = std::fs::read_to_string(&out).expect("out");
    let written = text.lines().filter(|l| l.starts_with("v ")).count();
    let lines: Vec<usize> = std::fs::read_to_string(&map)
        .expect("map")
        .lines()
        .map(|l| l.parse().expect("index"))
        .collect();
    assert_eq!(lines.len(), written);
    let split: Vec<usize> = a["non_manifold"]["split_vertices"]
        .as_array()
        .expect("list")
        .iter()
        .map(|v| v.as_u64().expect("int") as usize)
        .collect();
    let kept = lines.len() - 6;
    assert!(
        lines[..kept].iter().enumerate().all(|(i, &v)| i == v),
        "input vertices first"
    );
    let mut copies = lines[lines.len() - 6..].to_vec();
    copies.sort_unstable();
    assert_eq!(copies, split);
}

/// `conformap atlas FIXTURE --seamless` into `dir`: its report (checked seamless, every
/// seam within 1e-6 of a quarter-turn rigid map) and the written atlas's path.
fn seamless_atlas(dir: &std::path::Path, mesh: &str) -> (serde_json::Value, std::path::PathBuf) {
    let (out, rep) = (dir.join("atlas.obj"), dir.join("r.json"));
    conformap_ok(&[
        "atlas",
        s(&fixture(mesh)),
        "-o",
        s(&out),
        "--seamless",
        "--report",
        s(&rep),
    ]);
    let r = json(&rep);
    let a = &r["atlas"];
    assert_eq!(a["seamless"], true, "{a}");
    let number = |k: &str| a[k].as_f64().expect("number");
    assert!(number("seam_rotation_error_max") <= 1e-6, "{a}");
    assert!(number("seam_rigid_residual_max") <= 1e-6, "{a}");
    (r, out)
}

#[test]
fn seamless_spot_has_quarter_turn_seams_and_cones() {
    let d = tmpdir("atlas-seamless");
    let (r, out) = seamless_atlas(&d, "spot.obj");
    let a = &r["atlas"];
    let cones = a["cone_list"].as_array().expect("cones");
    assert!(!cones.is_empty());
    for c in cones {
        let q = c["angle_deg"].as_f64().expect("angle") / 90.0;
        assert!((q - q.round()).abs() < 1e-9, "{c}");
    }
    check_atlas(&r, &out, 5856);
}

#[test]
fn seamless_refuses_auto_cones_and_cones_off_quarter_turns() {
    let d = tmpdir("atlas-seamless-bad");
    let mesh = fixture("spot.obj");
    let out = d.join("x.obj");
    let o = conformap(&[
        "atlas",
        s(&mesh),
        "-o",
        s(&out),
        "--seamless",
        "--cones",
        "auto",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--seamless"), "{}", stderr(&o));
    assert!(!out.exists());
    // Gauss–Bonnet holds (180 + 180 + 180 + 260 − 80 = 720° of curvature) but 100° and
    // 440° are no quarter turns
    let f = d.join("cones.txt");
    std::fs::write(&f, "10 180\n500 180\n1000 180\n1500 100\n2000 440\n").expect("write");
    let o = conformap(&[
        "atlas",
        s(&mesh),
        "-o",
        s(&out),
        "--seamless",
        "--cones",
        s(&f),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(e.contains("cones.txt") && e.contains("vertex 1500"), "{e}");
    assert!(e.contains("hint:"), "{e}");
    assert!(!out.exists());
}

/// The largest rotation error (radians, from the nearest quarter turn) and residual after
/// that quarter turn's rigid map (relative to the edge length) over the seam edges of an
/// atlas OBJ, read from the file: an edge of two faces whose `vt` differ on its two sides.
fn seam_rigidity_of_file(path: &std::path::Path) -> (usize, f64, f64) {
    let text = std::fs::read_to_string(path).expect("read output");
    let vt: Vec<[f64; 2]> = corners(path).0;
    let mut sides = std::collections::HashMap::new();
    for l in text.lines().filter_map(|l| l.strip_prefix("f ")) {
        let c: Vec<(usize, usize)> = l
            .split_whitespace()
            .map(|c| {
                let mut it = c.split('/').map(|x| x.parse::<usize>().expect("index") - 1);
                (it.next().expect("v"), it.next().expect("vt"))
            })
            .collect();
        for k in 0..3 {
            let (a, b) = (c[k], c[(k + 1) % 3]);
            sides.insert((a.0, b.0), (a.1, b.1));
        }
    }
    let (mut seams, mut rotation, mut residual) = (0, 0.0f64, 0.0f64);
    for (&(a, b), &(ta, tb)) in &sides {
        let Some(&(tq, tp)) = sides.get(&(b, a)) else {
            continue;
        };
        if a > b || (ta == tp && tb == tq) {
            continue; // each edge once; not a seam
        }
        // the edge a → b on both sides
        let d1 = [vt[tb][0] - vt[ta][0], vt[tb][1] - vt[ta][1]];
        let d2 = [vt[tp][0] - vt[tq][0], vt[tp][1] - vt[tq][1]];
        let angle = (d1[1] * d2[0] - d1[0] * d2[1]).atan2(d1[0] * d2[0] + d1[1] * d2[1]);
        let turns = (angle / std::f64::consts::FRAC_PI_2).round();
        rotation = rotation.max((angle - turns * std::f64::consts::FRAC_PI_2).abs());
        // the quarter turn exactly
        let (cos, sin) = match (turns as i64).rem_euclid(4) {
            0 => (1.0, 0.0),
            1 => (0.0, 1.0),
            2 => (-1.0, 0.0),
            _ => (0.0, -1.0),
        };
        let r = [cos * d2[0] - sin * d2[1], sin * d2[0] + cos * d2[1]];
        let len = d1[0].hypot(d1[1]);
        residual = residual.max((d1[0] - r[0]).hypot(d1[1] - r[1]) / len);
        seams += 1;
    }
    (seams, rotation, residual)
}

#[test]
fn seamless_genus_two_has_quarter_turn_seams_and_branch_point_cones() {
    // eightsim (genus 2, 350 faces) through its holomorphic 1-form: the discrete form
    // folded a face beside each zero (the atlas mirrored them: seams 0.71 rad off a quarter
    // turn, refused); each zero is now a branch point of the layout (chart/seamless.rs,
    // `branch_zero`): cones of 720°, every seam a translation or a quarter-turn rigid map
    let d = tmpdir("atlas-seamless-genus2");
    let (r, out) = seamless_atlas(&d, "eightsim.obj");
    let a = &r["atlas"];
    // 2g − 2 = 2 simple zeros of the form, cones of 720° (a multiple of 90°)
    let cones = a["cone_list"].as_array().expect("cones");
    assert_eq!(cones.len(), 2, "{a}");
    for c in cones {
        assert_eq!(c["angle_deg"].as_f64().expect("angle"), 720.0, "{c}");
    }
    // 350 large faces: the default atlas has one spanning 0.14 of the texture too
    check_atlas_spans(&r, &out, 350, 0.2);
    // the same from the written file: every seam a quarter-turn rigid map
    let (seams, rotation, residual) = seam_rigidity_of_file(&out);
    assert!(seams > 50, "{seams}");
    assert!(
        rotation <= 1e-6 && residual <= 1e-6,
        "{rotation} {residual}"
    );
}
