//! The large shared meshes (`../shared/meshes/`): run with
//! `cargo test --release -p conformap-sphere --test large_meshes -- --ignored`.
//! Each test skips (saying so) a mesh that is absent.

mod common;

use common::{assert_more_uniform, uniform_disk, uniform_sphere};
use conformap_sphere::{sphere_map, sphere_metrics, SphereOptions};

/// Mean chord-angle distortion bounds (degrees): the 2° for david_head and brain
/// (measured 0.877° and 1.226°); armadillo measured 1.926°, spot 2.953°.
const MEAN_ANGLE_BOUND_DEG: [(&str, f64); 4] = [
    ("spot.obj", 3.1),
    ("david_head.obj", 2.0),
    ("armadillo.obj", 2.1),
    ("brain.obj", 2.0),
];

#[test]
#[ignore = "large meshes: run in release with --ignored"]
fn class_c_sphere_maps() {
    for (name, bound) in MEAN_ANGLE_BOUND_DEG {
        let Some(mesh) = conformap_testkit::read_shared_mesh_or_skip(name, "class_c_sphere_maps")
        else {
            continue;
        };
        let map = sphere_map(&mesh, &SphereOptions::DEFAULT).unwrap();
        let m = sphere_metrics(&mesh, &map.points).unwrap();
        assert!(
            m.radius_residual_max <= 1e-12,
            "{name}: {}",
            m.radius_residual_max
        );
        assert_eq!(m.flipped_faces, 0, "{name}");
        assert!(
            m.angle_distortion_deg.mean < bound,
            "{name}: {:?}",
            m.angle_distortion_deg
        );
        let best = uniform_sphere(&mesh, &map.points);
        assert_more_uniform(&best.report, name);
        let m2 = sphere_metrics(&mesh, &best.points).unwrap();
        assert_eq!(m2.flipped_faces, 0, "{name}");
        assert!(m2.radius_residual_max <= 1e-12);
        assert!(
            (m2.cross_ratio_log.mean_abs - m.cross_ratio_log.mean_abs).abs() < 1e-9,
            "{name}"
        );
    }
}

/// Expected differences: maps whose crowded parts hold image triangles near or below f64
/// resolution (alligator's limbs, maze's corridors, the 7 boundary gaps of igea_open's
/// CCEM map held at 1e-13 rad), where moving the points by any map re-rounds the tiny
/// edges, so the invariant cross-ratios change by round-off above 1e-9. Measured mean |Δ|
/// (CEM / CCEM-QN): alligator 8.4e-4 / 2.2e-5, maze – / 2.4e-11, igea_open 1.7e-16 /
/// 2.9e-9; every other mesh ≤ 5e-15. maze's raw CEM map folds 3,260 faces (its corridors
/// crowd below what f64 resolves): cross-ratios of folded triangles say nothing, and only
/// its uniformity is checked.
const CROWDED: [(&str, f64); 3] = [
    ("alligator.obj", 2e-3),
    ("maze.obj", 1e-6),
    ("igea_open.obj", 1e-6),
];

#[test]
#[ignore = "large meshes: run in release with --ignored"]
fn class_a_mobius_lowers_uniformity_of_cem_and_ccem() {
    for name in conformap_testkit::CLASS_A {
        let Some(mesh) = conformap_testkit::read_shared_mesh_or_skip(name, "class_a_mobius") else {
            continue;
        };
        let mut problem = conformap_disk::DiskProblem::new(&mesh).unwrap();
        let cem = conformap_disk::cem(&mut problem, &conformap_disk::CemOptions::DEFAULT).unwrap();
        let ccem = conformap_disk::compute_disk_map(
            &mesh,
            conformap_disk::DiskMethod::CcemQn,
            &conformap_disk::DiskOptions::DEFAULT,
        )
        .unwrap();
        for (method, map) in [("cem", &cem.map), ("ccem-qn", &ccem.map)] {
            let best = uniform_disk(&mesh, map);
            let r = &best.report;
            assert_more_uniform(r, &format!("{name} {method}"));
            // the moved map inverts no face the given one did not (maze: the optimal boost
            // would invert 2,393 crowded faces and is shortened)
            let inverted = |m: &[num_complex::Complex64]| {
                mesh.faces()
                    .iter()
                    .filter(|t| {
                        let (u, v) = (
                            m[t[1] as usize] - m[t[0] as usize],
                            m[t[2] as usize] - m[t[0] as usize],
                        );
                        !(u.re * v.im - u.im * v.re > 0.0)
                    })
                    .count()
            };
            assert!(
                inverted(&best.map) <= inverted(map),
                "{name} {method}: {} inverted faces after, {} before (flip limit {:?})",
                inverted(&best.map),
                inverted(map),
                r.flip_limited
            );
            let a = conformap_metrics::cross_ratio_distortion(&mesh, map).unwrap();
            let b = conformap_metrics::cross_ratio_distortion(&mesh, &best.map).unwrap();
            eprintln!(
                "{name} {method}: uniformity {:.4e} -> {:.4e}, cross-ratio mean change {:.1e}, \
                 flip limit {:?}",
                r.uniformity_before,
                r.uniformity_after,
                (a.mean_abs - b.mean_abs).abs(),
                r.flip_limited
            );
            if name == "maze.obj" && method == "cem" {
                continue;
            }
            let tol = CROWDED
                .iter()
                .find(|(n, _)| *n == name)
                .map_or(1e-9, |(_, t)| *t);
            assert!(
                (a.mean_abs - b.mean_abs).abs() < tol,
                "{name} {method}: {a:?} {b:?}"
            );
        }
    }
}
