//! Möbius transformations: group laws, invariants, and the optimizer on analytic cases.

mod common;

use common::{norm, Lcg};
use conformap_sphere::{
    optimize_disk_mobius, optimize_sphere_mobius, sphere_metrics, DiskAutomorphism, Mobius,
    MobiusObjective, MobiusOptions, SphereError,
};
use num_complex::Complex64;

fn random_mobius(rng: &mut Lcg) -> Mobius {
    let mut c = || Complex64::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
    let (a, b, cc, d) = (c(), c(), c(), c());
    Mobius::try_new(a, b, cc, d).expect("random matrices are regular")
}

fn random_sphere_point(rng: &mut Lcg) -> [f64; 3] {
    loop {
        let p = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let r = norm(p);
        if r > 0.1 && r <= 1.0 {
            return [p[0] / r, p[1] / r, p[2] / r];
        }
    }
}

#[test]
fn mobius_composed_with_inverse_is_the_identity() {
    let mut rng = Lcg(20240611);
    for _ in 0..200 {
        let m = random_mobius(&mut rng);
        let id = m.compose(&m.inverse());
        for _ in 0..10 {
            let p = random_sphere_point(&mut rng);
            for q in [
                m.inverse().apply_sphere(m.apply_sphere(p)),
                id.apply_sphere(p),
            ] {
                let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
                assert!(norm(d) < 1e-12, "{p:?} came back as {q:?}");
            }
            let z = Complex64::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            let back = m.inverse().apply(m.apply(z));
            assert!((back - z).norm() < 1e-12 * (1.0 + z.norm()));
        }
        // ad − bc = 1 after normalization
        assert!((m.a * m.d - m.b * m.c - 1.0).norm() < 1e-13);
    }
}

#[test]
fn disk_automorphisms_keep_the_circle_and_the_disk() {
    let mut rng = Lcg(7);
    for _ in 0..200 {
        let v = [rng.range(-3.0, 3.0), rng.range(-3.0, 3.0)];
        let m = DiskAutomorphism::from_vector(v)
            .compose(&DiskAutomorphism::rotation(rng.range(0.0, 7.0)));
        assert!((m.a.norm_sqr() - m.b.norm_sqr() - 1.0).abs() < 1e-10);
        for _ in 0..20 {
            let t = rng.range(0.0, std::f64::consts::TAU);
            let z = Complex64::from_polar(1.0, t);
            assert!((m.apply(z).norm() - 1.0).abs() < 1e-12);
            let w = Complex64::from_polar(rng.next().sqrt() * 0.999, t);
            assert!(m.apply(w).norm() < 1.0);
            assert!((m.inverse().apply(m.apply(w)) - w).norm() < 1e-10);
        }
    }
    // a map with |b| ≥ |a| does not keep the disk and is refused
    assert!(matches!(
        DiskAutomorphism::try_new(Complex64::new(1.0, 0.0), Complex64::new(0.0, 2.0)),
        Err(SphereError::SingularMobius { .. })
    ));
}

/// A Möbius map is conformal: the exactly Möbius-invariant discrete measure (length
/// cross-ratios) does not move; the chord-triangle angles move by O(h |∇ log λ|).
#[test]
fn mobius_maps_keep_cross_ratios_exactly() {
    let mesh = conformap_sphere::doc_support::octahedron_sphere(3);
    let base: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .map(|p| {
            let r = norm([p[0], p[1], 2.0 * p[2]]);
            [p[0] / r, p[1] / r, 2.0 * p[2] / r]
        })
        .collect();
    let m0 = sphere_metrics(&mesh, &base).unwrap();
    let mut rng = Lcg(99);
    for _ in 0..10 {
        let m = random_mobius(&mut rng);
        let moved: Vec<[f64; 3]> = base.iter().map(|&p| m.apply_sphere(p)).collect();
        let m1 = sphere_metrics(&mesh, &moved).unwrap();
        assert!((m1.cross_ratio_log.mean_abs - m0.cross_ratio_log.mean_abs).abs() < 1e-9);
        assert!((m1.cross_ratio_log.max_abs - m0.cross_ratio_log.max_abs).abs() < 1e-9);
        assert_eq!(m1.flipped_faces, 0);
    }
    // planar: a disk automorphism of a flat disk mesh
    let disk = conformap_testkit::flat_disk(8, 10);
    let z: Vec<Complex64> = disk
        .positions()
        .iter()
        .map(|p| Complex64::new(p[0], p[1]))
        .collect();
    let c0 = conformap_metrics::cross_ratio_distortion(&disk, &z).unwrap();
    let a = DiskAutomorphism::from_vector([1.3, -0.4]);
    let w: Vec<Complex64> = z.iter().map(|&q| a.apply(q)).collect();
    let c1 = conformap_metrics::cross_ratio_distortion(&disk, &w).unwrap();
    assert!(c0.max_abs < 1e-12 && c1.max_abs < 1e-9, "{c0:?} {c1:?}");
}

