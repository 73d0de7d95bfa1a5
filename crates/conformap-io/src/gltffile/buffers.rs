//! Loading a glTF's buffers (the GLB `BIN` chunk, data URIs, external files) with errors
//! that name the buffer, and guards against the inputs that could panic or read without
//! bound.

use std::path::{Path, PathBuf};

use gltf::buffer::Source;

use super::container::{check_data_uri, container_error};
use crate::error::IoError;

/// The bytes of every buffer of a document, in buffer order (each zero-padded to a multiple
/// of 4, as glTF readers do).
pub(crate) type Buffers = Vec<Vec<u8>>;

/// Loads every buffer: the GLB `BIN` chunk, data URIs, or files relative to `base`.
///
/// Reads the buffers itself (not through `gltf`'s importer, which would bring image
/// decoders in): a data URI is checked and decoded here, a referenced file must be a
/// regular file (not a device or FIFO, which could be read forever), and every buffer must
/// hold at least its `byteLength`.
pub(crate) fn load_buffers(
    doc: &gltf::Document,
    base: Option<&Path>,
    mut blob: Option<Vec<u8>>,
    path: &Path,
) -> Result<Buffers, IoError> {
    let mut buffers = Vec::with_capacity(doc.buffers().len());
    for buffer in doc.buffers() {
        let mut data = match buffer.source() {
            Source::Bin => blob.take().ok_or_else(|| {
                container_error(
                    path,
                    "a buffer without `uri` refers to the GLB's BIN chunk, but the file has none",
                )
            })?,
            Source::Uri(uri) => read_uri(uri, buffer.index(), base, path)?,
        };
        while data.len() % 4 != 0 {
            data.push(0);
        }
        if data.len() < buffer.length() {
            return Err(container_error(
                path,
                format!(
                    "buffer {}: its byteLength is {} bytes, but its data has only {} (a \
                     truncated .bin file or data URI)",
                    buffer.index(),
                    buffer.length(),
                    data.len()
                ),
            ));
        }
        buffers.push(data);
    }
    Ok(buffers)
}

/// The bytes a buffer's `uri` refers to: a base64 data URI, a `file:` path, or a path
/// relative to `base` (percent-decoded). Without `base` (bytes read from memory) only
/// data URIs are read.
fn read_uri(
    uri: &str,
    buffer: usize,
    base: Option<&Path>,
    path: &Path,
) -> Result<Vec<u8>, IoError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        check_data_uri(rest, buffer, path)?;
        let payload = rest.split_once(',').map_or("", |(_, p)| p);
        return Ok(base64_decode(payload));
    }
    // a `file:` path is taken as it is; any other is relative to the .gltf's directory
    let (target, relative) = if let Some(rest) = uri.strip_prefix("file:") {
        (
            PathBuf::from(rest.strip_prefix("//").unwrap_or(rest)),
            false,
        )
    } else if uri.contains(':') {
        return Err(container_error(
            path,
            "a buffer URI has an unsupported scheme (only relative paths, file: and data: \
             URIs are read)",
        ));
    } else {
        let decoded = percent_decode(uri).ok_or_else(|| {
            container_error(path, format!("buffer URI `{uri}` does not decode to UTF-8"))
        })?;
        (PathBuf::from(decoded), true)
    };
    let Some(base) = base else {
        return Err(container_error(
            path,
            "a buffer refers to an external file, but the glTF was given as bytes (no \
             directory to look in)",
        ));
    };
    let target = if relative { base.join(target) } else { target };
    if !target.is_file() {
        let msg = format!(
            "buffer {buffer} refers to `{}`, which is not a readable file",
            target.display()
        );
        return Err(container_error(path, msg).with_hint(
            "put the buffer file next to the .gltf (its URI is relative to the .gltf), \
             or save the asset as one GLB",
        ));
    }
    std::fs::read(&target).map_err(|e| IoError::Gltf {
        path: path.to_path_buf(),
        source: gltf::Error::Io(e),
    })
}

/// Decodes base64 that [`check_data_uri`] accepted (standard alphabet, at most two
/// trailing `=`, a length some byte string encodes to); any other character counts as 0.
fn base64_decode(text: &str) -> Vec<u8> {
    let digit = |c: u8| -> u32 {
        match c {
            b'A'..=b'Z' => u32::from(c - b'A'),
            b'a'..=b'z' => u32::from(c - b'a') + 26,
            b'0'..=b'9' => u32::from(c - b'0') + 52,
            b'+' => 62,
            b'/' => 63,
            _ => 0,
        }
    };
    let data = text.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(data.len() * 3 / 4);
    for chunk in data.chunks(4) {
        let n = chunk
            .iter()
            .enumerate()
            .fold(0u32, |n, (k, &c)| n | (digit(c) << (18 - 6 * k)));
        let bytes = [(n >> 16) as u8, (n >> 8) as u8, n as u8];
        // 2, 3 or 4 characters carry 1, 2 or 3 bytes
        out.extend_from_slice(&bytes[..chunk.len().saturating_sub(1)]);
    }
    out
}

/// Decodes `%XX` escapes (invalid escapes stay literal, as in `urlencoding`); `None` if the
/// result is not UTF-8.
fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |k: usize| b.get(k).and_then(|&c| (c as char).to_digit(16));
        match (b[i], hex(i + 1), hex(i + 2)) {
            (b'%', Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            (c, _, _) => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_rfc4648_vectors() {
        let cases = [
            ("", ""),
            ("Zg==", "f"),
            ("Zm8=", "fo"),
            ("Zm9v", "foo"),
            ("Zm9vYg==", "foob"),
            ("Zm9vYmE=", "fooba"),
            ("Zm9vYmFy", "foobar"),
            ("Zm9vYg", "foob"),
        ];
        for (coded, plain) in cases {
            assert_eq!(base64_decode(coded), plain.as_bytes(), "{coded}");
        }
    }

    #[test]
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b.bin").as_deref(), Some("a b.bin"));
        assert_eq!(percent_decode("%zz%4").as_deref(), Some("%zz%4"));
        assert_eq!(percent_decode("%FF.bin"), None);
    }
}
