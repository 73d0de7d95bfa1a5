//! The frame directory of `conformap morph -o DIR/`: created when missing, and cleared of
//! the frames of an earlier run that this run did not write.

use std::path::{Path, PathBuf};

use crate::failure::Failure;

/// Creates the frame directory `-o DIR/` (and its parents) when it does not exist.
pub(crate) fn create_frame_directory(dir: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(dir).map_err(|e| {
        Failure::BadInput(
            format!("cannot create the frame directory {}: {e}", dir.display()),
            Some("check the parent directory's permissions, or write elsewhere".into()),
        )
    })
}

/// Whether `name` is a frame file this command writes: `frame_<4 or more digits>.obj`.
fn is_frame_name(name: &str) -> bool {
    name.strip_prefix("frame_")
        .and_then(|rest| rest.strip_suffix(".obj"))
        .is_some_and(|digits| digits.len() >= 4 && digits.bytes().all(|b| b.is_ascii_digit()))
}

/// Removes from `dir` the frame files of an earlier run that this run did not write
/// (`frame_0003.obj` … after a run of 3 frames that followed one of 10), so that a sequence
/// loader sees this run only; other files are left alone. The message says what went.
pub(crate) fn remove_stale_frames(dir: &Path, written: &[PathBuf]) -> Option<String> {
    let written: std::collections::HashSet<&std::ffi::OsStr> =
        written.iter().filter_map(|p| p.file_name()).collect();
    let mut removed: Vec<String> = std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .filter_map(|entry| {
            let name = entry.file_name();
            let stale =
                is_frame_name(&name.to_string_lossy()) && !written.contains(name.as_os_str());
            (stale && std::fs::remove_file(entry.path()).is_ok())
                .then(|| name.to_string_lossy().into_owned())
        })
        .collect();
    if removed.is_empty() {
        return None;
    }
    removed.sort();
    let range = match removed.as_slice() {
        [one] => one.clone(),
        [first, .., last] => format!("{first} … {last}"),
        [] => String::new(),
    };
    Some(format!(
        "{}: removed {} frame file(s) of an earlier run that this run did not write ({range})",
        dir.display(),
        removed.len()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_this_commands_frame_names_are_frames() {
        assert!(is_frame_name("frame_0000.obj") && is_frame_name("frame_12345.obj"));
        for other in [
            "frame_000.obj",
            "frame_0001.glb",
            "frame_00a1.obj",
            "myframe_0001.obj",
        ] {
            assert!(!is_frame_name(other), "{other}");
        }
    }

    #[test]
    fn stale_frames_go_and_everything_else_stays() {
        let dir = std::env::temp_dir().join(format!("conformap-frames-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        create_frame_directory(&dir.join("sub")).unwrap_or_default();
        let dir = dir.join("sub");
        assert!(dir.is_dir(), "the missing directory is created");
        let names = [
            "frame_0000.obj",
            "frame_0001.obj",
            "frame_0002.obj",
            "notes.txt",
        ];
        for n in names {
            std::fs::write(dir.join(n), "x").unwrap_or_default();
        }
        let written = vec![dir.join("frame_0000.obj")];
        let message = remove_stale_frames(&dir, &written).unwrap_or_default();
        assert!(
            message.contains("removed 2 frame file(s)")
                && message.contains("frame_0001.obj … frame_0002.obj"),
            "{message}"
        );
        let left: Vec<bool> = names.iter().map(|n| dir.join(n).exists()).collect();
        assert_eq!(left, [true, false, false, true]);
        assert_eq!(remove_stale_frames(&dir, &written), None);
        let _ = std::fs::remove_dir_all(dir.parent().unwrap_or(&dir));
    }
}
