//! The large shared meshes (`../shared/meshes/`): run with
//! `cargo test --release -p conformap-global --test large_meshes -- --ignored`.
//! Each test skips (saying so) a mesh that is absent.

mod common;

use conformap_global::{
    optimize_disk_mobius, optimize_sphere_mobius, planar_cross_ratio_distortion, sphere_map,
    sphere_metrics, MobiusObjective, MobiusOptions, SphereOptions,
};

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
        let Some(path) = conformap_testkit::shared_mesh_or_skip(name, "class_c_sphere_maps") else {
            continue;
        };
        let mesh = conformap_testkit::read_plain_obj(&path).unwrap();
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
        let best = optimize_sphere_mobius(
            &mesh,
            &map.points,
            &MobiusObjective::Uniform,
            &MobiusOptions::DEFAULT,
        )
        .unwrap();
        let r = &best.report;
        assert!(
            r.uniformity_after < r.uniformity_before,
            "{name}: {} -> {}",
            r.uniformity_before,
            r.uniformity_after
        );
        let m2 = sphere_metrics(&mesh, &best.points).unwrap();
        assert_eq!(m2.flipped_faces, 0, "{name}");
        assert!(m2.radius_residual_max <= 1e-12);
        assert!(
            (m2.cross_ratio_log.mean_abs - m.cross_ratio_log.mean_abs).abs() < 1e-9,
            "{name}"
        );
    }
}

/// Expected differences: CEM maps whose crowded parts hold image triangles near or below
/// f64 resolution (alligator's limbs, maze's corridors), where moving the points by any map
/// re-rounds the tiny edges, so the invariant cross-ratios change by round-off far above
/// 1e-9. Measured mean |Δ|: alligator 1.7e-4, maze 4.0e-2; every other mesh ≤ 4e-15.
const CROWDED: [(&str, f64); 2] = [("alligator.obj", 1e-3), ("maze.obj", 0.1)];

#[test]
#[ignore = "large meshes: run in release with --ignored"]
fn class_a_mobius_lowers_uniformity_of_cem() {
    for name in [
        "woody.obj",
        "alligator.obj",
        "spothead.obj",
        "maze.obj",
        "camelhead.obj",
        "human_face.obj",
        "chinese_lion.obj",
        "hand.obj",
        "igea_open.obj",
    ] {
        let Some(path) = conformap_testkit::shared_mesh_or_skip(name, "class_a_mobius") else {
            continue;
        };
        let mesh = conformap_testkit::read_plain_obj(&path).unwrap();
        let mut problem = conformap_disk::DiskProblem::new(&mesh).unwrap();
        let cem = conformap_disk::cem(&mut problem, &conformap_disk::CemOptions::DEFAULT).unwrap();
        let best = optimize_disk_mobius(
            &mesh,
            &cem.map,
            &MobiusObjective::Uniform,
            &MobiusOptions::DEFAULT,
        )
        .unwrap();
        let r = &best.report;
        assert!(
            r.uniformity_after < r.uniformity_before,
            "{name}: {} -> {}",
            r.uniformity_before,
            r.uniformity_after
        );
        let a = planar_cross_ratio_distortion(&mesh, &cem.map).unwrap();
        let b = planar_cross_ratio_distortion(&mesh, &best.map).unwrap();
        let tol = CROWDED
            .iter()
            .find(|(n, _)| *n == name)
            .map_or(1e-9, |(_, t)| *t);
        assert!((a.mean_abs - b.mean_abs).abs() < tol, "{name}: {a:?} {b:?}");
    }
}
