//! Writers: OBJ round trips are exact; glTF/GLB round trips are exact to f32 (glTF stores
//! f32); output appears complete or not at all.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::{fixture, out_dir, planar_uv};
use conformap_io::{
    read_mesh, write_flat, write_mesh_with_uv, Format, IoError, WriteProblem, NO_VERTEX,
};

/// Largest |a − b| over texture coordinates.
fn max_uv_diff(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .zip(b)
        .flat_map(|(x, y)| [(x[0] - y[0]).abs(), (x[1] - y[1]).abs()])
        .fold(0.0, f64::max)
}

fn f32_round(p: &[[f64; 3]]) -> Vec<[f64; 3]> {
    p.iter().map(|q| q.map(|x| f64::from(x as f32))).collect()
}

#[test]
fn obj_round_trip_is_exact_on_woody() {
    let dir = out_dir("obj_round_trip");
    let a = read_mesh(fixture("woody.obj")).unwrap();
    // awkward values: thirds and tiny/huge magnitudes must survive bit for bit
    let uv: Vec<[f64; 2]> = planar_uv(a.mesh.positions())
        .iter()
        .enumerate()
        .map(|(k, t)| [t[0] / 3.0, t[1] * 1e-9 + k as f64 * 1e20])
        .collect();
    let out = dir.join("woody_uv.obj");
    write_mesh_with_uv(&out, &a.mesh, &uv, Some(&a.source)).unwrap();
    let b = read_mesh(&out).unwrap();
    assert_eq!(b.mesh.positions(), a.mesh.positions());
    assert_eq!(b.mesh.faces(), a.mesh.faces());
    assert_eq!(b.per_vertex_uv().unwrap(), uv.as_slice()); // exact, per vertex
                                                           // and again: the written file reproduces itself
    let out2 = dir.join("woody_uv2.obj");
    write_mesh_with_uv(&out2, &b.mesh, &uv, None).unwrap();
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&out2).unwrap());
}

#[test]
fn flat_obj_round_trip() {
    let dir = out_dir("flat_obj");
    let m = read_mesh(fixture("eightsim.obj")).unwrap().mesh;
    // unit-sphere-like points: normalised positions
    let pts: Vec<[f64; 3]> = m
        .positions()
        .iter()
        .map(|p| {
            let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            p.map(|x| x / r)
        })
        .collect();
    let out = dir.join("sphere.obj");
    write_flat(&out, &pts, m.faces()).unwrap();
    let back = read_mesh(&out).unwrap();
    assert_eq!(back.mesh.positions(), pts.as_slice());
    assert!(back.uv.is_none());
}

#[test]
fn gltf_and_glb_round_trips_are_exact_to_f32() {
    let dir = out_dir("gltf_round_trip");
    let a = read_mesh(fixture("spothead.obj")).unwrap();
    let uv = planar_uv(a.mesh.positions());
    for ext in ["gltf", "glb"] {
        let out = dir.join(format!("spothead.{ext}"));
        write_mesh_with_uv(&out, &a.mesh, &uv, Some(&a.source)).unwrap();
        let b = read_mesh(&out).unwrap();
        assert_eq!(b.source.format, Format::from_path(&out).unwrap());
        // glTF stores f32: positions come back as the nearest f32, exactly
        assert_eq!(b.mesh.positions(), f32_round(a.mesh.positions()).as_slice());
        assert_eq!(b.mesh.faces(), a.mesh.faces());
        let map = b.source.weld_map.as_ref().unwrap();
        assert!(map.iter().enumerate().all(|(i, &m)| m as usize == i));
        // TEXCOORD_0 is f32 and stored as t = 1 − v: error ≤ one f32 ulp at 1
        let back = b.per_vertex_uv().unwrap();
        assert!(
            max_uv_diff(back, &uv) <= 1.2e-7,
            "{}",
            max_uv_diff(back, &uv)
        );
    }
}

#[test]
fn committed_glb_fixture_reads() {
    let woody_obj = read_mesh(fixture("woody.obj")).unwrap().mesh;
    let glb = read_mesh(fixture("gltf/woody.glb")).unwrap();
    assert_eq!(
        glb.mesh.positions(),
        f32_round(woody_obj.positions()).as_slice()
    );
    assert_eq!(glb.mesh.faces(), woody_obj.faces());
    let uv = glb.per_vertex_uv().unwrap();
    assert!(max_uv_diff(uv, &planar_uv(woody_obj.positions())) <= 1.2e-7);
}

