//! CEM disk maps on real meshes and on analytic ones, judged by the metrics crate.
//!
//! The default run uses the committed fixtures (woody, alligator, spothead); the whole of
//! class a in `../shared/meshes/` runs with `cargo test --release -- --ignored`.

use conformap_disk::{cem, harmonic_arc_length, CemOptions, DiskMap, DiskProblem};
use conformap_mesh::TriMesh;
use conformap_metrics::{planar_map_metrics, MapMetrics, MetricsOptions};
use conformap_testkit::{fixture_path, flat_disk, shared_mesh_or_skip};
use num_complex::Complex64;

/// E_C that the best other tools reach on the same files (judged like ours); CEM must come
/// within 10 % of it.
const REFERENCE_EC: &[(&str, f64)] = &[
    ("woody.obj", 0.0670),
    ("alligator.obj", 0.0187),
    ("spothead.obj", 0.0130),
    ("camelhead.obj", 0.0457),
    ("human_face.obj", 0.00324),
    ("chinese_lion.obj", 0.0139),
    ("hand.obj", 0.0110),
    ("igea_open.obj", 0.0322),
];

/// Meshes whose cotangent weights are all positive: Tutte's theorem promises no flips.
const ALL_POSITIVE_WEIGHTS: &[&str] = &["woody.obj", "alligator.obj", "hand.obj"];

struct Outcome {
    cem: DiskMap,
    metrics: MapMetrics,
    harmonic_ec: f64,
}

fn run(mesh: &TriMesh) -> Outcome {
    run_with(mesh, &CemOptions::DEFAULT)
}

fn run_with(mesh: &TriMesh, options: &CemOptions) -> Outcome {
    let mut problem = DiskProblem::new(mesh).expect("disk problem");
    let harmonic = harmonic_arc_length(&problem);
    let harmonic_ec = harmonic.report.energy_history[0];
    let cem = cem(&mut problem, options).expect("cem");
    let metrics = planar_map_metrics(mesh, &cem.map, &MetricsOptions::default()).expect("metrics");
    Outcome {
        cem,
        metrics,
        harmonic_ec,
    }
}

fn check(name: &str, mesh: &TriMesh) {
    let o = run(mesh);
    let r = &o.cem.report;
    let ec = o.metrics.conformal_energy;
    let history_min = r
        .energy_history
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let reference = REFERENCE_EC
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, e)| *e)
        .expect("reference");
    eprintln!(
        "{name}: E_C {ec:.5} (reference {reference}, harmonic {:.5}), best iterate {} of {}, flips {}",
        o.harmonic_ec, r.best_iteration, r.iterations, o.metrics.flipped_faces
    );
    // the boundary is on the unit circle
    assert!(
        o.metrics.circle_residual_max < 1e-12,
        "{name}: circle residual {}",
        o.metrics.circle_residual_max
    );
    // the solver's energy is the judge's energy
    let solver_ec = r.energy_history[r.best_iteration];
    assert!(
        (ec - solver_ec).abs() <= 1e-9 * ec,
        "{name}: metrics {ec} vs solver {solver_ec}"
    );
    // the returned map is the best iterate, no worse than the initial map
    assert_eq!(solver_ec, history_min, "{name}");
    assert!(solver_ec <= r.energy_history[0], "{name}");
    // better than the usual starting point, and close to the best other tools
    assert!(
        ec < o.harmonic_ec,
        "{name}: {ec} vs harmonic {}",
        o.harmonic_ec
    );
    assert!(
        ec <= 1.10 * reference,
        "{name}: {ec} vs reference {reference}"
    );
    assert!(r.residual < 1e-10, "{name}: residual {}", r.residual);
    if ALL_POSITIVE_WEIGHTS.contains(&name) {
        assert_eq!(o.metrics.flipped_faces, 0, "{name}");
    }
    assert_eq!(o.metrics.degenerate_faces, 0, "{name}");
}

fn read(path: &std::path::Path) -> TriMesh {
    conformap_io::read_mesh(path).expect("read mesh").mesh
}

#[test]
fn cem_on_fixture_meshes() {
    for name in ["woody.obj", "alligator.obj", "spothead.obj"] {
        check(name, &read(&fixture_path(name)));
    }
}

#[test]
#[ignore = "reads the large meshes of ../shared/meshes; run with --release -- --ignored"]
fn cem_on_all_class_a_meshes() {
    for (name, _) in REFERENCE_EC {
        if let Some(path) = shared_mesh_or_skip(name, "cem_on_all_class_a_meshes") {
            check(name, &read(&path));
        }
    }
}

/// Max distance of the CEM map of `flat_disk(rings, 6)` from the best rotation of the
/// identity, and the map's conformal energy.
fn flat_disk_deviation(rings: usize) -> (f64, f64) {
    let mesh = flat_disk(rings, 6);
    // run CEM to its fixed point
    let o = run_with(
        &mesh,
        &CemOptions::DEFAULT.with_max_iter(400).with_tol(1e-14),
    );
    let z: Vec<Complex64> = mesh
        .positions()
        .iter()
        .map(|p| Complex64::new(p[0], p[1]))
        .collect();
    // best rotation e^{iφ}: φ = arg Σ f z̄
    let s: Complex64 = o.cem.map.iter().zip(&z).map(|(f, w)| f * w.conj()).sum();
    let rot = s / s.norm();
    let err = o
        .cem
        .map
        .iter()
        .zip(&z)
        .map(|(f, w)| (f - rot * w).norm())
        .fold(0.0, f64::max);
    (err, o.metrics.conformal_energy)
}

#[test]
fn flat_disk_maps_to_itself_up_to_rotation() {
    // The identity of a flat disk mesh has E_C = 0 exactly; CEM's fixed point is not the
    // exact minimizer but converges to it with the mesh: measured deviation 2.1e-3 (6 rings),
    // 5.0e-4 (12), 1.2e-4 (24), i.e. ≈ 0.075 h² for h = 1/rings.
    let (e6, c6) = flat_disk_deviation(6);
    let (e12, c12) = flat_disk_deviation(12);
    eprintln!(
        "flat disk: deviation {e6:.3e} (6 rings), {e12:.3e} (12 rings); E_C {c6:.3e}, {c12:.3e}"
    );
    assert!(e6 <= 0.1 / 36.0 && e12 <= 0.1 / 144.0, "{e6} {e12}");
    assert!(
        e6 / e12 > 3.5,
        "second-order convergence expected: {e6} / {e12}"
    );
    assert!(c12 < c6 / 10.0 && c12 < 1e-5, "{c6} {c12}");
}

#[test]
fn punctured_torus_is_refused() {
    let mesh = read(&fixture_path("punctured_torus.obj"));
    let err = DiskProblem::new(&mesh).expect_err("a genus-1 mesh is no disk");
    assert!(err.to_string().contains("genus 1"), "{err}");
}
