//! OBJ reading: vertex order, relative indices, polygons, objects, tolerated statements,
//! per-vertex texture coordinates, and every bad fixture's error kind and line.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::fixture;
use conformap_io::{
    read_mesh, read_mesh_from_bytes, Format, IoError, LoadedMesh, ObjProblem, Origin, UvProblem,
};
use conformap_mesh::MeshError;

fn obj(text: &str) -> Result<LoadedMesh, IoError> {
    read_mesh_from_bytes(text.as_bytes(), Format::Obj)
}

/// Positions of the `v` lines, parsed independently of the reader.
fn v_lines(text: &str) -> Vec<[f64; 3]> {
    text.lines()
        .filter_map(|l| l.strip_prefix("v "))
        .map(|l| {
            let x: Vec<f64> = l.split_whitespace().map(|t| t.parse().unwrap()).collect();
            [x[0], x[1], x[2]]
        })
        .collect()
}

#[test]
fn woody_keeps_file_vertex_order_and_faces() {
    let path = fixture("woody.obj");
    let text = std::fs::read_to_string(&path).unwrap();
    let loaded = read_mesh(&path).unwrap();
    assert_eq!(loaded.mesh.num_vertices(), 694);
    assert_eq!(loaded.mesh.num_faces(), 1267);
    // bit-exact and in file order (the first face starts at vertex 167, not vertex 1)
    assert_eq!(loaded.mesh.positions(), v_lines(&text).as_slice());
    assert_eq!(loaded.mesh.faces()[0], [166, 96, 165]);
    let lines = loaded.source.vertex_lines.as_ref().unwrap();
    assert_eq!(lines[0], 5); // after the 4 comment lines
    assert_eq!(loaded.source.face_lines.as_ref().unwrap()[0], 5 + 694);
    assert!(loaded.uv.is_none());
    assert_eq!(loaded.uv_problem, Some(UvProblem::Absent));
    assert!(matches!(
        loaded.per_vertex_uv(),
        Err(IoError::NotPerVertexUv {
            problem: UvProblem::Absent,
            ..
        })
    ));
}

#[test]
fn all_real_fixtures_read() {
    let cases = [
        ("alligator.obj", 3208, 5981),
        ("spothead.obj", 4537, 9024),
        ("punctured_torus.obj", 4599, 9184),
        ("halftunnel.obj", 831, 1568),
        ("spot.obj", 2930, 5856),
        ("eightsim.obj", 173, 350),
    ];
    for (name, v, f) in cases {
        let m = read_mesh(fixture(name)).unwrap().mesh;
        assert_eq!((m.num_vertices(), m.num_faces()), (v, f), "{name}");
    }
}

#[test]
fn negative_indices_are_relative_to_the_vertices_so_far() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 1 1 0\nf -3 -1 -2\n";
    let m = obj(text).unwrap().mesh;
    assert_eq!(m.faces(), &[[0, 1, 2], [1, 3, 2]]);
    // and running past the start is an error naming the line
    let err = obj("v 0 0 0\nv 1 0 0\nf -1 -2 -3\n").unwrap_err();
    assert!(matches!(
        err,
        IoError::ObjSyntax {
            line: 3,
            problem: ObjProblem::IndexOutOfRange {
                index: -3,
                count: 2,
                ..
            },
            ..
        }
    ));
}

#[test]
fn polygons_are_fan_triangulated_with_their_line() {
    // a convex pentagon on line 7, a quad on line 8
    let text = "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nv 1 -1 0\n\
                f 1 2 3 4 5\nf 1 6 2\n";
    let loaded = obj(text).unwrap();
    assert_eq!(
        loaded.mesh.faces(),
        &[[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 5, 1]]
    );
    assert_eq!(loaded.source.face_lines.unwrap(), vec![7, 7, 7, 8]);
}

#[test]
fn two_objects_keep_global_indices_and_file_order() {
    let text = "mtllib scene.mtl\n\
                o first\n\
                v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
                usemtl red\n\
                f 2 4 3\nf 1 2 3\n\
                o second\n\
                g part\n\
                v 2 0 0\nv 2 1 0\n\
                usemtl blue\n\
                f 2 5 4\nf -2 -1 4\n";
    let loaded = obj(text).unwrap();
    let m = &loaded.mesh;
    assert_eq!(m.positions(), v_lines(text).as_slice());
    assert_eq!(m.faces(), &[[1, 3, 2], [0, 1, 2], [1, 4, 3], [4, 5, 3]]);
    assert_eq!(loaded.source.face_lines.unwrap(), vec![8, 9, 15, 16]);
    assert_eq!(loaded.source.file_vertex_count, 6);
}