#[test]
fn uniform_optimum_undoes_a_boost_of_the_round_sphere() {
    let mesh = conformap_testkit::icosphere(1.0, 3);
    let boost = Mobius::boost([0.8, -0.5, 1.1]);
    let moved: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .map(|&p| boost.apply_sphere(p))
        .collect();
    let best = optimize_sphere_mobius(
        &mesh,
        &moved,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    )
    .unwrap();
    let r = &best.report;
    assert!(
        r.uniformity_after < 1e-3 * r.uniformity_before,
        "{} -> {}",
        r.uniformity_before,
        r.uniformity_after
    );
    // the result is the icosphere up to rotation: inner products are kept
    let p = mesh.positions();
    for i in (0..p.len()).step_by(7) {
        for j in (0..p.len()).step_by(11) {
            let a = p[i][0] * p[j][0] + p[i][1] * p[j][1] + p[i][2] * p[j][2];
            let q = (&best.points[i], &best.points[j]);
            let b = q.0[0] * q.1[0] + q.0[1] * q.1[1] + q.0[2] * q.1[2];
            assert!((a - b).abs() < 1e-6, "{a} vs {b}");
        }
    }
    assert!(r.starts.iter().all(|s| s.converged));
}

#[test]
fn emphasis_grows_the_region_up_to_the_cap() {
    let disk = conformap_testkit::flat_disk(10, 12);
    let z: Vec<Complex64> = disk
        .positions()
        .iter()
        .map(|p| Complex64::new(p[0], p[1]))
        .collect();
    let right: Vec<usize> = (0..disk.num_faces())
        .filter(|&f| {
            disk.faces()[f]
                .iter()
                .map(|&v| disk.positions()[v as usize][0])
                .sum::<f64>()
                > 0.0
        })
        .collect();
    let mut last = 0.0;
    for cap in [10.0, 100.0, 1e4] {
        let opts = MobiusOptions::DEFAULT.with_max_area_scale(cap);
        let r = optimize_disk_mobius(
            &disk,
            &z,
            &MobiusObjective::Emphasize {
                region: right.clone(),
            },
            &opts,
        )
        .unwrap()
        .report;
        let after = r.region_share_after.unwrap();
        assert!(after > r.region_share_before.unwrap());
        assert!(r.cap_active, "the emphasized share has no interior maximum");
        assert!((r.max_area_scale - cap).abs() < 1e-6 * cap);
        assert!(after > last);
        last = after;
    }
    assert!(last > 0.95);
    // bad regions are errors, not panics
    let bad = MobiusObjective::Emphasize {
        region: vec![disk.num_faces()],
    };
    assert!(matches!(
        optimize_disk_mobius(&disk, &z, &bad, &MobiusOptions::DEFAULT),
        Err(SphereError::RegionFaceOutOfRange { .. })
    ));
    let empty = MobiusObjective::Emphasize { region: vec![] };
    assert!(matches!(
        optimize_disk_mobius(&disk, &z, &empty, &MobiusOptions::DEFAULT),
        Err(SphereError::DegenerateRegion { .. })
    ));
}

#[test]
fn maps_off_the_domain_are_refused() {
    let mesh = conformap_testkit::icosphere(2.0, 1);
    let err = optimize_sphere_mobius(
        &mesh,
        mesh.positions(),
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    );
    assert!(matches!(
        err,
        Err(SphereError::NotOnSphere { vertex: 0, .. })
    ));
    let disk = conformap_testkit::flat_disk(3, 6);
    let z: Vec<Complex64> = disk
        .positions()
        .iter()
        .map(|p| Complex64::new(2.0 * p[0], p[1]))
        .collect();
    let err = optimize_disk_mobius(
        &disk,
        &z,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    );
    assert!(matches!(err, Err(SphereError::NotInDisk { .. })));
}
