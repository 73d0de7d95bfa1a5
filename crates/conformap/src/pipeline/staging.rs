//! Staging files: the short hidden names outputs are written under before
//! [`crate::pipeline::Staged::commit`] renames them into place, the registry of the ones
//! this process has now (so that an interrupted run removes them, [`abandon_staged`]), and
//! the removal of those a killed run left behind ([`remove_stale_staging`]).
//!
//! A staging file is `.cmstage-<pid>-<n>.<ext>` beside its target (the extension kept: the
//! writers choose the format by it); while it is written the writer's own temporary file
//! is `..cmstage-<pid>-<n>.<ext>.conformap-<pid>-<m>.tmp`. Neither embeds the target's name,
//! so a target name of any legal length can be staged.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The prefix of every staging file name: `.cmstage-<pid>-<n>[.<ext>]`.
pub const STAGE_PREFIX: &str = ".cmstage-";

/// Prefixes of staging files: ours, the writers' temporary files of ours (one more dot),
/// and those of earlier versions (`.conformap-stage-<pid>-<n>-<name>`), all followed by the
/// pid of the process that made them.
const STALE_PREFIXES: [&str; 4] = [
    ".cmstage-",
    "..cmstage-",
    ".conformap-stage-",
    "..conformap-stage-",
];

/// The longest target extension a staging name keeps (a longer one names no mesh format).
const MAX_EXTENSION: usize = 16;

/// How long [`abandon_staged`] waits before looking again for staging files that a writer
/// was creating while it removed the others.
const SETTLE: std::time::Duration = std::time::Duration::from_millis(30);

static NEXT: AtomicU64 = AtomicU64::new(0);

/// Set by [`abandon_staged`]: writers check it before each file ([`interrupted`]).
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Whether the run was interrupted ([`abandon_staged`]): a writer of many files stops.
pub(crate) fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::SeqCst)
}

/// The staging files of this process that exist or are being written now.
struct Registry {
    paths: BTreeSet<PathBuf>,
    abandoned: bool,
}

static REGISTRY: Mutex<Registry> = Mutex::new(Registry {
    paths: BTreeSet::new(),
    abandoned: false,
});

fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The directory `path` is in (`.` for a bare file name).
pub(crate) fn directory_of(path: &Path) -> PathBuf {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf()
}

/// A new registered staging path beside `target`: `.cmstage-<pid>-<n>.<ext>`.
pub(crate) fn stage_path(target: &Path) -> PathBuf {
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let pid = std::process::id();
    let name = match target
        .extension()
        .and_then(|e| e.to_str())
        .filter(|e| e.len() <= MAX_EXTENSION)
    {
        Some(ext) => format!("{STAGE_PREFIX}{pid}-{n}.{ext}"),
        None => format!("{STAGE_PREFIX}{pid}-{n}"),
    };
    let path = directory_of(target).join(name);
    registry().paths.insert(path.clone());
    path
}

/// Removes staged files that will not be committed and forgets them.
pub(crate) fn discard(paths: &[&Path]) {
    let mut reg = registry();
    for p in paths {
        let _ = std::fs::remove_file(p);
        reg.paths.remove(*p);
    }
}

/// Renames every `(staged, target)` pair in order, under the registry's lock (an interrupt
/// then waits until all are renamed, or finds none renamed). On the first failure returns
/// its index and error; the pairs from there on are left to the caller.
pub(crate) fn rename_all(files: &[(PathBuf, PathBuf)]) -> Result<(), (usize, std::io::Error)> {
    let mut reg = registry();
    if reg.abandoned {
        return Err((
            0,
            std::io::Error::new(std::io::ErrorKind::Interrupted, "the run was interrupted"),
        ));
    }
    for (k, (staged, target)) in files.iter().enumerate() {
        std::fs::rename(staged, target).map_err(|e| (k, e))?;
        reg.paths.remove(staged);
    }
    Ok(())
}

/// What an interrupted run does before it exits (the CLI on SIGINT and SIGTERM): removes
/// every staging file of this process (and the writers' temporary files beside them), and
/// keeps the registry locked so that nothing is staged or committed afterwards. Returns how
/// many files it removed. Call it once, right before the process exits.
pub fn abandon_staged() -> usize {
    INTERRUPTED.store(true, Ordering::SeqCst);
    let mut reg = registry();
    reg.abandoned = true;
    let dirs: BTreeSet<PathBuf> = reg.paths.iter().map(|p| directory_of(p)).collect();
    let mine = format!("{STAGE_PREFIX}{}-", std::process::id());
    let mut removed = remove_matching(&dirs, &mine);
    // a writer may have been creating its file while the first pass ran
    std::thread::sleep(SETTLE);
    removed += remove_matching(&dirs, &mine);
    // held until the process exits: no writer stages or commits anything now
    std::mem::forget(reg);
    removed
}

