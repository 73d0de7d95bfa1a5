//! Sphere maps: the round sphere, a real mesh (spot), wrong topologies.

mod common;

use common::{norm, uniform_sphere};
use conformap_sphere::{sphere_map, sphere_metrics, SphereError, SphereOptions};

/// Mean chord-angle distortion of spot's sphere map, measured 2.953° (default options; see
/// the README table), with headroom for platform rounding.
const SPOT_MEAN_ANGLE_BOUND_DEG: f64 = 3.1;

#[test]
fn round_sphere_maps_to_itself_up_to_rotation() {
    let mesh = conformap_testkit::icosphere(1.0, 4);
    let map = sphere_map(&mesh, &SphereOptions::DEFAULT).unwrap();
    let best = uniform_sphere(&mesh, &map.points);
    let m = sphere_metrics(&mesh, &best.points).unwrap();
    assert_eq!(m.flipped_faces, 0);
    assert!(
        m.angle_distortion_deg.mean < 0.1,
        "{:?}",
        m.angle_distortion_deg
    );
    // a rotation keeps every inner product
    let p = mesh.positions();
    let mut worst = 0.0f64;
    for i in (0..p.len()).step_by(5) {
        for j in (0..p.len()).step_by(13) {
            let a = p[i][0] * p[j][0] + p[i][1] * p[j][1] + p[i][2] * p[j][2];
            let (x, y) = (best.points[i], best.points[j]);
            worst = worst.max((a - (x[0] * y[0] + x[1] * y[1] + x[2] * y[2])).abs());
        }
    }
    assert!(worst < 2e-3, "inner products differ by {worst}");
}

#[test]
fn spot_maps_to_the_sphere_without_inversions() {
    let Some(mesh) = common::read("spot.obj") else {
        return;
    };
    assert_eq!(mesh.num_vertices(), 2930);
    let map = sphere_map(&mesh, &SphereOptions::DEFAULT).unwrap();
    assert!(map.points.iter().all(|&p| (norm(p) - 1.0).abs() <= 1e-12));
    let m = sphere_metrics(&mesh, &map.points).unwrap();
    assert!(m.radius_residual_max <= 1e-12);
    assert_eq!(m.flipped_faces, 0);
    assert!(
        m.angle_distortion_deg.mean < SPOT_MEAN_ANGLE_BOUND_DEG,
        "{:?}",
        m.angle_distortion_deg
    );
    // the corrections helped: the first stage (Angenent's map) is worse than the result
    let r = &map.report;
    assert!(
        r.stages[r.best_stage].mean_angle_distortion_deg
            < 0.8 * r.stages[0].mean_angle_distortion_deg
    );
    // Möbius optimization lowers the uniformity energy and keeps the map on the sphere
    let best = uniform_sphere(&mesh, &map.points);
    assert!(best.report.uniformity_after < 0.9 * best.report.uniformity_before);
    let m2 = sphere_metrics(&mesh, &best.points).unwrap();
    assert!(m2.radius_residual_max <= 1e-12);
    assert_eq!(m2.flipped_faces, 0);
    assert!((m2.cross_ratio_log.mean_abs - m.cross_ratio_log.mean_abs).abs() < 1e-9);
    assert!((m2.uniformity_energy - best.report.uniformity_after).abs() < 1e-15);
}

#[test]
fn wrong_topologies_and_options_are_errors() {
    let disk = conformap_testkit::flat_disk(3, 6);
    assert!(matches!(
        sphere_map(&disk, &SphereOptions::DEFAULT),
        Err(SphereError::WrongTopology { .. })
    ));
    let torus = conformap_testkit::torus(2.0, 0.5, 12, 8);
    assert!(matches!(
        sphere_map(&torus, &SphereOptions::DEFAULT),
        Err(SphereError::WrongTopology { .. })
    ));
    let s = conformap_testkit::icosphere(1.0, 1);
    for bad in [
        SphereOptions::DEFAULT.with_fixed_fraction(0.0),
        SphereOptions::DEFAULT.with_fixed_fraction(1.0),
        SphereOptions::DEFAULT.with_source_face(Some(10_000)),
    ] {
        assert!(matches!(
            sphere_map(&s, &bad),
            Err(SphereError::InvalidOption { .. })
        ));
    }
}

#[test]
fn zero_corrections_return_angenents_map() {
    let mesh = conformap_sphere::doc_support::octahedron_sphere(3);
    let map = sphere_map(&mesh, &SphereOptions::DEFAULT.with_max_corrections(0)).unwrap();
    assert_eq!(map.report.stages.len(), 1);
    assert_eq!(map.report.factorizations, 1);
    assert_eq!(sphere_metrics(&mesh, &map.points).unwrap().flipped_faces, 0);
}
