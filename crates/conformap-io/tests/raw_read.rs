//! The raw readers: the same parsing as `read_mesh` without validation, and the same
//! errors (with the same file places) once validated; plus the defect classes whose
//! fixtures only the raw path and the CLI use.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::{f32_bytes, fixture, glb};
use conformap_io::{
    read_mesh, read_mesh_from_bytes, read_raw_mesh, read_raw_mesh_from_bytes, Format, IoError,
    Origin,
};
use conformap_mesh::{repair, MeshError, RepairOptions, Topology, TriMesh};
use serde_json::json;

const BAD: &[&str] = &[
    "nan_coordinate.obj",
    "inf_coordinate.obj",
    "repeated_vertex.obj",
    "degenerate_face.obj",
    "duplicate_face.obj",
    "unreferenced_vertex.obj",
    "nonmanifold_edge.obj",
    "bowtie_vertex.obj",
    "inconsistent_orientation.obj",
    "mobius.obj",
    "dirty_disk.obj",
];

#[test]
fn validating_a_raw_read_is_read_mesh() {
    for name in BAD {
        let path = fixture(&format!("bad/{name}"));
        let direct = read_mesh(&path).unwrap_err().to_string();
        let raw = read_raw_mesh(&path).unwrap();
        let via_raw = raw.validate().unwrap_err().to_string();
        assert_eq!(direct, via_raw, "{name}");
    }
    for name in ["woody.obj", "gltf/woody.glb", "gltf/woody_soup.glb"] {
        let a = read_mesh(fixture(name)).unwrap();
        let b = read_raw_mesh(fixture(name)).unwrap().validate().unwrap();
        assert_eq!(a.mesh.positions(), b.mesh.positions(), "{name}");
        assert_eq!(a.mesh.faces(), b.mesh.faces(), "{name}");
        assert_eq!(a.uv, b.uv, "{name}");
        assert_eq!(a.source, b.source, "{name}");
    }
    // syntax errors are errors of the raw read already, and so is an empty file
    for name in ["garbage_line.obj", "index_zero.obj", "empty.obj"] {
        let path = fixture(&format!("bad/{name}"));
        assert_eq!(
            read_raw_mesh(&path).unwrap_err().to_string(),
            read_mesh(&path).unwrap_err().to_string()
        );
    }
}

#[test]
fn raw_reads_keep_every_defect_and_its_lines() {
    let raw = read_raw_mesh(fixture("bad/dirty_disk.obj")).unwrap();
    assert_eq!((raw.positions.len(), raw.faces.len()), (23, 26));
    let lines = raw.source.face_lines.as_ref().unwrap();
    assert_eq!((lines[0], lines[25]), (27, 52));
    assert_eq!(raw.source.vertex_lines.as_ref().unwrap()[7], 11);
    // no texture coordinates in the file
    assert!(raw.uv.is_none());
    let e = TriMesh::try_new(raw.positions.clone(), raw.faces.clone()).unwrap_err();
    assert_eq!(
        e,
        MeshError::UnreferencedVertex {
            vertex: 7,
            count: 1
        }
    );
    assert_eq!(raw.origin_of(&e), Some(Origin::Line(11)));
}

#[test]
fn new_defect_fixtures_name_kind_element_and_line() {
    let invalid = |name: &str| match read_mesh(fixture(&format!("bad/{name}"))).unwrap_err() {
        IoError::InvalidMesh { origin, source, .. } => (origin, source),
        other => panic!("{name}: expected InvalidMesh, got {other:?}"),
    };
    let (origin, e) = invalid("inf_coordinate.obj");
    assert_eq!(origin, Some(Origin::Line(4)));
    assert!(matches!(
        e,
        MeshError::NonFiniteCoordinate { vertex: 2, axis: 'z', value } if value == f64::INFINITY
    ));
    let (origin, e) = invalid("repeated_vertex.obj");
    assert_eq!(origin, Some(Origin::Line(7)));
    assert_eq!(e, MeshError::RepeatedVertexInFace { face: 1, vertex: 2 });
    // the Möbius strip: validation finds the twist as an orientation conflict on the
    // gluing quad, the last two faces (lines 32-33)
    let (origin, e) = invalid("mobius.obj");
    let MeshError::InconsistentOrientation { face, .. } = e else {
        panic!("{e:?}")
    };
    assert_eq!(origin, Some(Origin::Line(18 + face)));
    // several components are valid for the mesh crate; the topology says so
    let m = read_mesh(fixture("bad/two_components.obj")).unwrap();
    assert_eq!(
        m.mesh.topology(),
        Topology::SeveralComponents { components: 2 }
    );
}

