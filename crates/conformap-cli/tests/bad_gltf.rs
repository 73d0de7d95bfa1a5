//! The bad glTF/GLB files of `fixtures/bad/` through the binary (issue 18): `info` and
//! `disk` refuse each with exit 1 (bad input, `failure.rs`), a message that names the file,
//! the problem and its place, a `hint:` line, and no output file or report.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use support::{conformap, fixture, s, stderr, tmpdir};

/// Each bad file, a part of its message and a part of its hint.
const BAD: &[(&str, &str, &str)] = &[
    (
        "lines_only.gltf",
        "lines_only.gltf: mesh 0, primitive 0, the file has no triangles: its primitives are \
         LINES (mode 1)",
        "hint: export the surface as triangles",
    ),
    (
        "points_only.gltf",
        "points_only.gltf: mesh 0, primitive 0, the file has no triangles: its primitives \
         are POINTS (mode 0)",
        "point cloud",
    ),
    (
        "bad_base64.gltf",
        "bad_base64.gltf: buffer 0: character `@` at offset 0",
        "hint: the buffer embedded in the file is damaged",
    ),
    (
        "missing_buffer.gltf",
        "missing_buffer.gltf: buffer 0 refers to `",
        "hint: put the buffer file next to the .gltf",
    ),
    (
        "short_buffer.gltf",
        "short_buffer.gltf: buffer 0: its byteLength is 4096 bytes, but its data has only 44",
        "hint: re-export the asset",
    ),
    (
        "accessor_out_of_range.gltf",
        "accessor_out_of_range.gltf: mesh 0, primitive 0, accessor 0, POSITION: 30 elements",
        "hint: re-export the asset",
    ),
    (
        "gltf1.gltf",
        "gltf1.gltf: this is a glTF 1.0 file (asset.version is \"1.0\"), which is not supported",
        "hint: convert it to glTF 2.0",
    ),
    (
        "bad_magic.glb",
        "bad_magic.glb: not a GLB file: it starts with the bytes 67 6c 54 58 (`glTX`)",
        "hint: the file is truncated or not a GLB",
    ),
    (
        "bad_version.glb",
        "bad_version.glb: GLB version 1 is glTF 1.0",
        "hint: convert it to glTF 2.0",
    ),
    (
        "bad_chunk_length.glb",
        "bad_chunk_length.glb: the JSON chunk at byte 12 says it is 4524 bytes long",
        "hint: the file is truncated or not a GLB",
    ),
    (
        "bad_total_length.glb",
        "bad_total_length.glb: the GLB header says the file is 100000 bytes long, but it has 596",
        "hint: the file is truncated or not a GLB",
    ),
];

#[test]
fn info_and_disk_refuse_bad_gltf_with_exit_1_place_and_hint_and_write_nothing() {
    let d = tmpdir("bad_gltf");
    for (name, message, hint) in BAD {
        let file = fixture(&format!("bad/{name}"));
        let (out, report) = (d.join("o.obj"), d.join("r.json"));
        let disk = ["disk", s(&file), "-o", s(&out), "--report", s(&report)];
        for args in [&["info", s(&file)][..], &disk[..]] {
            let o = conformap(args);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
            assert!(
                err.contains(message),
                "{args:?}: expected `{message}` in:\n{err}"
            );
            assert!(err.contains(hint), "{args:?}: expected `{hint}` in:\n{err}");
            assert!(
                err.trim_end().lines().last().unwrap().starts_with("hint: "),
                "{err}"
            );
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert!(!out.exists() && !report.exists(), "{args:?} left an output");
        }
    }
}

#[test]
fn a_data_uri_gltf_is_read() {
    let o = conformap(&["info", s(&fixture("gltf/triangle_data_uri.gltf"))]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains('3') && text.contains('1'), "{text}");
}
