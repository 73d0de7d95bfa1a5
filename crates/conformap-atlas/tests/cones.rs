//! Cone placement on the bundled spot (closed, genus 0): 8 cones with less area spread than
//! boundary first flattening's 8 (1.01 with its command-line tool), valid cone angles, and
//! the Gauss–Bonnet balance; the cone metric of a flat disk is flat.

use conformap_atlas::{place_cones, ConeMetric, ConeOptions};

fn spot() -> conformap_mesh::TriMesh {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/spot.obj");
    conformap_io::read_mesh(path).expect("fixture reads").mesh
}

#[test]
fn eight_cones_on_spot_spread_less_than_bff() {
    let mesh = spot();
    let metric = ConeMetric::new(&mesh).expect("factors");
    // Gauss–Bonnet: a closed genus-0 surface carries 4π
    assert!((metric.total_defect() - 4.0 * std::f64::consts::PI).abs() < 1e-9);
    let set = place_cones(&metric, 8, &ConeOptions::default());
    assert_eq!(set.cones.len(), 8);
    let sum: f64 = set.cones.iter().map(|c| c.defect).sum();
    assert!(
        (sum - 4.0 * std::f64::consts::PI).abs() < 1e-9,
        "defects sum to {sum}"
    );
    for c in &set.cones {
        assert!(
            c.angle_deg() >= 90.0 - 1e-9 && c.angle_deg() <= 720.0 + 1e-9,
            "{c:?}"
        );
    }
    // BFF's tool: 1.01; measured 0.825 here (0.835 before the local descent)
    assert!(set.area_spread < 0.83, "spread {}", set.area_spread);
    assert!(set.area_spread <= set.greedy_spread);
    // the cone metric really has those curvatures: L u = K̃ − K away from the pinned vertex
    let u2 = metric.scale_factor(
        &set.cones
            .iter()
            .map(|c| (c.vertex, c.defect))
            .collect::<Vec<_>>(),
    );
    assert_eq!(u2, set.u);
}

#[test]
fn a_flat_disk_needs_no_scale() {
    // a planar fan: K = 0 inside, u = 0 on the boundary, so u = 0
    let mut p = vec![[0.0, 0.0, 0.0]];
    p.extend((0..12).map(|k| {
        let t = std::f64::consts::TAU * k as f64 / 12.0;
        [t.cos(), t.sin(), 0.0]
    }));
    let faces = (0..12u32).map(|k| [0, 1 + k, 1 + (k + 1) % 12]).collect();
    let mesh = conformap_mesh::TriMesh::try_new(p, faces).expect("valid");
    let metric = ConeMetric::new(&mesh).expect("factors");
    assert!(!metric.closed());
    let u = metric.scale_factor(&[]);
    assert!(u.iter().all(|x| x.abs() < 1e-14), "{u:?}");
    // one cone of defect π/2 at the centre: L u = K̃ − K gives u₀ = (π/2) / L₀₀, and the
    // regular 12-gon's centre has L₀₀ = 12 cot(75°) (two half-cotangents per spoke)
    let u = metric.scale_factor(&[(0, std::f64::consts::FRAC_PI_2)]);
    let l00 = 12.0 / 75f64.to_radians().tan();
    assert!(
        (u[0] - std::f64::consts::FRAC_PI_2 / l00).abs() < 1e-12,
        "{}",
        u[0]
    );
    assert!(u[1..].iter().all(|x| x.abs() < 1e-14));
}