#[test]
fn tolerated_statements_and_crlf() {
    let text = "# comment\r\n\r\nmtllib a.mtl\r\ng g1\r\ns 1\r\nv 0 0 0 1\r\nv 1 0 0\r\n\
                v 0 1 0 0.5 0.5 0.5\r\nvn 0 0 1\r\nvt 0 0\r\nvp 0.5\r\nusemtl m\r\n\
                f 1//1 2//1 3//1\r\nl 1 2\r\n";
    let loaded = obj(text).unwrap();
    assert_eq!(loaded.mesh.positions()[2], [0.0, 1.0, 0.0]); // colour dropped
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2]]);
    assert_eq!(loaded.source.notes.len(), 1, "{:?}", loaded.source.notes);
    // v x y z w divides by w, as tobj does
    let m = obj("v 2 4 6 2\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap().mesh;
    assert_eq!(m.positions()[0], [1.0, 2.0, 3.0]);
}

#[test]
fn per_vertex_texture_coordinates() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
                vt 0.25 0.5\nvt 0.125 1e-7\nvt 1 0\nvt 1 1\n\
                f 1/3 2/4 3/1\nf 2/4 4/2 3/1\n";
    let loaded = obj(text).unwrap();
    let uv = loaded.per_vertex_uv().unwrap();
    assert_eq!(uv, &[[1.0, 0.0], [1.0, 1.0], [0.25, 0.5], [0.125, 1e-7]]);
    // the same value under two vt indices is not a seam
    let dup = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0 0\n\
               f 1/1 2/2 3/3\n";
    assert!(obj(dup).unwrap().uv.is_some());
}

#[test]
fn uv_seam_and_missing_vt_name_the_line() {
    let loaded = read_mesh(fixture("bad/uv_seam.obj")).unwrap();
    assert!(loaded.uv.is_none());
    let err = loaded.per_vertex_uv().unwrap_err();
    assert!(
        matches!(
            &err,
            IoError::NotPerVertexUv {
                problem: UvProblem::Seam {
                    vertex: 1,
                    origin: Origin::Line(11),
                    first: Origin::Line(10),
                },
                ..
            }
        ),
        "{err:?}"
    );
    assert!(err.to_string().contains("uv_seam.obj:11"), "{err}");
    let missing = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\n\
                   f 1/1 2/1 3/1\nf 2 4 3\n";
    let loaded = obj(missing).unwrap();
    assert_eq!(
        loaded.uv_problem,
        Some(UvProblem::Missing {
            origin: Origin::Line(7)
        })
    );
}

fn invalid(name: &str) -> (Option<Origin>, MeshError) {
    match read_mesh(fixture(&format!("bad/{name}"))).unwrap_err() {
        IoError::InvalidMesh { origin, source, .. } => (origin, source),
        other => panic!("{name}: expected InvalidMesh, got {other:?}"),
    }
}

fn syntax(name: &str) -> (usize, ObjProblem) {
    match read_mesh(fixture(&format!("bad/{name}"))).unwrap_err() {
        IoError::ObjSyntax { line, problem, .. } => (line, problem),
        other => panic!("{name}: expected ObjSyntax, got {other:?}"),
    }
}

#[test]
fn bad_fixtures_give_the_specific_error_and_line() {
    let (origin, e) = invalid("nan_coordinate.obj");
    assert_eq!(origin, Some(Origin::Line(3)));
    assert!(matches!(
        e,
        MeshError::NonFiniteCoordinate {
            vertex: 1,
            axis: 'y',
            ..
        }
    ));

    let (line, p) = syntax("index_out_of_range.obj");
    assert_eq!(line, 5);
    assert!(matches!(
        p,
        ObjProblem::IndexOutOfRange {
            what: "vertex",
            index: 4,
            count: 3
        }
    ));

    let (line, p) = syntax("index_zero.obj");
    assert_eq!((line, p), (5, ObjProblem::IndexZero { what: "vertex" }));

    let (origin, e) = invalid("nonmanifold_edge.obj");
    assert_eq!(origin, Some(Origin::Line(9)));
    assert!(matches!(
        e,
        MeshError::NonManifoldEdge {
            a: 0,
            b: 1,
            count: 3,
            ..
        }
    ));

    let (origin, e) = invalid("bowtie_vertex.obj");
    assert_eq!(origin, Some(Origin::Line(2)));
    assert!(matches!(e, MeshError::NonManifoldVertex { vertex: 0, .. }));

    let (origin, e) = invalid("inconsistent_orientation.obj");
    assert_eq!(origin, Some(Origin::Line(7)));
    assert!(matches!(
        e,
        MeshError::InconsistentOrientation {
            face: 1,
            other: 0,
            ..
        }
    ));

    let (origin, e) = invalid("duplicate_face.obj");
    assert_eq!(origin, Some(Origin::Line(6)));
    assert!(matches!(e, MeshError::DuplicateFace { face: 1, first: 0 }));

    let (origin, e) = invalid("degenerate_face.obj");
    assert_eq!(origin, Some(Origin::Line(7)));
    assert!(matches!(e, MeshError::ZeroAreaFace { face: 1, .. }));

    let (origin, e) = invalid("unreferenced_vertex.obj");
    assert_eq!(origin, Some(Origin::Line(4)));
    assert!(matches!(
        e,
        MeshError::UnreferencedVertex {
            vertex: 2,
            count: 1
        }
    ));

    let (origin, e) = invalid("empty.obj");
    assert_eq!((origin, e), (None, MeshError::NoVertices));

    let (origin, e) = invalid("no_faces.obj");
    assert_eq!((origin, e), (None, MeshError::NoFaces { vertices: 3 }));

    let (line, p) = syntax("garbage_line.obj");
    assert_eq!(line, 4);
    assert_eq!(
        p,
        ObjProblem::UnknownStatement {
            keyword: "hello".into()
        }
    );

    // found by re-scanning after tobj rejects the number
    let (line, p) = syntax("bad_number.obj");
    assert_eq!(
        (line, p),
        (
            3,
            ObjProblem::BadNumber {
                keyword: "v".into(),
                text: "O.5".into(),
            }
        )
    );

    let (line, p) = syntax("too_few_corners.obj");
    assert_eq!((line, p), (5, ObjProblem::TooFewCorners { found: 2 }));
}