#[test]
fn seam_split_glb_is_welded() {
    let soup = read_mesh(fixture("gltf/woody_soup.glb")).unwrap();
    let woody = read_mesh(fixture("woody.obj")).unwrap().mesh;
    assert_eq!(soup.source.file_vertex_count, 3 * 1267);
    assert_eq!(soup.mesh.num_vertices(), 694);
    assert_eq!(soup.mesh.num_faces(), 1267);
    assert_eq!(soup.mesh.boundary_loops().len(), 1);
    // deterministic numbering: first occurrence wins
    let map = soup.source.weld_map.as_ref().unwrap();
    assert_eq!(&map[..6], &[0, 1, 2, 3, 0, 4]); // face 1 (411 167 259) reuses 167
    let mut seen = 0;
    for &m in map {
        assert!(m <= seen, "new vertices appear in order");
        if m == seen {
            seen += 1;
        }
    }
    // every welded vertex sits where woody's vertex is
    for (f_soup, f_woody) in soup.mesh.faces().iter().zip(woody.faces()) {
        for k in 0..3 {
            let p = soup.mesh.positions()[f_soup[k] as usize];
            let q = woody.positions()[f_woody[k] as usize].map(|x| f64::from(x as f32));
            assert_eq!(p, q);
        }
    }
    assert!(soup.source.notes.iter().any(|n| n.contains("welded 3801")));
}

#[test]
fn glb_output_keeps_the_files_vertex_layout() {
    let dir = out_dir("glb_layout");
    let soup = read_mesh(fixture("gltf/woody_soup.glb")).unwrap();
    let uv = planar_uv(soup.mesh.positions());
    let out = dir.join("soup_uv.glb");
    write_mesh_with_uv(&out, &soup.mesh, &uv, Some(&soup.source)).unwrap();
    let back = read_mesh(&out).unwrap();
    assert_eq!(back.source.file_vertex_count, 3801); // split vertices kept
    assert_eq!(back.source.weld_map, soup.source.weld_map);
    assert_eq!(back.mesh.positions(), soup.mesh.positions());
    assert!(max_uv_diff(back.per_vertex_uv().unwrap(), &uv) <= 1.2e-7);
    // without the source, the welded mesh is written
    let out = dir.join("soup_uv_welded.glb");
    write_mesh_with_uv(&out, &soup.mesh, &uv, None).unwrap();
    assert_eq!(read_mesh(&out).unwrap().source.file_vertex_count, 694);
}

#[test]
fn external_bin_with_escaped_uri_and_node_transform() {
    let q = read_mesh(fixture("gltf/quad_external.gltf")).unwrap();
    assert_eq!(q.mesh.num_faces(), 2);
    assert_eq!(q.mesh.positions()[2], [11.0, 1.0, 0.0]); // translated by (10, 0, 0)
    assert!(q
        .source
        .weld_map
        .as_ref()
        .unwrap()
        .iter()
        .all(|&m| m != NO_VERTEX));
}

#[test]
fn writer_errors_leave_no_file() {
    let dir = out_dir("writer_errors");
    let m = read_mesh(fixture("eightsim.obj")).unwrap();
    let n = m.mesh.num_vertices();
    let out = dir.join("x.obj");
    let err = write_mesh_with_uv(&out, &m.mesh, &vec![[0.0, 0.0]; n - 1], None).unwrap_err();
    assert!(matches!(
        err,
        IoError::BadWriteInput {
            problem: WriteProblem::UvCount { .. },
            ..
        }
    ));
    let mut uv = vec![[0.5, 0.5]; n];
    uv[7][1] = f64::NAN;
    let err = write_mesh_with_uv(dir.join("x.glb"), &m.mesh, &uv, None).unwrap_err();
    assert!(matches!(
        err,
        IoError::BadWriteInput {
            problem: WriteProblem::NonFinite { vertex: 7, .. },
            ..
        }
    ));
    let err = write_flat(dir.join("x.gltf"), &[[1e39, 0.0, 0.0]; 3], &[[0, 1, 2]]).unwrap_err();
    assert!(matches!(err, IoError::BadWriteInput { .. }), "f32 overflow");
    let err = write_flat(&out, &[[0.0; 3]; 3], &[[0, 1, 3]]).unwrap_err();
    assert!(matches!(
        err,
        IoError::BadWriteInput {
            problem: WriteProblem::FaceIndex {
                face: 0,
                index: 3,
                ..
            },
            ..
        }
    ));
    assert!(matches!(
        write_flat(dir.join("x.3ds"), &[], &[]),
        Err(IoError::UnknownFormat { .. })
    ));
    // STL and OFF are read only
    assert!(matches!(
        write_flat(dir.join("x.stl"), &[], &[]),
        Err(IoError::BadWriteInput {
            problem: WriteProblem::NotWritable { .. },
            ..
        })
    ));
    let err = write_flat(dir.join("missing/dir/x.obj"), &[[0.0; 3]], &[]).unwrap_err();
    assert!(matches!(err, IoError::Write { .. }));
    // nothing at all was left behind, not even temporary files
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
}

#[test]
fn overwriting_replaces_the_whole_file() {
    let dir = out_dir("overwrite");
    let out = dir.join("m.obj");
    let big = read_mesh(fixture("eightsim.obj")).unwrap().mesh;
    write_flat(&out, big.positions(), big.faces()).unwrap();
    write_flat(
        &out,
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2]],
    )
    .unwrap();
    assert_eq!(read_mesh(&out).unwrap().mesh.num_vertices(), 3);
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}
