//! Writing a file so that it is either complete or absent: a temporary file in the same
//! directory, written, then renamed over the target.
//!
//! No `fsync`: "complete or absent" is promised against this process's own failures (an
//! error, a full disk, a kill) and to concurrent readers, which the rename gives. Forcing
//! the bytes to the device cost 40–100 ms on a 7 MB map (a third of writing it) and
//! seconds on network file systems, and buys durability across a power cut, which is the
//! file system's business (ext4 and XFS flush a file renamed over another before the
//! rename commits).

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::IoError;
use crate::objfile::Encoded;

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` atomically (on the same file system, rename replaces the target
/// in one step). On failure the temporary file is removed and `path` is untouched.
///
/// # Errors
/// [`IoError::Write`] if the temporary file cannot be created, written or renamed.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    write_with_atomically(path, |file| file.write_all(bytes))
}

/// [`write_atomically`] of an OBJ text formatted as it is written (see
/// [`Encoded::write_to`]).
///
/// # Errors
/// As [`write_atomically`].
pub(crate) fn write_encoded_atomically(path: &Path, text: &Encoded<'_>) -> Result<(), IoError> {
    write_with_atomically(path, |file| text.write_to(file))
}

/// [`write_atomically`] of whatever `write` writes to the file.
fn write_with_atomically(
    path: &Path,
    write: impl FnOnce(&mut fs::File) -> std::io::Result<()>,
) -> Result<(), IoError> {
    let tmp = temp_sibling(path);
    let result = (|| {
        let mut file = fs::File::create(&tmp)?;
        write(&mut file)?;
        drop(file);
        fs::rename(&tmp, path)
    })();
    result.map_err(|source| {
        let _ = fs::remove_file(&tmp);
        IoError::Write {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// `dir/.name.conformap-PID-N.tmp` beside `path`.
fn temp_sibling(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp_name = format!(".{name}.conformap-{}-{n}.tmp", std::process::id());
    path.with_file_name(tmp_name)
}
