//! glTF reading on small hand-made assets: primitive modes, transforms, texture
//! coordinates, and errors that name mesh, primitive and accessor.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::{f32_bytes, glb};
use conformap_io::{read_mesh_from_bytes, Format, IoError, LoadedMesh, Origin, UvProblem};
use conformap_mesh::MeshError;
use serde_json::{json, Value};

/// A unit square's corners, counter-clockwise.
const SQUARE: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];

/// One-mesh GLB: `bin` holds positions first; `prims` and `accessors` are spliced in.
fn asset(prims: Value, accessors: Value, views: Value, bin: Vec<u8>, nodes: Value) -> Vec<u8> {
    let len = bin.len();
    let doc = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": nodes,
        "meshes": [{ "primitives": prims }],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": len }],
    });
    glb(&doc, bin)
}

fn vec3(view: usize, count: usize) -> Value {
    json!({ "bufferView": view, "componentType": 5126, "count": count, "type": "VEC3" })
}

fn view(offset: usize, length: usize) -> Value {
    json!({ "buffer": 0, "byteOffset": offset, "byteLength": length })
}

fn read(bytes: &[u8]) -> Result<LoadedMesh, IoError> {
    read_mesh_from_bytes(bytes, Format::Glb)
}

/// The square as a non-indexed primitive of the given mode and corner order.
fn square_with_mode(mode: u32, order: [usize; 4], nodes: Value) -> Vec<u8> {
    let pts: Vec<[f32; 3]> = order.iter().map(|&i| SQUARE[i]).collect();
    asset(
        json!([{ "attributes": { "POSITION": 0 }, "mode": mode },
               { "attributes": { "POSITION": 0 }, "mode": 0 }]),
        json!([vec3(0, 4)]),
        json!([view(0, 48)]),
        f32_bytes(&pts),
        nodes,
    )
}

#[test]
fn strips_and_fans_are_expanded_and_points_ignored() {
    // strip 0 1 3 2: triangles (0 1 3) and (3 1 2) after the odd-triangle swap
    let strip = read(&square_with_mode(5, [0, 1, 3, 2], json!([{ "mesh": 0 }]))).unwrap();
    assert_eq!(strip.mesh.faces(), &[[0, 1, 2], [2, 1, 3]]);
    assert_eq!(strip.mesh.boundary_loops().len(), 1);
    assert!(strip
        .source
        .notes
        .iter()
        .any(|n| n.contains("POINTS (mode 0)")));
    // fan around corner 0: (1 2 0), (2 3 0)
    let fan = read(&square_with_mode(6, [0, 1, 2, 3], json!([{ "mesh": 0 }]))).unwrap();
    assert_eq!(fan.mesh.faces(), &[[1, 2, 0], [2, 3, 0]]);
    assert_eq!(fan.mesh.boundary_loops()[0], vec![0, 1, 2, 3]);
}

#[test]
fn node_transforms_apply_and_mirrors_flip_winding() {
    let nodes = json!([
        { "children": [1], "translation": [0.0, 0.0, 5.0] },
        { "mesh": 0, "scale": [-2.0, 1.0, 1.0] }
    ]);
    let m = read(&square_with_mode(6, [0, 1, 2, 3], nodes))
        .unwrap()
        .mesh;
    assert_eq!(m.positions()[1], [-2.0, 0.0, 5.0]);
    // the mirror reverses the winding, so faces are flipped back to face outward
    assert_eq!(m.faces(), &[[1, 0, 2], [2, 0, 3]]);
}

#[test]
fn no_scene_reads_every_mesh_untransformed() {
    let doc = json!({
        "asset": { "version": "2.0" },
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 } }] }],
        "accessors": [vec3(0, 3)],
        "bufferViews": [view(0, 36)],
        "buffers": [{ "byteLength": 36 }],
    });
    let m = read(&glb(&doc, f32_bytes(&SQUARE[..3]))).unwrap().mesh;
    assert_eq!(m.num_faces(), 1);
}

