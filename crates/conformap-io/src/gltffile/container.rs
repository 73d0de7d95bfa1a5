//! Checks of a glTF file's outer layer before the `gltf` crate parses it, so that the common
//! ways a file is not glTF 2.0 get a message that says which: a GLB header with the wrong
//! magic, version or lengths, a glTF 1.0 document, a data URI that is not base64.

use std::path::Path;

use crate::error::{IoError, WriteProblem, GLTF_HINT};
use crate::loaded::Format;

/// A GLB header: magic, version, total length (12 bytes).
const HEADER: usize = 12;
/// A GLB chunk header: length, type (8 bytes).
const CHUNK_HEADER: usize = 8;

/// The hint for a file that is glTF 1.0.
pub(crate) const GLTF1_HINT: &str = "convert it to glTF 2.0 (e.g. `gltf-pipeline -i IN -o OUT` \
                                     upgrades 1.0 files, or re-export from Blender), or export \
                                     an OBJ";
const HEADER_HINT: &str = "the file is truncated or not a GLB: re-export it (a GLB starts \
                           with `glTF`, version 2, then the file's length)";

/// A container-level [`IoError::GltfData`] (no mesh, primitive or accessor).
pub(crate) fn container_error(path: &Path, problem: impl Into<String>) -> IoError {
    IoError::GltfData {
        path: path.to_path_buf(),
        mesh: None,
        primitive: None,
        accessor: None,
        problem: problem.into(),
        hint: GLTF_HINT,
    }
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Checks the GLB header and chunk lengths (or, for a `.glb` name, that the file is a GLB
/// or JSON at all). `gltf` reports these as bare "unsupported version" or a JSON parse
/// error at line 1; the messages here give the numbers.
pub(crate) fn check_container(bytes: &[u8], path: &Path, format: Format) -> Result<(), IoError> {
    let err = |msg: String| container_error(path, msg).with_hint(HEADER_HINT);
    let Some(rest) = bytes.strip_prefix(b"glTF") else {
        let first = bytes.iter().find(|b| !b.is_ascii_whitespace());
        if format == Format::Glb && first != Some(&b'{') {
            let magic: Vec<String> = bytes.iter().take(4).map(|b| format!("{b:02x}")).collect();
            return Err(err(format!(
                "not a GLB file: it starts with the bytes {} (`{}`), a GLB with `glTF`",
                magic.join(" "),
                String::from_utf8_lossy(&bytes[..bytes.len().min(4)]).escape_debug()
            )));
        }
        return Ok(());
    };
    let (Some(version), Some(length)) = (u32_at(rest, 0), u32_at(rest, 4)) else {
        let msg = format!(
            "GLB header is truncated: the file has {} bytes",
            bytes.len()
        );
        return Err(err(msg));
    };
    if version == 1 {
        return Err(container_error(
            path,
            "GLB version 1 is glTF 1.0 (KHR_binary_glTF), which is not supported: only glTF 2.0",
        )
        .with_hint(GLTF1_HINT));
    }
    if version != 2 {
        let msg = format!("GLB version {version} is not supported (only version 2, glTF 2.0)");
        return Err(err(msg));
    }
    let length = length as usize;
    if length < HEADER || length > bytes.len() {
        return Err(err(format!(
            "the GLB header says the file is {length} bytes long, but it has {}",
            bytes.len()
        )));
    }
    // the JSON chunk, then at most one BIN chunk, each within `length`
    let mut at = HEADER;
    for name in ["JSON", "BIN"] {
        if name == "BIN" && at + CHUNK_HEADER > length {
            break; // no BIN chunk (padding bytes are ignored, as `gltf` does)
        }
        let Some(chunk) = u32_at(&bytes[..length], at) else {
            return Err(err(format!(
                "the GLB has no {name} chunk (it ends at byte {at})"
            )));
        };
        let chunk = chunk as usize;
        let available = length.saturating_sub(at + CHUNK_HEADER);
        if chunk > available {
            return Err(err(format!(
                "the {name} chunk at byte {at} says it is {chunk} bytes long, but only \
                 {available} bytes follow its header"
            )));
        }
        at += CHUNK_HEADER + chunk;
    }
    Ok(())
}

/// The bytes of a GLB: the 12-byte header, the JSON chunk (space-padded) and the BIN chunk
/// (zero-padded), as [`check_container`] reads them back.
///
/// # Errors
/// [`WriteProblem::TooLarge`] when a length does not fit the header's `u32`.
pub(super) fn encode_glb(mut json: Vec<u8>, mut bin: Vec<u8>) -> Result<Vec<u8>, WriteProblem> {
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = HEADER + CHUNK_HEADER + json.len() + CHUNK_HEADER + bin.len();
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

/// The JSON text of a glTF or GLB file (the JSON chunk of a GLB that passed
/// [`check_container`]).
fn json_text(bytes: &[u8]) -> &[u8] {
    match bytes.strip_prefix(b"glTF") {
        Some(_) => {
            let len = u32_at(bytes, HEADER).map_or(0, |l| l as usize);
            let start = HEADER + CHUNK_HEADER;
            bytes.get(start..start.saturating_add(len)).unwrap_or(&[])
        }
        None => bytes,
    }
}

/// After `gltf` failed to parse the JSON: the error for a glTF 1.0 document (its
/// `asset.version` starts with `1`, or its top-level collections are objects keyed by name
/// instead of arrays), if it is one.
pub(crate) fn gltf1_error(bytes: &[u8], path: &Path) -> Option<IoError> {
    let root: serde_json::Value = serde_json::from_slice(json_text(bytes)).ok()?;
    let version = root.pointer("/asset/version").and_then(|v| v.as_str());
    let keyed = ["meshes", "accessors", "buffers", "bufferViews", "nodes"]
        .iter()
        .any(|k| root.get(k).is_some_and(serde_json::Value::is_object));
    if !version.is_some_and(|v| v.starts_with('1')) && !keyed {
        return None;
    }
    let what = match version {
        Some(v) => format!("asset.version is \"{v}\""),
        None => "its meshes, accessors or buffers are keyed by name".to_string(),
    };
    let msg = format!("this is a glTF 1.0 file ({what}), which is not supported: only glTF 2.0");
    Some(container_error(path, msg).with_hint(GLTF1_HINT))
}

/// Checks a buffer's `data:` URI (`rest` is what follows `data:`): base64, with only base64
/// characters and a possible length. `gltf` would say "Invalid byte 64, offset 0." without
/// naming the buffer.
pub(crate) fn check_data_uri(rest: &str, buffer: usize, path: &Path) -> Result<(), IoError> {
    let hint = "the buffer embedded in the file is damaged: re-export the asset (or save it \
                as a GLB, which stores buffers as binary)";
    let err =
        |msg: String| container_error(path, format!("buffer {buffer}: {msg}")).with_hint(hint);
    let Some((header, payload)) = rest.split_once(',') else {
        return Err(err("its data URI has no `,` before the data".into()));
    };
    if !header.ends_with(";base64") {
        return Err(err(format!(
            "its data URI (`data:{header},…`) is not base64; glTF buffers are \
             `data:application/octet-stream;base64,…`"
        )));
    }
    let data = payload.trim_end_matches('=');
    if payload.len() - data.len() > 2 {
        return Err(err("its base64 data ends in more than two `=`".into()));
    }
    let valid = |c: &u8| c.is_ascii_alphanumeric() || *c == b'+' || *c == b'/';
    if let Some(k) = data.bytes().position(|c| !valid(&c)) {
        let c = data[k..].chars().next().unwrap_or('?');
        return Err(err(format!(
            "character `{}` at offset {k} of its data URI's base64 data is not base64 \
             (A–Z, a–z, 0–9, +, /, then at most two `=`)",
            c.escape_debug()
        )));
    }
    if data.len() % 4 == 1 {
        let msg = format!(
            "its base64 data has {} characters, a length no byte string encodes to (cut short?)",
            data.len()
        );
        return Err(err(msg));
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    fn glb(version: u32, length: u32, json_len: u32) -> Vec<u8> {
        let mut b = b"glTF".to_vec();
        for x in [version, length, json_len] {
            b.extend(x.to_le_bytes());
        }
        b.extend(b"JSON{}  ");
        b
    }

    #[test]
    fn glb_headers() {
        let p = Path::new("x.glb");
        let msg = |b: &[u8]| check_container(b, p, Format::Glb).unwrap_err().to_string();
        assert!(check_container(&glb(2, 24, 4), p, Format::Glb).is_ok());
        assert!(msg(b"glTF").contains("truncated"));
        assert!(msg(&glb(1, 24, 4)).contains("glTF 1.0"));
        assert!(msg(&glb(3, 24, 4)).contains("version 3"));
        assert!(msg(&glb(2, 4, 4)).contains("is 4 bytes long, but it has 24"));
        assert!(msg(&glb(2, 25, 4)).contains("is 25 bytes long"));
        assert!(msg(&glb(2, 24, 9)).contains("JSON chunk at byte 12 says it is 9 bytes"));
        assert!(msg(b"glTX\x02\0\0\0").contains("`glTX`"));
        assert!(check_container(b" {}", p, Format::Glb).is_ok());
        assert!(check_container(b"xyz", p, Format::Gltf).is_ok());
    }

    #[test]
    fn encoded_glbs_pass_the_checks() {
        let bytes = encode_glb(b"{}".to_vec(), vec![1, 2, 3, 4, 5]).unwrap();
        assert_eq!(bytes.len(), 12 + 8 + 4 + 8 + 8);
        assert_eq!(u32_at(&bytes, 8), Some(40));
        assert!(check_container(&bytes, Path::new("x.glb"), Format::Glb).is_ok());
        assert_eq!(json_text(&bytes), b"{}  ");
        assert_eq!(&bytes[32..], &[1, 2, 3, 4, 5, 0, 0, 0]);
    }

    #[test]
    fn data_uris() {
        let p = Path::new("x.gltf");
        let ok = |s: &str| check_data_uri(s, 0, p).is_ok();
        assert!(ok("application/octet-stream;base64,AAAA"));
        assert!(ok("application/gltf-buffer;base64,AAE="));
        assert!(ok(";base64,"));
        assert!(!ok("application/octet-stream,AAAA"));
        assert!(!ok("application/octet-stream;base64,AAAAA"));
        assert!(!ok("application/octet-stream;base64,AA==="));
        let e = check_data_uri(";base64,AB@C", 3, p)
            .unwrap_err()
            .to_string();
        assert!(e.contains("buffer 3: character `@` at offset 2"), "{e}");
    }

    #[test]
    fn gltf1_is_recognised() {
        let p = Path::new("x.gltf");
        assert!(gltf1_error(br#"{"asset":{"version":"1.0"}}"#, p).is_some());
        assert!(gltf1_error(br#"{"meshes":{"m":{}}}"#, p).is_some());
        assert!(gltf1_error(br#"{"asset":{"version":"2.0"},"meshes":[]}"#, p).is_none());
        assert!(gltf1_error(b"not json", p).is_none());
    }
}
