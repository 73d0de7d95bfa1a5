//! glTF/GLB writing: one mesh, one triangle primitive with `POSITION`, optional
//! `TEXCOORD_0` and `u32` indices, in one buffer (a data URI in `.gltf`, the `BIN` chunk in
//! `.glb`).
//!
//! glTF stores vertex attributes as f32: positions and texture coordinates are rounded to
//! the nearest f32 (relative error ≤ 2⁻²⁴ ≈ 6e-8). Texture coordinates are written in the
//! glTF convention `(s, t) = (u, 1 − v)` (origin top-left); the reader converts back.

use serde_json::{json, Value};

use crate::error::WriteProblem;

use super::container::encode_glb;

/// glTF component type `FLOAT`.
pub(super) const FLOAT: u32 = 5126;
/// glTF component type `UNSIGNED_INT`.
pub(super) const UNSIGNED_INT: u32 = 5125;
/// glTF buffer view target of vertex attributes.
pub(super) const ARRAY_BUFFER: u32 = 34962;
/// glTF buffer view target of indices.
pub(super) const ELEMENT_ARRAY_BUFFER: u32 = 34963;

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
    let (lo, hi) = push_vec3(&mut bin, positions)?;
    let pos_len = bin.len();
    if let Some(uv) = uv {
        for (vertex, t) in uv.iter().enumerate() {
            bin.extend_from_slice(&f32_of(t[0], vertex)?.to_le_bytes());
            bin.extend_from_slice(&f32_of(1.0 - t[1], vertex)?.to_le_bytes());
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
        encode_glb(text.into_bytes(), bin)
    } else {
        Ok(text.into_bytes())
    }
}

fn view(offset: usize, length: usize, target: u32) -> Value {
    json!({ "buffer": 0, "byteOffset": offset, "byteLength": length, "target": target })
}

/// `x` rounded to f32; [`WriteProblem::NonFinite`] naming `vertex` (the row) if that is not
/// finite.
pub(super) fn f32_of(x: f64, vertex: usize) -> Result<f32, WriteProblem> {
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(WriteProblem::NonFinite { vertex, value: x })
    }
}

/// Appends `points` as f32 VEC3 and returns (min, max).
pub(super) fn push_vec3(
    bin: &mut Vec<u8>,
    points: &[[f64; 3]],
) -> Result<([f32; 3], [f32; 3]), WriteProblem> {
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for (vertex, p) in points.iter().enumerate() {
        for k in 0..3 {
            let x = f32_of(p[k], vertex)?;
            lo[k] = lo[k].min(x);
            hi[k] = hi[k].max(x);
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
    Ok((lo, hi))
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