/// Two triangles sharing the diagonal, each with its own vertices and TEXCOORD_0.
fn split_square(uv: [[f32; 2]; 6]) -> Vec<u8> {
    let pts = [
        SQUARE[0], SQUARE[1], SQUARE[2], SQUARE[0], SQUARE[2], SQUARE[3],
    ];
    let mut bin = f32_bytes(&pts);
    bin.extend(uv.iter().flatten().flat_map(|x| x.to_le_bytes()));
    asset(
        json!([{ "attributes": { "POSITION": 0, "TEXCOORD_0": 1 } }]),
        json!([vec3(0, 6), { "bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC2" }]),
        json!([view(0, 72), view(72, 48)]),
        bin,
        json!([{ "mesh": 0 }]),
    )
}

#[test]
fn texcoords_follow_the_weld_and_seams_are_reported() {
    let st = [[0., 1.], [1., 1.], [1., 0.], [0., 1.], [1., 0.], [0., 0.]];
    let ok = read(&split_square(st)).unwrap();
    assert_eq!(ok.mesh.num_vertices(), 4);
    assert_eq!(ok.source.weld_map.as_deref(), Some(&[0, 1, 2, 0, 2, 3][..]));
    // (s, t) -> (s, 1 - t)
    assert_eq!(
        ok.per_vertex_uv().unwrap(),
        &[[0., 0.], [1., 0.], [1., 1.], [0., 1.]]
    );
    let mut seam = st;
    seam[4] = [0.5, 0.5];
    let cut = read(&split_square(seam)).unwrap();
    assert_eq!(
        cut.uv_problem,
        Some(UvProblem::Seam {
            vertex: 2,
            origin: Origin::GltfVertex {
                mesh: 0,
                primitive: 0,
                vertex: 4
            },
            first: Origin::GltfVertex {
                mesh: 0,
                primitive: 0,
                vertex: 2
            },
        })
    );
}