/// Removes the files in `dirs` whose name is `prefix…` or `.prefix…`.
fn remove_matching(dirs: &BTreeSet<PathBuf>, prefix: &str) -> usize {
    let mut removed = 0;
    for dir in dirs {
        let Ok(entries) = std::fs::read_dir(dir) else {
            continue;
        };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            // a writer's temporary file has one more leading dot
            let bare = name
                .strip_prefix('.')
                .filter(|n| n.starts_with('.'))
                .unwrap_or(&name);
            if bare.starts_with(prefix) && std::fs::remove_file(entry.path()).is_ok() {
                removed += 1;
            }
        }
    }
    removed
}

/// The pid in a staging file's name, if `name` is one.
fn staging_pid(name: &str) -> Option<u32> {
    let rest = STALE_PREFIXES
        .iter()
        .rev()
        .find_map(|p| name.strip_prefix(p))?;
    let digits: &str = rest.split('-').next()?;
    if digits.is_empty() || !rest[digits.len()..].starts_with('-') {
        return None;
    }
    digits.parse().ok()
}

/// Whether process `pid` runs; `None` where this cannot be told (no `/proc`).
fn process_alive(pid: u32) -> Option<bool> {
    if !Path::new("/proc/self").is_dir() {
        return None;
    }
    Some(Path::new(&format!("/proc/{pid}")).exists())
}

/// Removes from `dir` the staging files of processes that are gone (a run killed while it
/// wrote), and returns their paths, sorted. Files of running processes are kept, and
/// nothing is removed where process ids cannot be checked (no `/proc`).
pub fn remove_stale_staging(dir: &Path) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let me = std::process::id();
    let mut removed: Vec<PathBuf> = entries
        .flatten()
        .filter_map(|entry| {
            let pid = staging_pid(&entry.file_name().to_string_lossy())?;
            let gone = pid != me && process_alive(pid) == Some(false);
            (gone && entry.file_type().is_ok_and(|t| t.is_file())).then(|| entry.path())
        })
        .filter(|p| std::fs::remove_file(p).is_ok())
        .collect();
    removed.sort();
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staging_names_carry_the_pid_and_stay_short() {
        let target = Path::new("dir").join(format!("{}.obj", "n".repeat(210)));
        let p = stage_path(&target);
        let name = p
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .to_string();
        assert!(name.len() < 40, "{name}");
        assert!(name.ends_with(".obj"), "{name}");
        assert_eq!(staging_pid(&name), Some(std::process::id()));
        discard(&[p.as_path()]);
        assert!(!registry().paths.contains(&p));
    }

    #[test]
    fn staging_pids_are_read_from_every_kind_of_name() {
        assert_eq!(staging_pid(".cmstage-42-7.obj"), Some(42));
        assert_eq!(
            staging_pid("..cmstage-42-7.obj.conformap-42-0.tmp"),
            Some(42)
        );
        assert_eq!(staging_pid(".conformap-stage-9-0-out.obj"), Some(9));
        assert_eq!(staging_pid("..conformap-stage-9-0-out.obj.tmp"), Some(9));
        assert_eq!(staging_pid(".cmstage-x-7.obj"), None);
        assert_eq!(staging_pid(".cmstage-42"), None);
        assert_eq!(staging_pid("out.obj"), None);
    }

    #[test]
    fn stale_files_of_dead_processes_are_removed_and_live_ones_kept() {
        if process_alive(1).is_none() {
            return; // no /proc: nothing is removed, as documented
        }
        let dir = std::env::temp_dir().join(format!("conformap-staging-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap_or_default();
        // pid_max is at most 2^22 on Linux: 999999999 never runs
        let dead = dir.join(".cmstage-999999999-3.obj");
        let dead_tmp = dir.join("..cmstage-999999999-3.obj.conformap-999999999-0.tmp");
        let live = dir.join(format!(".cmstage-{}-0.obj", std::process::id()));
        let other = dir.join("frame_0000.obj");
        for p in [&dead, &dead_tmp, &live, &other] {
            std::fs::write(p, "x").unwrap_or_default();
        }
        let removed = remove_stale_staging(&dir);
        assert_eq!(removed, vec![dead_tmp.clone(), dead.clone()]);
        assert!(!dead.exists() && !dead_tmp.exists());
        assert!(live.exists() && other.exists());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
