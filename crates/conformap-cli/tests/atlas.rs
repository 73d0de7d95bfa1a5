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
            assert!(hi - lo < 0.1, "a face spans {} of the texture", hi - lo);
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
    // BFF's tool at 8 cones: 1.01
    assert!(
        r["atlas"]["area_spread"].as_f64().expect("number") < 0.87,
        "{}",
        r["atlas"]
    );
    check_atlas(&r, &out, 5856);
}

#[test]
fn two_components_share_the_square() {
    let d = tmpdir("atlas-two");
    // woody (a disk) and spot (closed) in one file
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
