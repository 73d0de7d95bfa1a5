//! End-to-end runs of `conformap render`, `--png`, `batch` and the progress display.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
}

fn conformap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_conformap"))
        .args(args)
        .env_remove("NO_COLOR")
        .output()
        .expect("run conformap")
}

fn tmpdir(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("conformap-rb-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A decoded RGB8 PNG: width, height, pixels.
fn decode(path: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let file = std::fs::File::open(path).expect("open png");
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("png header");
    let mut buf = vec![0; reader.output_buffer_size().expect("png size")];
    let info = reader.next_frame(&mut buf).expect("png frame");
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", path.display());
    let px = buf[..info.buffer_size()]
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, px)
}

/// Share of pixels that are not the white background.
fn coverage(px: &[[u8; 3]]) -> f64 {
    px.iter().filter(|p| **p != [255, 255, 255]).count() as f64 / px.len() as f64
}

fn luminance(p: [u8; 3]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Disk map of `mesh` into `dir/uv.obj`.
fn disk_map(mesh: &str, dir: &Path) -> PathBuf {
    let uv = dir.join(format!("{mesh}_uv.obj"));
    let o = conformap(&["disk", s(&fixture(&format!("{mesh}.obj"))), "-o", s(&uv)]);
    assert!(o.status.success(), "{}", stderr(&o));
    uv
}

#[test]
fn render_draws_woody_checkerboard_in_two_tones() {
    let d = tmpdir("woody");
    let uv = disk_map("woody", &d);
    let png = d.join("surface.png");
    let o = conformap(&[
        "render",
        s(&fixture("woody.obj")),
        s(&uv),
        "-o",
        s(&png),
        "--size",
        "200",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, px) = decode(&png);
    assert_eq!((w, h), (200, 200));
    // woody is planar and fills about half its bounding box
    let cov = coverage(&px);
    assert!(cov > 0.25 && cov < 0.95, "coverage {cov}");
    // seen head-on, the flat surface is lit uniformly: the checker's two tones, a dark
    // blue and a near white, each cover a good share of the figure
    let covered: Vec<[u8; 3]> = px.into_iter().filter(|p| *p != [255; 3]).collect();
    let dark = covered
        .iter()
        .filter(|p| luminance(**p) < 110.0 && p[2] > p[0] + 60)
        .count();
    let light = covered.iter().filter(|p| luminance(**p) > 200.0).count();
    let (fd, fl) = (
        dark as f64 / covered.len() as f64,
        light as f64 / covered.len() as f64,
    );
    assert!(fd > 0.25 && fl > 0.25, "dark {fd:.3}, light {fl:.3}");
    assert!(
        fd + fl > 0.8,
        "anti-aliased mixes only at cell edges: {fd:.3} + {fl:.3}"
    );
}

#[test]
fn render_map_and_histogram_views_of_spothead() {
    let d = tmpdir("spothead");
    let uv = disk_map("spothead", &d);
    let mesh = fixture("spothead.obj");
    let map = d.join("map.png");
    let o = conformap(&[
        "render",
        s(&mesh),
        s(&uv),
        "-o",
        s(&map),
        "--view",
        "map",
        "--size",
        "256",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (w, h, px) = decode(&map);
    assert_eq!((w, h), (256, 256));
    // the unit disk fills π/4 of its frame less the margin and the colour bar
    let cov = coverage(&px);
    assert!(cov > 0.4 && cov < 0.9, "coverage {cov}");
    let colours: HashSet<[u8; 3]> = px.iter().copied().collect();
    assert!(
        colours.len() > 100,
        "a distortion colour map: {} colours",
        colours.len()
    );
    let hist = d.join("hist.svg");
    let o = conformap(&[
        "render",
        s(&mesh),
        s(&uv),
        "-o",
        s(&hist),
        "--view",
        "histogram",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = std::fs::read_to_string(&hist).expect("svg");
    assert!(
        svg.starts_with("<svg") || svg.starts_with("<?xml"),
        "{}",
        &svg[..40]
    );
    assert!(svg.matches("<rect").count() > 10);
}

#[test]
fn render_reads_spot_sphere_map_from_equirectangular_and_points() {
    let d = tmpdir("spot");
    let (uv, flat) = (d.join("uv.obj"), d.join("flat.obj"));
    let mesh = fixture("spot.obj");
    let o = conformap(&["sphere", s(&mesh), "-o", s(&uv), "--flat", s(&flat)]);
    assert!(o.status.success(), "{}", stderr(&o));
    // `sphere -o` writes the texture per corner (split along the seam), read back to one
    // sphere point per vertex and named as what it is; --flat holds the points themselves
    for (param, what) in [
        (&uv, "equirectangular texture coordinates per corner"),
        (&flat, "unit-sphere points"),
    ] {
        let out = d.join("spot.png");
        let o = conformap(&["render", s(&mesh), s(param), "-o", s(&out), "--size", "128"]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stderr(&o).contains(what), "{}", stderr(&o));
        let (_, _, px) = decode(&out);
        assert!(coverage(&px) > 0.2, "{what}");
    }
}

#[test]
fn render_refuses_bad_outputs_and_mismatched_maps_writing_nothing() {
    let d = tmpdir("refuse");
    let uv = disk_map("woody", &d);
    let mesh = fixture("woody.obj");
    // not a picture format: usage error
    let o = conformap(&["render", s(&mesh), s(&uv), "-o", s(&d.join("x.jpg"))]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("name the output .png"),
        "{}",
        stderr(&o)
    );
    // SVG only for the histogram
    let o = conformap(&["render", s(&mesh), s(&uv), "-o", s(&d.join("x.svg"))]);
    assert_eq!(o.status.code(), Some(2));
    // another mesh's map: bad input with a hint
    let out = d.join("x.png");
    let o = conformap(&["render", s(&fixture("spothead.obj")), s(&uv), "-o", s(&out)]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("hint:"), "{}", stderr(&o));
    // overwriting the map: usage error
    let o = conformap(&["render", s(&mesh), s(&uv), "-o", s(&uv)]);
    assert_eq!(o.status.code(), Some(2));
    // size out of range: clap's usage error
    let o = conformap(&["render", s(&mesh), s(&uv), "-o", s(&out), "--size", "4"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
    let leftovers: Vec<_> = std::fs::read_dir(&d)
        .expect("dir")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().starts_with(".conformap"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

#[test]
fn png_prefix_writes_surface_and_map_with_the_other_outputs() {
    let d = tmpdir("png");
    let prefix = d.join("spot");
    let out = d.join("spot_uv.obj");
    let o = conformap(&[
        "sphere",
        s(&fixture("spot.obj")),
        "-o",
        s(&out),
        "--png",
        s(&prefix),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // --quiet: no summary line
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
    for name in ["spot_surface.png", "spot_map.png"] {
        let (w, h, px) = decode(&d.join(name));
        assert_eq!((w, h), (1024, 1024), "{name}");
        assert!(coverage(&px) > 0.2, "{name}");
    }
    // --png naming an existing input: refused before anything is computed
    let o = conformap(&[
        "disk",
        s(&fixture("woody.obj")),
        "-o",
        s(&d.join("w.obj")),
        "--png",
        s(&d.join("w")),
        "--report",
        s(&d.join("w_map.png")),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(!d.join("w.obj").exists());
}

#[test]
fn no_progress_escape_codes_on_a_non_terminal_stderr() {
    let d = tmpdir("progress");
    // spothead's disk map runs long enough in a test build to pass the 1 s threshold only
    // on a slow machine; a sphere map of spot with the uniform Möbius map takes longer
    let o = conformap(&[
        "sphere",
        s(&fixture("spot.obj")),
        "-o",
        s(&d.join("o.obj")),
        "--mobius",
        "uniform",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(!err.contains('\u{1b}'), "escape codes on a pipe: {err:?}");
    assert!(!err.contains('\r'), "carriage returns on a pipe: {err:?}");
    assert_eq!(err.lines().count(), 1, "only the summary line: {err:?}");
}

/// Removes what a run measures rather than computes: `memory` and every time (`*_ms`).
fn drop_measurements(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(m) => {
            m.retain(|k, _| k != "memory" && !k.ends_with("_ms"));
            m.values_mut().for_each(drop_measurements);
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(drop_measurements),
        _ => {}
    }
}

/// Batch over the fixtures plus one broken file.
#[test]
fn batch_runs_fixtures_reports_lines_and_matches_single_runs() {
    let d = tmpdir("batch");
    let out = d.join("out");
    let bad = d.join("broken.obj");
    std::fs::copy(fixture("bad/index_out_of_range.obj"), &bad).expect("copy");
    let manifest = d.join("list.txt");
    let names = ["woody", "alligator", "spothead", "halftunnel"];
    let mut text = String::from("# fixtures and a broken file\n");
    for n in names {
        text.push_str(s(&fixture(&format!("{n}.obj"))));
        text.push('\n');
    }
    text.push_str("broken.obj\n");
    std::fs::write(&manifest, text).expect("manifest");
    let jsonl = d.join("r.jsonl");
    let run = |extra: &[&str]| {
        let mut args = vec![
            "batch",
            "--command",
            "disk",
            "--out-dir",
            s(&out),
            "--report",
            s(&jsonl),
        ];
        args.extend_from_slice(extra);
        args.push(s(&manifest));
        conformap(&args)
    };
    let o = run(&["--jobs", "2"]);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    assert_eq!(lines.len(), names.len() + 2, "{stdout}");
    assert_eq!(std::fs::read_to_string(&jsonl).expect("jsonl"), stdout);
    for (line, n) in lines.iter().zip(names) {
        assert_eq!(line["status"], "ok", "{line}");
        assert!(line["input"]
            .as_str()
            .expect("input")
            .ends_with(&format!("{n}.obj")));
        assert_eq!(line["metrics"]["flipped_faces"], 0, "{line}");
        assert!(line["timings_ms"]["total"].as_f64().expect("total") > 0.0);
        assert!(
            line["memory"]["estimated_peak_bytes"]
                .as_u64()
                .expect("mem")
                > 0
        );
        // two jobs share the process: their peak is the process's
        assert_eq!(line["memory"]["peak_rss_scope"], "process", "{line}");
    }
    let broken = &lines[names.len()];
    assert_eq!(broken["status"], "failed");
    assert_eq!(broken["exit_code"], 1);
    assert_eq!(broken["exit_class"], "bad input");
    assert!(broken["error"]
        .as_str()
        .expect("error")
        .contains("broken.obj"));
    let summary = &lines[names.len() + 1]["summary"];
    assert_eq!(summary["inputs"], 5);
    assert_eq!(summary["ok"], 4);
    assert_eq!(summary["failed"], 1);
    assert_eq!(summary["exit_code"], 4);

    // every output equals a single run's byte for byte; reports equal but for the run's
    // measurements (timings, memory)
    let single = d.join("single");
    std::fs::create_dir_all(&single).expect("dir");
    for n in names {
        let (mesh, rep) = (
            single.join(format!("{n}.obj")),
            single.join(format!("{n}.json")),
        );
        let o = conformap(&[
            "disk",
            s(&fixture(&format!("{n}.obj"))),
            "-o",
            s(&mesh),
            "--report",
            s(&rep),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let a = std::fs::read(out.join(format!("{n}.obj"))).expect("batch output");
        assert!(
            a == std::fs::read(&mesh).expect("single output"),
            "{n}: meshes differ"
        );
        let strip = |p: &Path| {
            let mut v: serde_json::Value =
                serde_json::from_str(&std::fs::read_to_string(p).expect("report")).expect("json");
            drop_measurements(&mut v);
            v
        };
        assert_eq!(
            strip(&out.join(format!("{n}.json"))),
            strip(&rep),
            "{n}: reports"
        );
    }

    // --skip-existing skips what is done and retries the broken file
    let o = run(&["--skip-existing"]);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    let statuses: Vec<&str> = lines[..5]
        .iter()
        .map(|l| l["status"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(
        statuses,
        ["skipped", "skipped", "skipped", "skipped", "failed"]
    );
    assert_eq!(lines[5]["summary"]["skipped"], 4);

    // all good: exit 0; usage errors: exit 2
    let o = conformap(&[
        "batch",
        "--command",
        "sphere",
        "--out-dir",
        s(&out),
        s(&fixture("spot.obj")),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // one job at a time: each input's peak is its own where the high-water mark can be
    // reset (Linux), and never above the batch's
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<serde_json::Value> = stdout
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    let resettable = std::fs::write("/proc/self/clear_refs", "5").is_ok();
    let scope = if resettable { "job" } else { "process" };
    assert_eq!(lines[0]["memory"]["peak_rss_scope"], scope, "{}", lines[0]);
    if let (Some(job), Some(all)) = (
        lines[0]["memory"]["peak_rss_bytes"].as_u64(),
        lines[1]["summary"]["peak_rss_bytes"].as_u64(),
    ) {
        assert!(job > 0 && job <= all, "{job} vs {all}");
    }
    let o = conformap(&[
        "batch",
        "--command",
        "disk",
        "--out-dir",
        s(&out),
        s(&fixture("woody.obj")),
        "--",
        "--method",
        "nonsense",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let o = conformap(&[
        "batch",
        "--command",
        "disk",
        "--out-dir",
        s(&out),
        s(&fixture("woody.obj")),
        s(&fixture("gltf/woody.glb")),
    ]);
    assert_eq!(o.status.code(), Some(2), "same stem: {}", stderr(&o));
}