#[test]
fn repairing_a_raw_read_and_naming_what_remains() {
    let raw = read_raw_mesh(fixture("bad/dirty_disk.obj")).unwrap();
    let r = repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT).unwrap();
    let log = &r.log;
    assert_eq!(log.duplicate_faces, 1);
    assert_eq!(log.components, 2);
    assert_eq!(log.component_faces_dropped, 1);
    assert_eq!(log.component_vertices_dropped, 3);
    assert_eq!(log.flipped_faces, 1);
    assert_eq!(log.unreferenced_vertices, 1);
    let m = TriMesh::try_new(r.positions, r.faces).unwrap();
    assert_eq!((m.num_vertices(), m.num_faces()), (19, 24));
    assert_eq!(m.topology(), Topology::Disk);

    // the Möbius strip cannot be oriented: the error names input faces, and their lines
    let raw = read_raw_mesh(fixture("bad/mobius.obj")).unwrap();
    let MeshError::NonOrientable { face, other, .. } =
        repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT).unwrap_err()
    else {
        panic!("expected NonOrientable")
    };
    let lines = raw.source.face_lines.as_ref().unwrap();
    assert!(face < 16 && other < 16);
    assert_eq!(lines[face], 18 + face);

    // a defect repair leaves alone is named in input numbering, at its input line
    let text = "v 0 0 0\nv 9 9 9\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 3 4\nf 1 3 4\nf 1 3 5\n";
    let raw = read_raw_mesh_from_bytes(text.as_bytes(), Format::Obj).unwrap();
    let r = repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT).unwrap();
    let e = TriMesh::try_new(r.positions, r.faces).unwrap_err();
    let e = r.log.to_input_error(e);
    assert!(
        matches!(e, MeshError::ZeroAreaFace { face: 2, .. }),
        "{e:?}"
    );
    match raw.invalid_mesh(e) {
        IoError::InvalidMesh { origin, .. } => assert_eq!(origin, Some(Origin::Line(8))),
        other => panic!("{other:?}"),
    }
}

#[test]
fn raw_gltf_names_primitive_triangles_and_vertices() {
    // two primitives: a square, then a copy of its first triangle (a duplicate face)
    let sq: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
    let mut pts = sq.to_vec();
    pts.extend([sq[0], sq[1], sq[2]]);
    let idx: Vec<u8> = [0u16, 1, 2, 0, 2, 3]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let mut bin = f32_bytes(&pts);
    let off = bin.len();
    bin.extend(idx);
    let len = bin.len();
    let doc = json!({
        "asset": { "version": "2.0" },
        "meshes": [{ "primitives": [
            { "attributes": { "POSITION": 0 }, "indices": 2 },
            { "attributes": { "POSITION": 1 } }
        ] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3" },
            { "bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3" },
            { "bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR" }
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
            { "buffer": 0, "byteOffset": 48, "byteLength": 36 },
            { "buffer": 0, "byteOffset": off, "byteLength": 12 }
        ],
        "buffers": [{ "byteLength": len }],
    });
    let bytes = glb(&doc, bin);
    let raw = read_raw_mesh_from_bytes(&bytes, Format::Glb).unwrap();
    assert_eq!((raw.positions.len(), raw.faces.len()), (4, 3)); // welded
    let err = read_mesh_from_bytes(&bytes, Format::Glb).unwrap_err();
    let IoError::InvalidMesh { origin, source, .. } = err else {
        panic!("{err:?}")
    };
    assert_eq!(source, MeshError::DuplicateFace { face: 2, first: 0 });
    let t = Origin::GltfTriangle {
        mesh: 0,
        primitive: 1,
        triangle: 0,
    };
    assert_eq!(origin, Some(t));
    assert_eq!(raw.origin_of(&source), Some(t));
    let e = MeshError::NonManifoldVertex {
        vertex: 3,
        faces: 1,
    };
    let v = Origin::GltfVertex {
        mesh: 0,
        primitive: 0,
        vertex: 3,
    };
    assert_eq!(raw.origin_of(&e), Some(v));
    // repaired: the duplicate goes, the square remains
    let r = repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT).unwrap();
    assert_eq!(r.log.duplicate_faces, 1);
    assert!(TriMesh::try_new(r.positions, r.faces).is_ok());
}
