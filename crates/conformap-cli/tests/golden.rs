//! Golden reports: end-to-end CLI runs on the committed fixtures, their JSON reports
//! compared against `tests/golden/*.json` within stated tolerances.
//!
//! What is compared: every field of the report except what depends on the machine or the
//! run (`timings_ms`, `memory`, any `*_ms` or `time_ms` field, `path`, the free-text
//! `notes`, `conformap_version`). Numbers agree to [`REL_TOL`] relative (or [`ABS_TOL`]
//! absolute near zero); strings, booleans, array lengths and object keys exactly — so a
//! changed energy, flip count or circle residual, or a renamed field, fails the test.
//! Iteration counts and histories of the solver are the exception ([`COUNT_TOL`]): a stop
//! at the rounding level of `E_C` may come an iteration earlier or later where the dense
//! kernels round differently (another SIMD width), so the solver's integer counts may move
//! by 10 % (at least 2) and of each `*_history` only the last entry is compared.
//!
//! A change that moves these numbers on purpose is blessed with
//! `CONFORMAP_BLESS=1 cargo test -p conformap-cli --test golden` (`just bless`), and the
//! diff of `tests/golden/` shows what moved.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::path::{Path, PathBuf};

use serde_json::Value;
use support::{conformap, fixture, s, stderr, tmpdir};

/// Relative tolerance on numbers: far above the run-to-run differences (the outputs are
/// byte-identical for the same input and options, on any thread count), far below any
/// change of method (the smallest deliberate change measured, a restart rule of CCEM-QN,
/// moved `E_C` by 2e-10 relative on spothead and 7.6e-5 on igea_open).
const REL_TOL: f64 = 1e-6;

/// Absolute tolerance for numbers near zero (residuals at round-off, 1e-16).
const ABS_TOL: f64 = 1e-12;

/// Integer counts in the solver's part of a report (iterations, evaluations, products) may
/// differ from the golden ones by this share (at least 2).
const COUNT_TOL: f64 = 0.1;

/// Keys dropped before comparing (machine- or run-dependent).
fn dropped(key: &str) -> bool {
    matches!(
        key,
        "timings_ms" | "memory" | "path" | "notes" | "conformap_version" | "time_ms"
    ) || key.ends_with("_ms")
}

/// The report without the dropped keys.
fn view(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| !dropped(k))
                .map(|(k, v)| (k.clone(), view(v)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(view).collect()),
        other => other.clone(),
    }
}

/// Differences between `got` and `want` (paths into the report), empty when they agree.
fn compare(got: &Value, want: &Value, at: &str, out: &mut Vec<String>) {
    match (got, want) {
        (Value::Number(gn), Value::Number(wn)) => {
            let (g, w) = (
                gn.as_f64().unwrap_or(f64::NAN),
                wn.as_f64().unwrap_or(f64::NAN),
            );
            let count = wn.is_u64() && at.contains(".solver");
            let tol = if count {
                (COUNT_TOL * w.abs()).max(2.0)
            } else {
                ABS_TOL.max(REL_TOL * w.abs())
            };
            if !((g - w).abs() <= tol) {
                out.push(format!("{at}: {g:e}, golden {w:e}"));
            }
        }
        (Value::Array(g), Value::Array(w)) if at.ends_with("_history") => {
            match (g.last(), w.last()) {
                (Some(gv), Some(wv)) => compare(gv, wv, &format!("{at}[last]"), out),
                (None, None) => {}
                _ => out.push(format!("{at}: {} entries, golden {}", g.len(), w.len())),
            }
        }
        (Value::Object(g), Value::Object(w)) => {
            for k in w.keys().filter(|k| !g.contains_key(*k)) {
                out.push(format!("{at}.{k}: missing"));
            }
            for (k, gv) in g {
                match w.get(k) {
                    Some(wv) => compare(gv, wv, &format!("{at}.{k}"), out),
                    None => out.push(format!("{at}.{k}: not in the golden report")),
                }
            }
        }
        (Value::Array(g), Value::Array(w)) => {
            if g.len() != w.len() {
                out.push(format!("{at}: {} entries, golden {}", g.len(), w.len()));
            } else {
                for (i, (gv, wv)) in g.iter().zip(w).enumerate() {
                    compare(gv, wv, &format!("{at}[{i}]"), out);
                }
            }
        }
        (g, w) if g == w => {}
        (g, w) => out.push(format!("{at}: {g}, golden {w}")),
    }
}

fn golden_path(case: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{case}.json"))
}

