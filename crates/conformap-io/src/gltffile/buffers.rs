//! Guards around the `gltf` crate's container parsing and buffer import, which can panic
//! or read without bound on a few hostile inputs; the checks here turn those into errors.

use std::path::{Path, PathBuf};

use gltf::buffer::{Data, Source};

use crate::error::IoError;

fn container_error(path: &Path, problem: impl Into<String>) -> IoError {
    IoError::GltfData {
        path: path.to_path_buf(),
        mesh: None,
        primitive: None,
        accessor: None,
        problem: problem.into(),
    }
}

/// Rejects a GLB header whose length field is smaller than the header itself (`gltf`
/// subtracts without checking).
pub(crate) fn check_container(bytes: &[u8], path: &Path) -> Result<(), IoError> {
    if let Some(rest) = bytes.strip_prefix(b"glTF") {
        let length = rest
            .get(4..8)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        if length.is_none_or(|l| l < 12) {
            return Err(container_error(
                path,
                "GLB header is truncated or its length is < 12",
            ));
        }
    }
    Ok(())
}

/// Loads every buffer: the GLB `BIN` chunk, data URIs, or files relative to `base`.
///
/// Before handing a URI to `gltf`, checks that its percent-decoding is UTF-8 (`gltf`
/// unwraps it) and that a referenced file is a regular file (not a device or FIFO, which
/// could be read forever).
pub(crate) fn load_buffers(
    doc: &gltf::Document,
    base: Option<&Path>,
    blob: Option<Vec<u8>>,
    path: &Path,
) -> Result<Vec<Data>, IoError> {
    for buffer in doc.buffers() {
        let Source::Uri(uri) = buffer.source() else {
            continue;
        };
        if uri.starts_with("data:") {
            continue;
        }
        let target = if let Some(rest) = uri.strip_prefix("file:") {
            Some(PathBuf::from(rest.strip_prefix("//").unwrap_or(rest)))
        } else if uri.contains(':') {
            None // unsupported scheme: gltf reports it
        } else {
            let decoded = percent_decode(uri).ok_or_else(|| {
                container_error(path, format!("buffer URI `{uri}` does not decode to UTF-8"))
            })?;
            base.map(|b| b.join(decoded))
        };
        if let (Some(target), Some(_)) = (target, base) {
            if !target.is_file() {
                let msg = format!(
                    "buffer {} refers to `{}`, which is not a readable file",
                    buffer.index(),
                    target.display()
                );
                return Err(container_error(path, msg));
            }
        }
    }
    gltf::import_buffers(doc, base, blob).map_err(|source| IoError::Gltf {
        path: path.to_path_buf(),
        source,
    })
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
    fn percent_decoding() {
        assert_eq!(percent_decode("a%20b.bin").as_deref(), Some("a b.bin"));
        assert_eq!(percent_decode("%zz%4").as_deref(), Some("%zz%4"));
        assert_eq!(percent_decode("%FF.bin"), None);
    }

    #[test]
    fn short_glb_header_is_an_error() {
        let p = Path::new("x.glb");
        assert!(check_container(b"glTF\x02\0\0\0\x04\0\0\0", p).is_err());
        assert!(check_container(b"glTF", p).is_err());
        assert!(check_container(b"{}", p).is_ok());
    }
}
