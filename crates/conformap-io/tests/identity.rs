//! Parse → write → parse is the identity, bit for bit: positions, faces and texture
//! coordinates come back exactly (the writer's `ryu` shortest representation is correctly
//! parsed back by `fast-float2`). On hard values always; on every mesh of
//! `../shared/meshes/` with `--ignored` (they are too large for the default run).
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use std::path::{Path, PathBuf};

use common::out_dir;
use conformap_io::{read_mesh, read_raw_mesh, write_flat, write_mesh_with_uv};

fn bits3(p: &[[f64; 3]]) -> Vec<[u64; 3]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

fn bits2(p: &[[f64; 2]]) -> Vec<[u64; 2]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

/// Writes `mesh_file` back (with a texture coordinate per vertex: the file's own, else
/// its x, y) and reads it again; asserts every bit survives. Returns the vertex count.
fn assert_identity(mesh_file: &Path, out: &Path) -> usize {
    let loaded = read_mesh(mesh_file).unwrap();
    let uv = match loaded.per_vertex_uv() {
        Ok(uv) => uv.to_vec(),
        Err(_) => loaded
            .mesh
            .positions()
            .iter()
            .map(|p| [p[0], p[1]])
            .collect(),
    };
    // formatted (no source), then with the file's own numbers copied (its source)
    for source in [None, Some(&loaded.source)] {
        write_mesh_with_uv(out, &loaded.mesh, &uv, source).unwrap();
        let again = read_mesh(out).unwrap();
        let name = format!("{} (source: {})", mesh_file.display(), source.is_some());
        assert_eq!(
            bits3(again.mesh.positions()),
            bits3(loaded.mesh.positions()),
            "{name}: positions"
        );
        assert_eq!(again.mesh.faces(), loaded.mesh.faces(), "{name}: faces");
        assert_eq!(
            bits2(again.per_vertex_uv().unwrap()),
            bits2(&uv),
            "{name}: texture coordinates"
        );
    }
    loaded.mesh.num_vertices()
}

/// With the file's source, `v` lines carry the numbers exactly as the file wrote them; a
/// vertex that no longer matches its text (a mesh changed after reading) is formatted, and
/// the file still reads back to the mesh written.
#[test]
fn written_positions_copy_the_file_text_only_where_it_still_holds() {
    let d = out_dir("identity_text");
    let input = d.join("in.obj");
    let text = "v 1.000000 0.0 0e0\nv 0.1000 1e0 -0.0\nv   +2.50   2.5E-1\t3\nv 1 1 1 1\nf 1 2 3\nf 2 4 3\n";
    std::fs::write(&input, text).unwrap();
    let loaded = read_mesh(&input).unwrap();
    let uv = vec![[0.0, 0.0]; 4];
    let out = d.join("out.obj");
    write_mesh_with_uv(&out, &loaded.mesh, &uv, Some(&loaded.source)).unwrap();
    let written = std::fs::read_to_string(&out).unwrap();
    let v_lines: Vec<&str> = written.lines().filter(|l| l.starts_with("v ")).collect();
    // copied as written, from the first number to the last; the homogeneous line formatted
    assert_eq!(
        v_lines,
        [
            "v 1.000000 0.0 0e0",
            "v 0.1000 1e0 -0.0",
            "v +2.50   2.5E-1\t3",
            "v 1.0 1.0 1.0"
        ]
    );
    // a moved vertex: its text no longer parses to it, so it is formatted
    let mut moved = loaded.mesh.positions().to_vec();
    moved[1][0] = 0.25;
    let mesh =
        conformap_mesh::TriMesh::try_new(moved.clone(), loaded.mesh.faces().to_vec()).unwrap();
    write_mesh_with_uv(&out, &mesh, &uv, Some(&loaded.source)).unwrap();
    let again = read_mesh(&out).unwrap();
    assert_eq!(bits3(again.mesh.positions()), bits3(&moved));
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(written.contains("v 0.25 1.0 -0.0\n"), "{written}");
    assert!(written.contains("v 1.000000 0.0 0e0\n"), "{written}");
}

#[test]
fn hard_numbers_round_trip_bit_for_bit() {
    let d = out_dir("identity_hard");
    let hard = [
        0.1 + 0.2,
        -0.0,
        5e-324,                     // smallest subnormal
        2.225_073_858_507_201e-308, // largest subnormal
        f64::MIN_POSITIVE,
        f64::MAX,
        -f64::MAX,
        1e23, // the classic wrongly-rounded decimal
        9_007_199_254_740_993.0,
        std::f64::consts::PI,
        1.0 / 3.0,
        123_456_789.012_345_68,
    ];
    let points: Vec<[f64; 3]> = hard
        .iter()
        .enumerate()
        .map(|(k, &x)| [x, -x / 7.0, f64::from(k as u32) * 0.1])
        .collect();
    let faces: Vec<[u32; 3]> = (0..points.len() as u32 - 2)
        .map(|k| [k, k + 1, k + 2])
        .collect();
    let out = d.join("hard.obj");
    write_flat(&out, &points, &faces).unwrap();
    let raw = read_raw_mesh(&out).unwrap();
    assert_eq!(bits3(&raw.positions), bits3(&points));
    assert_eq!(raw.faces, faces);
}

#[test]
fn fixture_meshes_round_trip_bit_for_bit() {
    let d = out_dir("identity_fixtures");
    for name in ["woody.obj", "spothead.obj", "alligator.obj"] {
        assert_identity(&common::fixture(name), &d.join(name));
    }
}

fn shared_meshes() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/meshes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "obj"))
        .collect();
    files.sort();
    files
}

#[test]
#[ignore = "reads every mesh of ../shared/meshes (30 MB): cargo test -p conformap-io --test identity -- --ignored"]
fn every_shared_mesh_round_trips_bit_for_bit() {
    let d = out_dir("identity_shared");
    let files = shared_meshes();
    assert!(files.len() >= 20, "{} meshes", files.len());
    for f in &files {
        let out = d.join(f.file_name().unwrap());
        let n = assert_identity(f, &out);
        assert!(n > 0);
        std::fs::remove_file(&out).unwrap();
    }
}
