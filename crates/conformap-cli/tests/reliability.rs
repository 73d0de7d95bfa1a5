//! Staging files under signals and at start, and morph's frame directory, through the
//! binary.

#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use support::{conformap, conformap_ok, fixture, s, stderr, tmpdir};

/// Files in `dir` whose names mark them as staging files (ours or a writer's temporary).
fn staging_files(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("cmstage-") || n.contains("conformap-stage-"))
        .collect()
}

fn landmarks(dir: &Path) -> PathBuf {
    let lm = dir.join("lm.txt");
    std::fs::write(&lm, "400 a\n401 b\n").unwrap();
    lm
}

#[test]
fn sigterm_while_writing_leaves_no_staging_file_and_exits_143() {
    let d = tmpdir("sigterm");
    let (woody, lm) = (fixture("woody.obj"), landmarks(&d));
    let frames = d.join("frames");
    std::fs::create_dir_all(&frames).unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_conformap"))
        .args(["morph", s(&woody), s(&woody), "--landmarks", s(&lm), s(&lm)])
        .args(["--frames", "800", "-o", &format!("{}/", s(&frames))])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t = Instant::now();
    while staging_files(&frames).is_empty() {
        assert!(
            t.elapsed() < Duration::from_secs(300),
            "no staging file appeared"
        );
        assert!(child.try_wait().unwrap().is_none(), "ended before writing");
        std::thread::sleep(Duration::from_millis(2));
    }
    let kill = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(143), "{err}");
    assert!(err.contains("interrupted by SIGTERM"), "{err}");
    assert_eq!(staging_files(&frames), Vec::<String>::new());
    // all or nothing: no frame was renamed into place
    assert_eq!(std::fs::read_dir(&frames).unwrap().count(), 0);
}

#[test]
fn stale_staging_files_of_dead_runs_are_removed_at_start_and_long_names_work() {
    let d = tmpdir("stale");
    // pid_max is at most 2^22 on Linux: process 999999999 never runs
    let stale = [
        ".cmstage-999999999-0.obj",
        "..cmstage-999999999-0.obj.conformap-999999999-1.tmp",
        ".conformap-stage-999999999-2-out.obj",
    ];
    for n in stale {
        std::fs::write(d.join(n), "partial").unwrap();
    }
    let live = format!(".cmstage-{}-0.obj", std::process::id());
    std::fs::write(d.join(&live), "a running process's").unwrap();
    // a legal 210-byte name (before: "File name too long" from the staging name)
    let out = d.join(format!("{}.obj", "n".repeat(206)));
    let o = conformap_ok(&["disk", s(&fixture("woody.obj")), "-o", s(&out)]);
    let err = stderr(&o);
    assert!(
        err.contains("removed 3 staging file(s) left by an interrupted earlier run"),
        "{err}"
    );
    assert!(out.is_file());
    assert_eq!(staging_files(&d), vec![live]);
}

#[test]
fn morph_frame_directory_is_created_and_cleared_of_stale_frames() {
    let d = tmpdir("morph-dir");
    let (woody, lm) = (fixture("woody.obj"), landmarks(&d));
    let dir = d.join("new").join("frames");
    let run = |frames: &str| {
        conformap(&[
            "morph",
            s(&woody),
            s(&woody),
            "--landmarks",
            s(&lm),
            s(&lm),
            "--frames",
            frames,
            "-o",
            &format!("{}/", s(&dir)),
        ])
    };
    // before: "the directory … does not exist"
    let o = run("5");
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    let o = run("3");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("removed 2 frame file(s) of an earlier run that this run did not write (frame_0003.obj … frame_0004.obj)"),
        "{}",
        stderr(&o)
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "frame_0000.obj",
            "frame_0001.obj",
            "frame_0002.obj",
            "notes.txt"
        ]
    );
}