#[test]
fn normalized_u16_texcoords() {
    let mut bin = f32_bytes(&SQUARE[..3]);
    for t in [0u16, 65535, 65535, 65535, 0, 0] {
        bin.extend_from_slice(&t.to_le_bytes());
    }
    let bytes = asset(
        json!([{ "attributes": { "POSITION": 0, "TEXCOORD_0": 1 } }]),
        json!([vec3(0, 3), { "bufferView": 1, "componentType": 5123, "normalized": true,
                              "count": 3, "type": "VEC2" }]),
        json!([view(0, 36), view(36, 12)]),
        bin,
        json!([{ "mesh": 0 }]),
    );
    let uv = read(&bytes).unwrap().uv.unwrap();
    assert_eq!(uv, vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
}

fn data_error(bytes: &[u8]) -> (Option<usize>, Option<usize>, Option<usize>, String) {
    match read(bytes).unwrap_err() {
        IoError::GltfData {
            mesh,
            primitive,
            accessor,
            problem,
            ..
        } => (mesh, primitive, accessor, problem),
        other => panic!("expected GltfData, got {other:?}"),
    }
}

#[test]
fn accessor_errors_name_mesh_primitive_and_accessor() {
    // index 7 of 3 positions, in accessor 1
    let mut bin = f32_bytes(&SQUARE[..3]);
    bin.extend([0u8, 1, 7, 0]);
    let bytes = asset(
        json!([{ "attributes": { "POSITION": 0 }, "indices": 1 }]),
        json!([vec3(0, 3), { "bufferView": 1, "componentType": 5121, "count": 3, "type": "SCALAR" }]),
        json!([view(0, 36), view(36, 3)]),
        bin,
        json!([{ "mesh": 0 }]),
    );
    let (m, p, a, msg) = data_error(&bytes);
    assert_eq!((m, p, a), (Some(0), Some(0), Some(1)));
    assert!(msg.contains("index 7"), "{msg}");

    // positions claimed past the end of their view
    let bytes = asset(
        json!([{ "attributes": { "POSITION": 0 } }]),
        json!([vec3(0, 1000)]),
        json!([view(0, 36)]),
        f32_bytes(&SQUARE[..3]),
        json!([{ "mesh": 0 }]),
    );
    assert_eq!(data_error(&bytes).2, Some(0));

    // no POSITION
    let bytes = asset(
        json!([{ "attributes": { "NORMAL": 0 } }]),
        json!([vec3(0, 3)]),
        json!([view(0, 36)]),
        f32_bytes(&SQUARE[..3]),
        json!([{ "mesh": 0 }]),
    );
    // (the gltf crate's validation catches this one; its path names mesh and primitive)
    let err = read(&bytes).unwrap_err();
    assert!(matches!(err, IoError::Gltf { .. }));
    let msg = err.to_string();
    assert!(
        msg.contains(r#"meshes[0].primitives[0].attributes["POSITION"]"#),
        "{msg}"
    );

    // a node cycle
    let cyc = square_with_mode(4, [0, 1, 2, 3], json!([{ "mesh": 0, "children": [0] }]));
    assert!(data_error(&cyc).3.contains("node 0"));
}

#[test]
fn invalid_mesh_errors_name_the_primitive_triangle() {
    let pts = [
        SQUARE[0], SQUARE[1], SQUARE[2], SQUARE[0], SQUARE[1], SQUARE[2],
    ];
    let bytes = asset(
        json!([{ "attributes": { "POSITION": 0 } }]),
        json!([vec3(0, 6)]),
        json!([view(0, 72)]),
        f32_bytes(&pts),
        json!([{ "mesh": 0 }]),
    );
    match read(&bytes).unwrap_err() {
        IoError::InvalidMesh { origin, source, .. } => {
            assert!(matches!(
                source,
                MeshError::DuplicateFace { face: 1, first: 0 }
            ));
            let t = Origin::GltfTriangle {
                mesh: 0,
                primitive: 0,
                triangle: 1,
            };
            assert_eq!(origin, Some(t));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn hostile_containers_are_errors_not_panics() {
    let cases: Vec<Vec<u8>> = vec![
        b"glTF\x02\0\0\0\x04\0\0\0".to_vec(),
        b"glTF".to_vec(),
        b"glTF\x02\0\0\0\xff\xff\xff\xff\x10\0\0\0JSON{}".to_vec(),
        b"{".to_vec(),
        Vec::new(),
        br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"%FF.bin"}]}"#.to_vec(),
        br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"x.bin"}]}"#.to_vec(),
        br#"{"asset":{"version":"2.0"},"buffers":[{"byteLength":4,"uri":"data:,abc"}]}"#.to_vec(),
        // POSITION names a missing accessor (gltf-json's validation would index it)
        br#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":3}}]}]}"#
            .to_vec(),
    ];
    for bytes in &cases {
        assert!(
            read_mesh_from_bytes(bytes, Format::Gltf).is_err(),
            "{bytes:?}"
        );
    }
    // stride smaller than an element, sparse accessor
    let bad_stride = asset(
        json!([{ "attributes": { "POSITION": 0 } }]),
        json!([vec3(0, 3)]),
        json!([{ "buffer": 0, "byteOffset": 0, "byteLength": 36, "byteStride": 4 }]),
        f32_bytes(&SQUARE[..3]),
        json!([{ "mesh": 0 }]),
    );
    assert!(read(&bad_stride).is_err());
    let mut sparse = vec3(0, 3);
    sparse["sparse"] = json!({ "count": 1,
        "indices": { "bufferView": 0, "componentType": 5121 },
        "values": { "bufferView": 0 } });
    let sparse = asset(
        json!([{ "attributes": { "POSITION": 0 } }]),
        json!([sparse]),
        json!([view(0, 36)]),
        f32_bytes(&SQUARE[..3]),
        json!([{ "mesh": 0 }]),
    );
    assert!(data_error(&sparse).3.contains("sparse"));
}
