//! `conformap global --topology-opt` on spot (closed genus 0), on a compact ellipsoid (the
//! sphere map returned, drawn as `sphere` draws it) and on a disk with limbs (alligator).
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::collections::{HashMap, HashSet};
use std::path::Path;

use support::{conformap, fixture, json, s, stderr, tmpdir};

/// Largest relative difference of an edge's texture-coordinate vector in its two faces,
/// over the interior edges of the input that are not on a slit (across a slit the two sides
/// are different boundary arcs of the slit surface, not one edge).
fn seam_defect_off_slits(
    mesh_path: &Path,
    map_path: &Path,
    slit_edges: &HashSet<(u32, u32)>,
) -> f64 {
    let mesh = conformap_io::read_mesh(mesh_path).unwrap().mesh;
    let map = conformap_io::read_mesh(map_path).unwrap();
    let c = map.corner_uv.expect("per-corner texture coordinates");
    assert_eq!(
        map.mesh.positions(),
        mesh.positions(),
        "v lines must be the input's"
    );
    assert_eq!(map.mesh.faces(), mesh.faces(), "faces must be the input's");
    let mut half: HashMap<(u32, u32), (usize, usize)> = HashMap::new();
    let mut worst = 0.0f64;
    for (f, t) in mesh.faces().iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if let Some(&(g, j)) = half.get(&(b, a)) {
                if slit_edges.contains(&(a.min(b), a.max(b))) {
                    continue;
                }
                let (p, q) = (c.corner(f, (k + 1) % 3), c.corner(f, k));
                let (r, u) = (c.corner(g, j), c.corner(g, (j + 1) % 3));
                let d = ((p[0] - q[0]) - (r[0] - u[0])).hypot((p[1] - q[1]) - (r[1] - u[1]));
                worst = worst.max(d);
            } else {
                half.insert((a, b), (f, k));
            }
        }
    }
    worst
}

#[test]
fn spot_is_slit_and_laid_out_more_uniformly_than_the_sphere_map() {
    let d = tmpdir("global-topology-spot");
    let (out, rep) = (d.join("spot.obj"), d.join("spot.json"));
    let mesh = fixture("spot.obj");
    let o = conformap(&[
        "global",
        s(&mesh),
        "-o",
        s(&out),
        "--report",
        s(&rep),
        "--topology-opt",
        "--max-slits",
        "8",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = json(&rep);
    let t = &r["topology_opt"];
    assert_eq!(t["returned"], "slits", "{t}");
    let steps = t["steps"].as_array().unwrap();
    // measured: step 1 slits 5 clusters (0.33× … 5.1× depending on the step), step 2 reaches
    // 8 slits at 0.574× the sphere map's energy
    assert_eq!(steps[0]["slits"], 0);
    assert!(steps.len() >= 3, "{t}");
    let ratio = t["ratio_to_start"].as_f64().unwrap();
    assert!(ratio < 0.65, "{ratio}");
    assert_eq!(r["metrics"]["folds_outside_zeros"], 0);
    let slits = t["slits"].as_array().unwrap();
    assert!(slits.len() >= 2 && slits.len() <= 8, "{t}");
    let mut edges = HashSet::new();
    for p in slits {
        let p: Vec<u32> = p
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap() as u32)
            .collect();
        assert!(p.len() >= 3);
        for w in p.windows(2) {
            edges.insert((w[0].min(w[1]), w[0].max(w[1])));
        }
    }
    // seams away from the slits are pure translations (the texture is scaled to the unit
    // square: rounding level)
    let defect = seam_defect_off_slits(&mesh, &out, &edges);
    assert!(defect < 1e-9, "{defect:e}");
}

#[test]
fn topology_opt_usage_is_checked() {
    let d = tmpdir("global-topology-usage");
    let out = d.join("x.obj");
    let spot = fixture("spot.obj");
    let o = conformap(&["global", s(&spot), "-o", s(&out), "--max-slits", "4"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = conformap(&[
        "global",
        s(&spot),
        "-o",
        s(&out),
        "--topology-opt",
        "--objective",
        "basis",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = conformap(&[
        "global",
        s(&spot),
        "-o",
        s(&out),
        "--topology-opt",
        "--slit-length",
        "1.5",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // several components are still refused (exit 1) and nothing is written
    let two = d.join("two.obj");
    std::fs::write(
        &two,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 0 0\nv 6 0 0\nv 5 1 0\nv 5 0 1\n\
         f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 5 7 6\nf 5 6 8\nf 6 7 8\nf 7 5 8\n",
    )
    .unwrap();
    let o = conformap(&["global", s(&two), "-o", s(&out), "--topology-opt"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!out.exists());
}

/// Writes `mesh` as a plain OBJ.
fn write_obj(path: &Path, mesh: &conformap_mesh::TriMesh) {
    let mut text = String::new();
    for p in mesh.positions() {
        text += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for f in mesh.faces() {
        text += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(path, text).unwrap();
}

#[test]
fn a_returned_sphere_map_is_drawn_as_sphere_draws_it() {
    let d = tmpdir("global-topology-sphere-png");
    let mesh = d.join("ellipsoid.obj");
    write_obj(&mesh, &conformap_sphere::doc_support::octahedron_sphere(3));
    let (a, b) = (d.join("a"), d.join("b"));
    let o = conformap(&[
        "sphere",
        s(&mesh),
        "-o",
        s(&d.join("a.obj")),
        "--mobius",
        "uniform",
        "--png",
        s(&a),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rep = d.join("b.json");
    let o = conformap(&[
        "global",
        s(&mesh),
        "-o",
        s(&d.join("b.obj")),
        "--topology-opt",
        "--report",
        s(&rep),
        "--png",
        s(&b),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(json(&rep)["topology_opt"]["returned"], "sphere");
    // the same uniform-Möbius sphere map, so the same two pictures, byte for byte (before:
    // the equirectangular texture drawn as a flat map)
    for suffix in ["_surface.png", "_map.png"] {
        let read = |p: &Path| std::fs::read(format!("{}{suffix}", p.display())).unwrap();
        let (pa, pb) = (read(&a), read(&b));
        let differing = pa.iter().zip(&pb).filter(|(x, y)| x != y).count();
        assert_eq!((pa.len(), differing), (pb.len(), 0), "{suffix}");
    }
}

#[test]
fn a_disk_with_limbs_is_slit_and_laid_out_more_uniformly_than_its_disk_map() {
    let d = tmpdir("global-topology-disk");
    let (out, rep) = (d.join("alligator.obj"), d.join("alligator.json"));
    let o = conformap(&[
        "global",
        s(&fixture("alligator.obj")),
        "-o",
        s(&out),
        "--report",
        s(&rep),
        "--topology-opt",
        "--max-slits",
        "9",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = json(&rep);
    let t = &r["topology_opt"];
    let steps = t["steps"].as_array().unwrap();
    assert_eq!(steps[0]["slits"], 0);
    let start = t["start_energy"].as_f64().unwrap();
    // the uniform-Möbius disk map's energy, as `disk` + `mobius --objective uniform` give it
    // (measured 1.1631e-3; 9 slits 0.666× of it)
    assert!((start - 1.1631e-3).abs() < 1e-7, "{start:e}");
    let ratio = t["ratio_to_start"].as_f64().unwrap();
    assert!(ratio < 0.7, "{ratio}");
    assert_eq!(t["returned"], "slits", "{t}");
    assert_eq!(r["metrics"]["folds_outside_zeros"], 0);
    assert!(out.exists());
}