#[test]
fn messages_name_file_and_line() {
    let err = read_mesh(fixture("bad/degenerate_face.obj")).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("degenerate_face.obj:7: face 1 is degenerate"),
        "{msg}"
    );
    let err = read_mesh(fixture("bad/garbage_line.obj")).unwrap_err();
    assert!(
        err.to_string().contains("garbage_line.obj:4: `hello`"),
        "{err}"
    );
}

#[test]
fn hostile_text_is_an_error_not_a_panic() {
    let cases: &[&[u8]] = &[
        b"v 0 0 0\nvt 0 0\nf 1/0 1/1 1/1\n",
        b"v 0 0 0\nvt 0 0\nf 1/3074457345618258602 1 1\n",
        b"v 0 0 0\nvn 0 0 1\nf 1//-9223372036854775808 1 1\n",
        b"v 1 2 3 0\nv 0 0 0\nv 1 1 1\nf 1 2 3\n",
        b"v 1 2\n",
        b"v 1 2 3 4 5\n",
        b"vt\n",
        b"f\n",
        b"f 1 2 3\n",
        b"\xff\xfe",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 \xc3\n",
        b"usemtl\nv 0 0 0\n",
    ];
    for bytes in cases {
        assert!(
            read_mesh_from_bytes(bytes, Format::Obj).is_err(),
            "{bytes:?}"
        );
    }
    let err = read_mesh_from_bytes(b"v 0 0 0\n\xff\n", Format::Obj).unwrap_err();
    assert!(matches!(
        err,
        IoError::ObjSyntax {
            line: 2,
            problem: ObjProblem::NotUtf8,
            ..
        }
    ));
}

#[test]
fn unknown_extension_and_missing_file() {
    // neither the extension nor the first bytes name a mesh format
    assert!(matches!(
        read_mesh(fixture("README.md")),
        Err(IoError::UnknownFormat { .. })
    ));
    assert!(matches!(
        read_mesh(fixture("no_such_file.obj")),
        Err(IoError::Read { .. })
    ));
}

/// Inputs that common OBJ readers accept: a trailing comment, `f v//vn` without `vn`
/// lines; and number errors that quote the text, say when it overflowed, and speak of
/// `w` only where there is one.
#[test]
fn common_obj_inputs_and_number_messages() {
    let tri = "v 0 0 0 # origin\nv 1 0 0\t# x\nv 0 1 0 #\nvt 0 0 # uv\nf 1 2 3 # face\n";
    let loaded = read_mesh_from_bytes(tri.as_bytes(), Format::Obj).unwrap();
    assert_eq!(loaded.mesh.positions()[1], [1.0, 0.0, 0.0]);
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2]]);
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4 # quad\n";
    let loaded = read_mesh_from_bytes(quad.as_bytes(), Format::Obj).unwrap();
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);

    let normals = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n";
    let loaded = read_mesh_from_bytes(normals.as_bytes(), Format::Obj).unwrap();
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2]]);
    // with `vn` lines, a normal index is still checked
    let err = read_mesh_from_bytes(b"v 0 0 0\nvn 0 0 1\nf 1//2 1//1 1//1\n", Format::Obj);
    assert!(matches!(
        err,
        Err(IoError::ObjSyntax {
            problem: ObjProblem::IndexOutOfRange { what: "normal", .. },
            ..
        })
    ));

    let msg = |text: &str| {
        read_mesh_from_bytes(text.as_bytes(), Format::Obj)
            .unwrap_err()
            .to_string()
    };
    let m = msg("v 1 O.5 0\n");
    assert!(
        m.contains("`O.5` is not a number") && !m.contains("w = 0"),
        "{m}"
    );
    let m = msg("vt 0 x\n");
    assert!(m.contains("`x`") && !m.contains("w = 0"), "{m}");
    let m = msg("v 1e400 0 0\n");
    assert!(m.contains("`1e400` overflows"), "{m}");
    let m = msg("v 1 2 3 0\n");
    assert!(m.contains("w = 0"), "{m}");
}
