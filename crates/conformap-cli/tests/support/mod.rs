//! Helpers shared by the end-to-end test files (each uses a subset).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
}

/// A mesh of `../shared/meshes` next to the workspace, if present (ignored tests only).
pub fn shared(name: &str) -> Option<PathBuf> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/meshes")
        .join(name);
    if p.is_file() {
        Some(p)
    } else {
        eprintln!("SKIPPED: {name} not found in ../shared/meshes");
        None
    }
}

pub fn conformap(args: &[&str]) -> Output {
    conformap_env(args, &[])
}

pub fn conformap_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_conformap"));
    c.args(args);
    for (k, v) in env {
        c.env(k, v);
    }
    c.output().expect("run conformap")
}

/// A fresh directory for one test: unique per call (tests of one binary run in parallel
/// threads and may share a tag).
pub fn tmpdir(tag: &str) -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("conformap-test-{tag}-{}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

pub fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("read json")).expect("parse json")
}

/// Runs `conformap ARGS…` and asserts that it succeeds (its stderr in the failure message).
pub fn conformap_ok(args: &[&str]) -> Output {
    let o = conformap(args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

/// Runs `conformap ARGS… -o OUT [--flat FLAT] --report REPORT`, asserts that it succeeds and
/// returns the report.
pub fn map_report(
    args: &[&str],
    out: &Path,
    flat: Option<&Path>,
    report: &Path,
) -> serde_json::Value {
    let mut all = args.to_vec();
    all.extend(["-o", s(out)]);
    if let Some(flat) = flat {
        all.extend(["--flat", s(flat)]);
    }
    all.extend(["--report", s(report)]);
    conformap_ok(&all);
    json(report)
}

/// `conformap mobius MESH PARAM --domain DOMAIN --objective OBJECTIVE EXTRA… -o OUT`, not
/// checked (the caller asserts its exit code).
pub fn mobius(
    mesh: &Path,
    param: &Path,
    domain: &str,
    objective: &str,
    extra: &[&str],
    out: &Path,
) -> Output {
    let mut args = vec![
        "mobius",
        s(mesh),
        s(param),
        "--domain",
        domain,
        "--objective",
        objective,
    ];
    args.extend(extra);
    args.extend(["-o", s(out)]);
    conformap(&args)
}

/// `conformap metrics MESH MAP --json`, asserted to succeed, parsed.
pub fn metrics_json(mesh: &Path, map: &Path) -> serde_json::Value {
    let o = conformap_ok(&["metrics", s(mesh), s(map), "--json"]);
    serde_json::from_slice(&o.stdout).expect("metrics --json")
}
