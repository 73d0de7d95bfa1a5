//! The shell examples of the READMEs and of `batch --help` run as written: every line that
//! runs `conformap` (or `cargo run -p conformap-cli --`) in a ```sh block of the top
//! README and of each crate's README, in a fresh directory where `fixtures/` is the
//! repository's and a manifest `meshes.txt` lists two fixtures; each must exit 0.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;

use support::{conformap_ok, tmpdir};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `conformap` arguments of a shell line, or `None` for a line that does not run it.
fn conformap_args(line: &str) -> Option<Vec<String>> {
    let code = line.split(" #").next().unwrap_or_default().trim();
    let rest = code
        .strip_prefix("conformap ")
        .or_else(|| code.split_once("-p conformap-cli -- ").map(|(_, r)| r))?;
    Some(rest.split_whitespace().map(str::to_string).collect())
}

/// The lines of the ```sh blocks of `text`.
fn sh_lines(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.starts_with("```") {
            inside = line.starts_with("```sh");
            continue;
        }
        if inside {
            out.push(line.to_string());
        }
    }
    out
}

/// A directory to run examples in: `fixtures/` linked, `meshes.txt` a manifest.
fn workdir() -> PathBuf {
    let d = tmpdir("examples");
    std::os::unix::fs::symlink(root().join("fixtures"), d.join("fixtures")).unwrap();
    std::fs::write(
        d.join("meshes.txt"),
        "fixtures/woody.obj\nfixtures/spothead.obj\n",
    )
    .unwrap();
    d
}

fn run_in(dir: &Path, args: &[String], from: &str) {
    let o = Command::new(env!("CARGO_BIN_EXE_conformap"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{from}: conformap {}\n{}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn readme_shell_examples_run() {
    let mut readmes = vec![root().join("README.md")];
    for entry in std::fs::read_dir(root().join("crates")).unwrap() {
        let readme = entry.unwrap().path().join("README.md");
        if readme.is_file() {
            readmes.push(readme);
        }
    }
    readmes.sort();
    let mut ran = 0;
    for readme in &readmes {
        // one directory per README: its lines may use each other's outputs
        let dir = workdir();
        let text = std::fs::read_to_string(readme).unwrap();
        for line in sh_lines(&text) {
            if let Some(args) = conformap_args(&line) {
                run_in(&dir, &args, &readme.display().to_string());
                ran += 1;
            }
        }
    }
    // the top README's five, the CLI README's six
    assert!(ran >= 11, "ran {ran} examples");
}

#[test]
fn batch_help_example_runs() {
    let help = String::from_utf8_lossy(&conformap_ok(&["batch", "--help"]).stdout).to_string();
    let line = help
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("conformap batch "))
        .unwrap_or_else(|| panic!("no example in:\n{help}"));
    let dir = workdir();
    let args = conformap_args(line).unwrap();
    run_in(&dir, &args, "batch --help");
    // every input converged: the summary names none stopped at the cap
    assert!(dir.join("out").join("woody.obj").is_file());
}
