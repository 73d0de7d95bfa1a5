//! Benchmarks of `conformap disk` stages on real and generated meshes.
//!
//! ```text
//! cargo run --release -p conformap-bench -- [--runs N] [--method ccem-qn|ccem|cem|harmonic|global] [--ordering auto|amd|nd] MESH... [gen:250k gen:1m cap:1m ...]
//! ```
//!
//! The default method is `conformap disk`'s, `ccem-qn`. Stages: see [`stages`].
//! `--method global` measures `conformap global` on meshes of genus ≥ 1 instead (see
//! [`global_row`]).
//! Each (mesh, run) executes in a child process of this binary, so that the peak resident
//! set size (VmHWM) is that run's alone; the parent prints a Markdown table of medians.
//! `gen:N` (N like `250k`, `1m`, `2m`) is a bumpy height field over a square with about N
//! faces, generated in code, written once to a temporary OBJ and then read like any file;
//! `disk:N` the same bumps over the unit disk (no corners); `cap:N` is a bumpy closed
//! surface with one small hole (a short boundary, like a scan cut
//! open). See [`generate`].

mod generate;
mod global_row;
mod row;
mod stages;

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::row::Row;
use crate::stages::StageRow;

fn usage() -> ! {
    eprintln!(
        "usage: conformap-bench [--runs N] [--method ccem-qn|ccem|cem|harmonic|global] [--ordering auto|amd|nd] MESH.obj... [gen:250k|disk:1m|cap:1m ...]\n       \
         conformap-bench --child MESH METHOD ORDERING   (internal)"
    );
    std::process::exit(2)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--child") {
        let (Some(mesh), Some(method), Some(ordering)) = (args.get(1), args.get(2), args.get(3))
        else {
            usage()
        };
        let line = if method == "global" {
            global_row::run_once(Path::new(mesh)).map(|r| r.to_line())
        } else {
            stages::run_once(Path::new(mesh), method, ordering).map(|r| r.to_line())
        };
        match line {
            Ok(line) => println!("{line}"),
            Err(e) => {
                eprintln!("{mesh}: {e}");
                std::process::exit(1);
            }
        }
        return;
    }
    let mut runs = 3usize;
    let mut method = "ccem-qn".to_string();
    let mut ordering = "auto".to_string();
    let mut inputs = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--runs" => {
                runs = it
                    .next()
                    .and_then(|s| s.parse().ok())
                    .unwrap_or_else(|| usage())
            }
            "--method" => method = it.next().unwrap_or_else(|| usage()),
            "--ordering" => ordering = it.next().unwrap_or_else(|| usage()),
            "-h" | "--help" => usage(),
            _ => inputs.push(a),
        }
    }
    if inputs.is_empty() {
        usage();
    }
    let exe = std::env::current_exe().unwrap_or_else(|_| PathBuf::from("conformap-bench"));
    println!(
        "method `{method}`, ordering `{ordering}`, the run of median ratio of {runs}, each in its own process; times in ms\n"
    );
    let global = method == "global";
    println!(
        "{}",
        if global {
            global_row::GlobalRow::header()
        } else {
            StageRow::header()
        }
    );
    for input in inputs {
        let generated = if let Some(size) = input.strip_prefix("gen:") {
            Some(generate::generated_obj(size))
        } else if let Some(size) = input.strip_prefix("disk:") {
            Some(generate::generated_disk_obj(size))
        } else {
            input.strip_prefix("cap:").map(generate::generated_cap_obj)
        };
        let path = match generated {
            Some(Ok(p)) => p,
            Some(Err(e)) => {
                eprintln!("{input}: {e}");
                continue;
            }
            None => PathBuf::from(&input),
        };
        let mut rows = Vec::new();
        let mut global_rows = Vec::new();
        for _ in 0..runs {
            let out = Command::new(&exe)
                .arg("--child")
                .arg(&path)
                .arg(&method)
                .arg(&ordering)
                .output();
            match out {
                Ok(o) if o.status.success() => {
                    let line = String::from_utf8_lossy(&o.stdout);
                    if global {
                        global_rows.extend(global_row::GlobalRow::from_line(&line));
                    } else if let Some(row) = StageRow::from_line(&line) {
                        rows.push(row);
                    }
                }
                Ok(o) => {
                    eprintln!(
                        "{}: {}",
                        path.display(),
                        String::from_utf8_lossy(&o.stderr).trim()
                    );
                    break;
                }
                Err(e) => {
                    eprintln!("{}: cannot run child: {e}", path.display());
                    break;
                }
            }
        }
        if let Some((median, lo, hi)) = StageRow::median(&rows) {
            println!("{}", median.to_markdown(&input, lo, hi));
        }
        if let Some((median, lo, hi)) = global_row::GlobalRow::median(&global_rows) {
            println!("{}", median.to_markdown(&input, lo, hi));
        }
    }
}