/// Compares (or, with `CONFORMAP_BLESS=1`, rewrites) the golden report of `case`.
fn check(case: &str, report: &Path) {
    let text = std::fs::read_to_string(report).expect("report written");
    let got = view(&serde_json::from_str::<Value>(&text).expect("report is JSON"));
    let path = golden_path(case);
    if std::env::var_os("CONFORMAP_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().expect("golden dir")).expect("golden dir");
        let mut pretty = serde_json::to_string_pretty(&got).expect("JSON");
        pretty.push('\n');
        std::fs::write(&path, pretty).expect("write golden report");
        return;
    }
    let want: Value = serde_json::from_str(
        &std::fs::read_to_string(&path)
            .unwrap_or_else(|_| panic!("{}: missing; run `just bless`", path.display())),
    )
    .expect("golden report is JSON");
    let mut diffs = Vec::new();
    compare(&got, &want, case, &mut diffs);
    assert!(
        diffs.is_empty(),
        "{case}: the report differs from {} ({} differences; bless on purpose with \
         `just bless`):\n{}",
        path.display(),
        diffs.len(),
        diffs
            .iter()
            .take(20)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// Runs `conformap ARGS... -o OUT --report R` and checks the report against `case`.
fn run_case(case: &str, args: &[&str]) -> PathBuf {
    let d = tmpdir(&format!("golden-{case}"));
    let (out, rep) = (d.join("out.obj"), d.join("report.json"));
    let mut all: Vec<&str> = args.to_vec();
    all.extend(["-o", s(&out), "--report", s(&rep)]);
    let o = conformap(&all);
    assert!(o.status.success(), "{case}: {}", stderr(&o));
    check(case, &rep);
    out
}

#[test]
fn disk_default_method_on_the_disk_fixtures() {
    for name in ["woody", "alligator", "spothead"] {
        let mesh = fixture(&format!("{name}.obj"));
        run_case(&format!("disk_{name}"), &["disk", s(&mesh)]);
    }
}

#[test]
fn disk_cem_and_harmonic_on_spothead() {
    let mesh = fixture("spothead.obj");
    for method in ["cem", "harmonic"] {
        run_case(
            &format!("disk_spothead_{method}"),
            &["disk", s(&mesh), "--method", method],
        );
    }
}

#[test]
fn disk_with_circular_holes_on_halftunnel() {
    let mesh = fixture("halftunnel.obj");
    run_case("disk_halftunnel", &["disk", s(&mesh)]);
}

#[test]
fn sphere_with_uniform_mobius_on_spot() {
    let mesh = fixture("spot.obj");
    run_case("sphere_spot", &["sphere", s(&mesh), "--mobius", "uniform"]);
}

#[test]
fn mobius_of_the_disk_map_of_spothead() {
    let mesh = fixture("spothead.obj");
    let d = tmpdir("golden-mobius-src");
    let param = d.join("spothead_uv.obj");
    let o = conformap(&["disk", s(&mesh), "-o", s(&param)]);
    assert!(o.status.success(), "{}", stderr(&o));
    run_case(
        "mobius_spothead",
        &[
            "mobius",
            s(&mesh),
            s(&param),
            "--domain",
            "disk",
            "--objective",
            "uniform",
        ],
    );
}

#[test]
fn comparison_detects_changes() {
    // the comparison itself: a number past the tolerance, a changed length, a missing key
    let want: Value = serde_json::json!({"a": 1.0, "b": [1, 2], "c": "x", "d": 0.0});
    let same: Value = serde_json::json!({"a": 1.0 + 1e-9, "b": [1, 2], "c": "x", "d": 1e-14});
    let mut diffs = Vec::new();
    compare(&same, &want, "r", &mut diffs);
    assert!(diffs.is_empty(), "{diffs:?}");
    let moved: Value = serde_json::json!({"a": 1.0 + 1e-5, "b": [1], "c": "y"});
    compare(&moved, &want, "r", &mut diffs);
    assert_eq!(diffs.len(), 4, "{diffs:?}");
    // solver counts and histories: loose, but not blind
    let want: Value =
        serde_json::json!({"solver": {"iterations": 40, "energy_history": [3.0, 2.0]}});
    let close: Value =
        serde_json::json!({"solver": {"iterations": 43, "energy_history": [3.0, 2.5, 2.0]}});
    let far: Value =
        serde_json::json!({"solver": {"iterations": 50, "energy_history": [3.0, 2.1]}});
    let mut diffs = Vec::new();
    compare(&close, &want, "r", &mut diffs);
    assert!(diffs.is_empty(), "{diffs:?}");
    compare(&far, &want, "r", &mut diffs);
    assert_eq!(diffs.len(), 2, "{diffs:?}");
    // timings and notes are not compared
    let report: Value = serde_json::json!({"timings_ms": {"total": 3.0}, "solver": {"notes": ["x"], "form_ms": 1.0, "iterations": 3}});
    assert_eq!(
        view(&report),
        serde_json::json!({"solver": {"iterations": 3}})
    );
}
