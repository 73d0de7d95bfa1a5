//! The bad glTF/GLB files of `fixtures/bad/`: each is refused with a message that names the
//! problem and its place, and a hint; the valid forms next to them (base64 data URIs, a
//! one-triangle GLB) are read.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::fixture;
use conformap_io::{read_mesh, read_mesh_from_bytes, Format};

/// Each bad file, a part of its message (after the file name) and a part of its hint.
const BAD: &[(&str, &str, &str)] = &[
    (
        "lines_only.gltf",
        ": mesh 0, primitive 0, the file has no triangles: its primitives are LINES (mode 1)",
        "export the surface as triangles",
    ),
    (
        "points_only.gltf",
        ": mesh 0, primitive 0, the file has no triangles: its primitives are POINTS (mode 0)",
        "point cloud",
    ),
    (
        "bad_base64.gltf",
        ": buffer 0: character `@` at offset 0 of its data URI's base64 data is not base64",
        "embedded in the file is damaged",
    ),
    (
        "missing_buffer.gltf",
        "buffer 0 refers to `",
        "put the buffer file next to the .gltf",
    ),
    (
        "short_buffer.gltf",
        ": buffer 0: its byteLength is 4096 bytes, but its data has only 44",
        "Khronos glTF validator",
    ),
    (
        "accessor_out_of_range.gltf",
        ": mesh 0, primitive 0, accessor 0, POSITION: 30 elements do not fit in the bufferView",
        "Khronos glTF validator",
    ),
    (
        "gltf1.gltf",
        ": this is a glTF 1.0 file (asset.version is \"1.0\"), which is not supported",
        "gltf-pipeline",
    ),
    (
        "bad_magic.glb",
        ": not a GLB file: it starts with the bytes 67 6c 54 58 (`glTX`)",
        "a GLB starts with `glTF`",
    ),
    (
        "bad_version.glb",
        ": GLB version 1 is glTF 1.0 (KHR_binary_glTF), which is not supported",
        "gltf-pipeline",
    ),
    (
        "bad_chunk_length.glb",
        ": the JSON chunk at byte 12 says it is 4524 bytes long, but only 576 bytes follow",
        "truncated or not a GLB",
    ),
    (
        "bad_total_length.glb",
        ": the GLB header says the file is 100000 bytes long, but it has 596",
        "truncated or not a GLB",
    ),
];

#[test]
fn bad_gltf_files_name_the_problem_and_the_place() {
    for (name, message, hint) in BAD {
        let path = fixture(&format!("bad/{name}"));
        let e = read_mesh(&path).map(|_| ()).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.starts_with(&path.display().to_string()),
            "{name}: {msg}"
        );
        assert!(msg.contains(message), "{name}: {msg}");
        assert!(e.hint().contains(hint), "{name}: hint `{}`", e.hint());
    }
}

#[test]
fn data_uri_buffers_are_read_from_a_file_and_from_bytes() {
    let path = fixture("gltf/triangle_data_uri.gltf");
    let from_file = read_mesh(&path).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let from_bytes = read_mesh_from_bytes(&bytes, Format::Gltf).unwrap();
    for m in [&from_file.mesh, &from_bytes.mesh] {
        assert_eq!(m.faces(), &[[0, 1, 2]]);
        assert_eq!(m.positions()[1], [1.0, 0.0, 0.0]);
    }
    // the same triangle in a GLB's BIN chunk
    let glb = read_mesh(fixture("gltf/triangle.glb")).unwrap();
    assert_eq!(glb.mesh.positions(), from_file.mesh.positions());
}

#[test]
fn a_mixed_file_keeps_its_triangles_and_notes_the_lines() {
    // the lines fixture with its primitive duplicated as triangles: read, with a note
    let text = std::fs::read_to_string(fixture("bad/lines_only.gltf")).unwrap();
    let mut doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let prims = doc["meshes"][0]["primitives"].as_array_mut().unwrap();
    let mut tri = prims[0].clone();
    tri["mode"] = 4.into();
    prims.push(tri);
    let bytes = serde_json::to_vec(&doc).unwrap();
    let raw = conformap_io::read_raw_mesh_from_bytes(&bytes, Format::Gltf).unwrap();
    assert_eq!(raw.faces.len(), 1);
    let notes = raw.source.notes.join("\n");
    assert!(
        notes.contains("primitive 0: mode LINES (mode 1) is not triangles"),
        "{notes}"
    );
}
