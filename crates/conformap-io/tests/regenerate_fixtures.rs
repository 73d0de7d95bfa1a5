//! Regenerates the glTF fixtures in `fixtures/gltf/` (on purpose only):
//! `cargo test -p conformap-io --test regenerate_fixtures -- --ignored`
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::{f32_bytes, fixture, planar_uv};
use conformap_io::{read_mesh, write_flat, write_mesh_with_uv};

#[test]
#[ignore = "rewrites committed fixtures"]
fn regenerate_gltf_fixtures() {
    let dir = fixture("gltf");
    std::fs::create_dir_all(&dir).unwrap();
    let woody = read_mesh(fixture("woody.obj")).unwrap().mesh;

    // woody with a stand-in planar map, written by our GLB writer
    let uv = planar_uv(woody.positions());
    write_mesh_with_uv(dir.join("woody.glb"), &woody, &uv, None).unwrap();

    // the same surface as a triangle soup: every face has its own three vertices
    let mut soup = Vec::new();
    let mut faces = Vec::new();
    for f in woody.faces() {
        let k = soup.len() as u32;
        soup.extend(f.iter().map(|&i| woody.positions()[i as usize]));
        faces.push([k, k + 1, k + 2]);
    }
    write_flat(dir.join("woody_soup.glb"), &soup, &faces).unwrap();

    // a hand-made unit quad with an external .bin, u16 indices and a translated node
    let pos: [[f32; 3]; 4] = [[0., 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]];
    let mut bin = f32_bytes(&pos);
    for i in [0u16, 1, 2, 0, 2, 3] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.join("quad external.bin"), &bin).unwrap();
    let json = serde_json::json!({
        "asset": { "version": "2.0", "generator": "hand-made for conformap-io tests" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "translation": [10.0, 0.0, 0.0] }],
        "meshes": [{ "name": "quad", "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
              "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0] },
            { "bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR" }
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 48 },
            { "buffer": 0, "byteOffset": 48, "byteLength": 12 }
        ],
        "buffers": [{ "byteLength": 60, "uri": "quad%20external.bin" }]
    });
    let text = serde_json::to_string_pretty(&json).unwrap();
    std::fs::write(dir.join("quad_external.gltf"), text + "\n").unwrap();
}
