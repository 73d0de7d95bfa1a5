//! Guards around the `gltf` crate's buffer import, which can panic or read without bound on
//! a few hostile inputs, and names the buffer in its errors.

use std::path::{Path, PathBuf};

use gltf::buffer::{Data, Source};

use super::container::{check_data_uri, container_error};
use crate::error::IoError;

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
        if let Some(rest) = uri.strip_prefix("data:") {
            check_data_uri(rest, buffer.index(), path)?;
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
                return Err(container_error(path, msg).with_hint(
                    "put the buffer file next to the .gltf (its URI is relative to the .gltf), \
                     or save the asset as one GLB",
                ));
            }
        }
    }
    gltf::import_buffers(doc, base, blob).map_err(|source| import_error(source, path))
}

/// `gltf`'s import errors, in words that name the buffer where `gltf` knows it.
fn import_error(source: gltf::Error, path: &Path) -> IoError {
    let msg = match source {
        gltf::Error::BufferLength {
            buffer,
            expected,
            actual,
        } => format!(
            "buffer {buffer}: its byteLength is {expected} bytes, but its data has only \
             {actual} (a truncated .bin file or data URI)"
        ),
        gltf::Error::MissingBlob => "a buffer without `uri` refers to the GLB's BIN chunk, \
                                     but the file has none"
            .to_string(),
        gltf::Error::ExternalReferenceInSliceImport => "a buffer refers to an external file, \
                                                         but the glTF was given as bytes \
                                                         (no directory to look in)"
            .to_string(),
        gltf::Error::UnsupportedScheme => "a buffer URI has an unsupported scheme (only \
                                           relative paths, file: and data: URIs are read)"
            .to_string(),
        source => {
            return IoError::Gltf {
                path: path.to_path_buf(),
                source,
            }
        }
    };
    container_error(path, msg)
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
}
