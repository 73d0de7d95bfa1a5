//! glTF/GLB writing: one mesh, one triangle primitive with `POSITION`, optional
//! `TEXCOORD_0` and `u32` indices, in one buffer (a data URI in `.gltf`, the `BIN` chunk in
//! `.glb`).
//!
//! glTF stores vertex attributes as f32: positions and texture coordinates are rounded to
//! the nearest f32 (relative error ≤ 2⁻²⁴ ≈ 6e-8). Texture coordinates are written in the
//! glTF convention `(s, t) = (u, 1 − v)` (origin top-left); the reader converts back.

use serde_json::{json, Value};

use crate::error::WriteProblem;

const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;

/// Encodes a `.glb` (`binary`) or a `.gltf` with an embedded base64 buffer. `uv`, if given,
/// has one entry per position; faces index positions (checked by the caller).
pub(crate) fn encode_gltf(
    binary: bool,
    positions: &[[f64; 3]],
    uv: Option<&[[f64; 2]]>,
    faces: &[[u32; 3]],
) -> Result<Vec<u8>, WriteProblem> {
    if positions.is_empty() || faces.is_empty() {
        return Err(WriteProblem::Empty);
    }
    let n = positions.len();
    let mut bin: Vec<u8> = Vec::with_capacity(n * 20 + faces.len() * 12);
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for (vertex, p) in positions.iter().enumerate() {
        for k in 0..3 {
            let x = to_f32(p[k], vertex)?;
            lo[k] = lo[k].min(x);
            hi[k] = hi[k].max(x);
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    let pos_len = bin.len();
    if let Some(uv) = uv {
        for (vertex, t) in uv.iter().enumerate() {
            bin.extend_from_slice(&to_f32(t[0], vertex)?.to_le_bytes());
            bin.extend_from_slice(&to_f32(1.0 - t[1], vertex)?.to_le_bytes());
        }
    }
    let uv_len = bin.len() - pos_len;
    for &i in faces.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let idx_len = bin.len() - pos_len - uv_len;
    if u32::try_from(bin.len() + (1 << 20)).is_err() {
        return Err(WriteProblem::TooLarge);
    }

    let mut views = vec![view(0, pos_len, ARRAY_BUFFER)];
    let mut accessors = vec![json!({
        "bufferView": 0, "componentType": FLOAT, "count": n, "type": "VEC3",
        "min": lo, "max": hi,
    })];
    let mut attributes = json!({ "POSITION": 0 });
    if uv.is_some() {
        views.push(view(pos_len, uv_len, ARRAY_BUFFER));
        accessors.push(json!({
            "bufferView": 1, "componentType": FLOAT, "count": n, "type": "VEC2",
        }));
        attributes["TEXCOORD_0"] = json!(1);
    }
    views.push(view(pos_len + uv_len, idx_len, ELEMENT_ARRAY_BUFFER));
    accessors.push(json!({
        "bufferView": views.len() - 1, "componentType": UNSIGNED_INT,
        "count": 3 * faces.len(), "type": "SCALAR",
    }));
    let mut buffer = json!({ "byteLength": bin.len() });
    if !binary {
        buffer["uri"] = Value::String(format!(
            "data:application/octet-stream;base64,{}",
            base64(&bin)
        ));
    }
    let doc = json!({
        "asset": { "version": "2.0", "generator": "conformap-io" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0 }],
        "meshes": [{ "primitives": [{
            "attributes": attributes, "indices": accessors.len() - 1, "mode": 4,
        }] }],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [buffer],
    });
    let text = doc.to_string();
    if binary {
        glb(text.into_bytes(), bin)
    } else {
        Ok(text.into_bytes())
    }
}

fn view(offset: usize, length: usize, target: u32) -> Value {
    json!({ "buffer": 0, "byteOffset": offset, "byteLength": length, "target": target })
}

fn to_f32(x: f64, vertex: usize) -> Result<f32, WriteProblem> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(WriteProblem::NonFinite { vertex, value: x })
    }
}

/// GLB container: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded).
fn glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>, WriteProblem> {
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let u = |x: usize| u32::try_from(x).map_err(|_| WriteProblem::TooLarge);
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&u(total)?.to_le_bytes());
    out.extend_from_slice(&u(json.len())?.to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&u(bin.len())?.to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    Ok(out)
}

/// Standard base64 with padding (RFC 4648).
fn base64(data: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(data.len().div_ceil(3) * 4);
    for chunk in data.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(n >> (18 - 6 * k)) as usize & 63]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, coded) in cases {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
    }
}
