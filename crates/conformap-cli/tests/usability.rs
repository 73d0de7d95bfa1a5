//! Usability (issue 38): map files matched as other tools write them, tiny disks, batch
//! inputs listed twice, a file where a directory is expected, option messages that name
//! what the user typed, options that would be ignored said aloud, and help texts that say
//! how the map becomes texture coordinates.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use support::{conformap, conformap_ok, fixture, metrics_json, s, stderr, tmpdir};

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
