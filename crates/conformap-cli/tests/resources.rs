//! Resources and reproducibility through the binary: the memory check refuses early with
//! its estimate; the same input gives byte-identical outputs.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod support;

use std::path::Path;

use support::{conformap, conformap_env, fixture, json, s, shared, stderr, tmpdir};

#[test]
fn the_memory_check_refuses_early_with_the_estimate() {
    let d = tmpdir("memory");
    let (out, rep) = (d.join("o.obj"), d.join("r.json"));
    let spothead = fixture("spothead.obj");
    let disk = |limit: &str| {
        let args = ["disk", s(&spothead), "-o", s(&out), "--report", s(&rep)];
        conformap(&[&args[..], &["--max-memory", limit]].concat())
    };
    let o = disk("10M");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains(
            "spothead.obj: a disk map of this mesh (4537 vertices, 9024 faces) needs an \
             estimated"
        ),
        "{err}"
    );
    assert!(
        err.contains("more than the 10.0 MiB allowed (--max-memory); nothing was computed"),
        "{err}"
    );
    assert!(err.contains("hint: ") && err.contains("decimate"), "{err}");
    assert!(!out.exists() && !rep.exists());
    // below what reading the file takes: refused before reading it
    let o = conformap(&["disk", s(&spothead), "-o", s(&out), "--max-memory", "1M"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("spothead.obj: reading this 276 KiB file needs an estimated 2.2 MiB"),
        "{}",
        stderr(&o)
    );
    // a generous limit passes and is reported with the estimate and the measured peak
    let o = disk("4GiB");
    assert!(o.status.success(), "{}", stderr(&o));
    let m = &json(&rep)["memory"];
    assert_eq!(m["limit_bytes"], 4u64 << 30);
    assert_eq!(m["limit_source"], "--max-memory");
    let (est, peak) = (
        m["estimated_peak_bytes"].as_u64().unwrap(),
        m["peak_rss_bytes"].as_u64().unwrap_or(0),
    );
    assert!(peak <= est, "peak {peak} above the estimate {est}");
    // a limit that is not a size is a usage error
    let o = conformap(&["disk", s(&spothead), "-o", s(&out), "--max-memory", "lots"]);
    assert_eq!(o.status.code(), Some(2));
}

/// The report without what measures the run rather than the input: timings (`*_ms`,
/// `timings_ms`) and the machine's memory (`limit_bytes`, `peak_rss_bytes`).
fn without_measurements(v: &serde_json::Value) -> serde_json::Value {
    match v {
        serde_json::Value::Object(m) => m
            .iter()
            .filter(|(k, _)| !(k.ends_with("_ms") || *k == "limit_bytes" || *k == "peak_rss_bytes"))
            .map(|(k, x)| (k.clone(), without_measurements(x)))
            .collect::<serde_json::Map<_, _>>()
            .into(),
        serde_json::Value::Array(a) => a.iter().map(without_measurements).collect(),
        other => other.clone(),
    }
}

