//! Shared helpers for the integration tests.
#![allow(dead_code)] // each test binary uses a different subset

use std::path::PathBuf;

/// `fixtures/NAME` at the workspace root.
pub fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
}

/// A fresh, empty directory for one test's output files.
pub fn out_dir(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("conformap-io")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create test output directory");
    dir
}

/// A texture coordinate per vertex: the (x, y) position scaled into [0, 1]² (a stand-in map).
pub fn planar_uv(positions: &[[f64; 3]]) -> Vec<[f64; 2]> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in positions {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    positions
        .iter()
        .map(|p| {
            [
                (p[0] - lo[0]) / (hi[0] - lo[0]),
                (p[1] - lo[1]) / (hi[1] - lo[1]),
            ]
        })
        .collect()
}

/// A GLB container around `json` and `bin` (for hand-made glTF tests).
pub fn glb(json: &serde_json::Value, mut bin: Vec<u8>) -> Vec<u8> {
    let mut j = json.to_string().into_bytes();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = (12 + 8 + j.len() + 8 + bin.len()) as u32;
    let mut out = Vec::new();
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total.to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}

/// Little-endian f32 bytes of the points.
pub fn f32_bytes(points: &[[f32; 3]]) -> Vec<u8> {
    points
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect()
}
