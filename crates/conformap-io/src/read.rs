//! Reading a file without validating it: the format by extension (or magic), the bytes,
//! and the reader of the format ([`read_raw_mesh`], [`read_raw_mesh_from_bytes`]).

use std::path::Path;

use crate::error::IoError;
use crate::gltffile::read_gltf_raw;
use crate::loaded::{Format, VertexText};
use crate::objfile::read_obj_raw;
use crate::raw::RawMesh;

/// The name errors use for data that did not come from a file.
const MEMORY: &str = "<memory>";

/// Reads the triangles of an `.obj`, `.gltf` or `.glb` file (by extension) without
/// validating them: the same parsing, triangulation, node transforms and welding as
/// [`read_mesh`](crate::read_mesh), which is this followed by [`RawMesh::validate`].
///
/// # Errors
/// As [`read_mesh`](crate::read_mesh), except that [`IoError::InvalidMesh`] only comes for
/// a file with no vertex at all (`NoVertices`).
///
/// # Examples
/// ```no_run
/// let raw = conformap_io::read_raw_mesh("fixtures/bad/duplicate_face.obj")?;
/// assert_eq!(raw.source.face_lines.as_deref(), Some(&[5, 6][..]));
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn read_raw_mesh(path: impl AsRef<Path>) -> Result<RawMesh, IoError> {
    let path = path.as_ref();
    let named = Format::from_path(path);
    let bytes = read_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    // a FreeSurfer surface (`lh.white`) or a file named otherwise is known by its magic
    let format = match named {
        Ok(format) => format,
        Err(e) => Format::sniff(&bytes)
            .or_else(|| freesurfer_name(path))
            .ok_or(e)?,
    };
    match format {
        Format::Obj => {
            let (mut raw, spans) = read_obj_raw(&bytes, path)?;
            // the bytes move into the source (no copy) for the writer to reuse
            raw.source.vertex_text = Some(std::sync::Arc::new(VertexText::new(bytes, spans)));
            Ok(raw)
        }
        Format::Gltf | Format::Glb => {
            let base = path.parent().unwrap_or(Path::new(""));
            read_gltf_raw(&bytes, path, Some(base), format)
        }
        other => read_other_raw(&bytes, path, other),
    }
}

/// FreeSurfer for a name like `lh.mysurf` or `rh.x` (whose extension names no format): its
/// reader then says what is wrong with the magic.
fn freesurfer_name(path: &Path) -> Option<Format> {
    let name = path.file_name()?.to_str()?;
    (name.starts_with("lh.") || name.starts_with("rh.")).then_some(Format::FreeSurfer)
}

/// The readers of PLY, STL, OFF, GIfTI and FreeSurfer surfaces.
fn read_other_raw(bytes: &[u8], path: &Path, format: Format) -> Result<RawMesh, IoError> {
    match format {
        Format::Ply => crate::plyfile::read_ply_raw(bytes, path),
        Format::Stl => crate::stlfile::read_stl_raw(bytes, path),
        Format::Off => crate::offfile::read_off_raw(bytes, path),
        Format::Gifti => crate::gifti::read_gifti_raw(bytes, path),
        Format::FreeSurfer => crate::freesurfer::read_freesurfer_raw(bytes, path),
        Format::Obj | Format::Gltf | Format::Glb => Ok(read_obj_raw(bytes, path)?.0),
    }
}

/// Files at least this large are read by all threads at once, each its own part.
const PARALLEL_READ_MIN_BYTES: u64 = 1 << 20;

/// The bytes of a file, as [`std::fs::read`] gives them. A large file is read in parts on
/// all threads at once: the copy from the page cache into fresh memory costs a page fault
/// per 4 KiB, which both cores then share (a 3.7 MB mesh: 4–7 ms read alone).
#[cfg(unix)]
fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    use rayon::prelude::*;
    use std::io::{Read, Seek, SeekFrom};
    use std::os::unix::fs::FileExt;

    let mut file = std::fs::File::open(path)?;
    let len = file.metadata()?.len();
    if len < PARALLEL_READ_MIN_BYTES {
        let mut bytes = Vec::new();
        file.read_to_end(&mut bytes)?;
        return Ok(bytes);
    }
    let mut bytes = vec![0u8; usize::try_from(len).map_err(std::io::Error::other)?];
    let part = bytes.len().div_ceil(rayon::current_num_threads().max(1));
    bytes
        .par_chunks_mut(part)
        .enumerate()
        .try_for_each(|(k, chunk)| file.read_exact_at(chunk, (k * part) as u64))?;
    // what a file that grew meanwhile has beyond, as a plain read would have it
    file.seek(SeekFrom::Start(len))?;
    file.read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The bytes of a file ([`std::fs::read`]).
#[cfg(not(unix))]
fn read_file(path: &Path) -> std::io::Result<Vec<u8>> {
    std::fs::read(path)
}

/// [`read_raw_mesh`] from bytes already in memory (tests, fuzzing); errors name the file
/// `<memory>` and a glTF that refers to external files is an error.
///
/// # Errors
/// As [`read_raw_mesh`].
pub fn read_raw_mesh_from_bytes(bytes: &[u8], format: Format) -> Result<RawMesh, IoError> {
    let path = Path::new(MEMORY);
    match format {
        Format::Obj => Ok(read_obj_raw(bytes, path)?.0),
        Format::Gltf | Format::Glb => read_gltf_raw(bytes, path, None, format),
        other => read_other_raw(bytes, path, other),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    /// A file large enough to be read in parts comes back byte for byte, parts of an odd
    /// size included; so does a small one.
    #[test]
    fn files_read_in_parts_are_whole() {
        let dir = std::env::temp_dir().join(format!("conformap-io-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for len in [0usize, 10, (3 << 20) + 7] {
            let bytes: Vec<u8> = (0..len).map(|i| (i * 7 + i / 4099) as u8).collect();
            let path = dir.join(format!("f{len}.bin"));
            std::fs::write(&path, &bytes).unwrap();
            assert!(read_file(&path).unwrap() == bytes, "{len} bytes");
        }
        assert!(read_file(&dir.join("absent.obj")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