/// Runs `disk` on `mesh` writing OBJ, GLB, a flat OBJ and a report (in `dir`, files
/// tagged `k`); returns the three outputs' bytes and the report.
fn run_disk(
    mesh: &Path,
    dir: &Path,
    k: &str,
    env: &[(&str, &str)],
    extra: &[&str],
) -> (Vec<Vec<u8>>, serde_json::Value) {
    let files = [
        dir.join(format!("o{k}.obj")),
        dir.join(format!("o{k}.glb")),
        dir.join(format!("f{k}.obj")),
    ];
    let rep = dir.join(format!("r{k}.json"));
    for out in &files[..2] {
        let mut args = vec![
            "disk",
            s(mesh),
            "-o",
            s(out),
            "--flat",
            s(&files[2]),
            "--report",
            s(&rep),
        ];
        args.extend(extra);
        let o = conformap_env(&args, env);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let bytes = files.iter().map(|f| std::fs::read(f).unwrap()).collect();
    (bytes, json(&rep))
}

/// Asserts byte-identical outputs and reports identical but for the measurements.
fn assert_same(
    tag: &str,
    a: &(Vec<Vec<u8>>, serde_json::Value),
    b: &(Vec<Vec<u8>>, serde_json::Value),
) {
    for (k, name) in ["OBJ", "GLB", "flat OBJ"].iter().enumerate() {
        assert!(a.0[k] == b.0[k], "{tag}: the {name} outputs differ");
    }
    assert_eq!(
        without_measurements(&a.1),
        without_measurements(&b.1),
        "{tag}"
    );
    assert!(a.1["timings_ms"]["total"].as_f64().is_some());
}

/// Runs `disk` twice on `mesh` and asserts byte-identical outputs.
fn assert_deterministic(mesh: &Path, tag: &str, env: &[(&str, &str)], extra: &[&str]) {
    let d = tmpdir(tag);
    let a = run_disk(mesh, &d, "0", env, extra);
    let b = run_disk(mesh, &d, "1", env, extra);
    assert_same(tag, &a, &b);
}

#[test]
fn the_same_input_gives_byte_identical_outputs() {
    assert_deterministic(&fixture("spothead.obj"), "det-spot", &[], &[]);
    assert_deterministic(
        &fixture("bad/dirty_disk.obj"),
        "det-dirty",
        &[],
        &["--repair"],
    );
}

/// faer factors `L_II` with a supernodal Cholesky whose dense kernels run on rayon threads.
/// Measured (2 cores): hand.obj (53k vertices) and igea_open.obj (130k) give the same bytes
/// run after run and with 1 or 2 threads, so no single-threaded mode is needed.
#[test]
#[ignore = "large shared meshes; run with --release -- --ignored"]
fn supernodal_parallel_factorization_is_reproducible() {
    use conformap_io::read_mesh;
    use conformap_operators::{
        cotan_laplacian, Cholesky, CholeskyOptions, LaplacianBlocks, Partition,
    };
    for name in ["hand.obj", "igea_open.obj"] {
        let Some(path) = shared(name) else { continue };
        // the default method and CEM, twice each, and on all threads against one
        for method in ["ccem-qn", "cem"] {
            let d = tmpdir("det-big");
            let m = ["--method", method];
            let all = run_disk(&path, &d, "a", &[], &m);
            assert_same(name, &all, &run_disk(&path, &d, "b", &[], &m));
            let one = run_disk(&path, &d, "1", &[("RAYON_NUM_THREADS", "1")], &m);
            assert_same(&format!("{name} {method}, 1 thread"), &all, &one);
        }
        // the factor itself, all threads against one: identical solves
        let mesh = read_mesh(&path).unwrap().mesh;
        let l = cotan_laplacian(&mesh);
        let part = Partition::new(mesh.num_vertices(), &mesh.boundary_loops()[0]);
        let ii = LaplacianBlocks::new(&l, &part).ii;
        let many = Cholesky::factor_with(&ii, &CholeskyOptions::DEFAULT).unwrap();
        let one = Cholesky::factor_with(&ii, &CholeskyOptions::DEFAULT.with_threads(1)).unwrap();
        assert!(
            many.stats().supernodal,
            "{name}: expected a supernodal factor"
        );
        let rhs: Vec<f64> = (0..ii.rows())
            .map(|i| ((i * 7919) % 1000) as f64 - 500.0)
            .collect();
        let (mut x, mut y) = (rhs.clone(), rhs);
        many.solve_in_place(&mut x, 1);
        one.solve_in_place(&mut y, 1);
        assert!(
            x.iter().zip(&y).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{name}: 1 and all threads differ"
        );
        eprintln!(
            "{name}: n = {}, nnz(L) = {}, factor {:.0} ms on all threads, {:.0} ms on one",
            ii.rows(),
            many.stats().nnz_factor,
            many.stats().factor_ms,
            one.stats().factor_ms
        );
    }
}

/// The memory estimate is an upper bound of the measured peak (VmHWM) on real meshes, for
/// the default method and CEM, and not far above it (within 2×, but for maze.obj whose
/// dense-Schur allowance of 8 n_B² = 75 MiB CCEM declines there). Run after changing the
/// pipeline's memory use.
#[test]
#[ignore = "large shared meshes; run with --release -- --ignored"]
fn memory_estimate_bounds_the_measured_peak() {
    let d = tmpdir("mem-cal");
    let (out, rep) = (d.join("o.obj"), d.join("r.json"));
    for name in [
        "woody.obj",
        "spothead.obj",
        "camelhead.obj",
        "human_face.obj",
        "chinese_lion.obj",
        "maze.obj",
        "hand.obj",
        "igea_open.obj",
    ] {
        let Some(path) = shared(name) else { continue };
        for method in ["ccem-qn", "cem", "harmonic"] {
            let o = conformap(&[
                "disk",
                s(&path),
                "-o",
                s(&out),
                "--report",
                s(&rep),
                "--method",
                method,
            ]);
            assert!(o.status.success(), "{name}: {}", stderr(&o));
            let m = &json(&rep)["memory"];
            let est = m["estimated_peak_bytes"].as_u64().unwrap() as f64;
            let peak = m["peak_rss_bytes"].as_u64().unwrap() as f64;
            eprintln!(
                "{name} {method}: estimate {:.1} MiB, peak {:.1} MiB ({:.2}×)",
                est / 1048576.0,
                peak / 1048576.0,
                est / peak
            );
            assert!(
                peak <= est,
                "{name} {method}: estimate {est} below the peak {peak}"
            );
            if name != "maze.obj" {
                assert!(est <= 2.0 * peak, "{name} {method}: {est} vs {peak}");
            }
        }
    }
}
