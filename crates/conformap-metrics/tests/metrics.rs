//! Metrics of maps whose answers are known in closed form, on analytic meshes from the
//! testkit and on the real planar mesh woody (fixtures/ or ../shared/meshes/).

use conformap_mesh::TriMesh;
use conformap_metrics::{
    conformal_energy, dirichlet_energy, image_area, planar_map_metrics, MapMetrics, MetricsError,
    MetricsOptions, OuterCircle, ANGLE_HISTOGRAM_EDGES_DEG, MAP_ABS_LIMIT,
};
use conformap_operators::{corner_angles, cotan_laplacian, quadratic_form, surface_area};
use conformap_testkit::{
    annulus, assert_near, assert_rel_near, disk_with_holes, flat_disk, icosphere, read_plain_obj,
    real_mesh_or_skip, square_grid, Circle,
};
use num_complex::Complex64;

type TestResult = Result<(), Box<dyn std::error::Error>>;

fn z(p: &[f64; 3]) -> Complex64 {
    Complex64::new(p[0], p[1])
}

/// `g(z)` at every vertex of a planar mesh.
fn planar_map(mesh: &TriMesh, g: impl Fn(Complex64) -> Complex64) -> Vec<Complex64> {
    mesh.positions().iter().map(|p| g(z(p))).collect()
}

/// woody (694 vertices, planar, one boundary loop), or `None` with a SKIPPED line.
fn woody(test: &str) -> Option<TriMesh> {
    let path = real_mesh_or_skip("woody.obj", test)?;
    match read_plain_obj(&path) {
        Ok(mesh) => Some(mesh),
        Err(e) => panic!("{e}"),
    }
}

fn metrics(mesh: &TriMesh, map: &[Complex64]) -> MapMetrics {
    match planar_map_metrics(mesh, map, &MetricsOptions::DEFAULT) {
        Ok(m) => m,
        Err(e) => panic!("{e}"),
    }
}

fn assert_perfect(m: &MapMetrics, what: &str) {
    assert!(
        m.conformal_energy.abs() <= 1e-12 * m.image_area,
        "{what}: E_C = {:e}, A = {:e}",
        m.conformal_energy,
        m.image_area
    );
    assert!(
        m.angle_distortion_deg.max < 1e-9,
        "{what}: {:?}",
        m.angle_distortion_deg
    );
    assert!(m.angle_distortion_deg.p95 < 1e-9, "{what}");
    assert!(m.beltrami_abs.max < 1e-12, "{what}: {:?}", m.beltrami_abs);
    assert!(
        m.area_distortion_log.mean_abs < 1e-12,
        "{what}: {:?}",
        m.area_distortion_log
    );
    assert_eq!((m.flipped_faces, m.degenerate_faces), (0, 0), "{what}");
}

#[test]
fn similarity_of_the_flat_disk_is_perfect() {
    let mesh = flat_disk(12, 6);
    let (a, c) = (Complex64::new(-0.6, 1.7), Complex64::new(3.0, -2.0));
    let m = metrics(&mesh, &planar_map(&mesh, |w| a * w + c));
    assert_perfect(&m, "flat disk");
    assert!(!m.orientation_reversed);
    // A = |a|² × the area of the disk polygon
    assert_rel_near!(m.image_area, a.norm_sqr() * surface_area(&mesh), 1e-13);
    assert_rel_near!(m.dirichlet_energy, m.image_area, 1e-13);
}

#[test]
fn similarity_of_woody_is_perfect() {
    let Some(mesh) = woody("similarity_of_woody_is_perfect") else {
        return;
    };
    // woody is planar (z = 0) with coordinates in the hundreds
    let (a, c) = (Complex64::new(0.002, -0.001), Complex64::new(-0.4, 0.3));
    let m = metrics(&mesh, &planar_map(&mesh, |w| a * w + c));
    assert_perfect(&m, "woody");
    assert_rel_near!(m.image_area, a.norm_sqr() * surface_area(&mesh), 1e-12);
}

#[test]
fn affine_map_has_the_predicted_beltrami_and_energy() {
    let (a, b) = (Complex64::new(1.2, 0.5), Complex64::new(-0.3, 0.4));
    let k = b.norm() / a.norm();
    for (name, mesh) in [("disk", flat_disk(10, 6)), ("grid", square_grid(7, 5))] {
        let m = metrics(&mesh, &planar_map(&mesh, |w| a * w + b * w.conj()));
        let area = surface_area(&mesh);
        assert_near!(m.beltrami_abs.mean, k, 1e-13, "{name}");
        assert_near!(m.beltrami_abs.max, k, 1e-13, "{name}");
        assert!(
            m.beltrami_abs.sd < 1e-13,
            "{name}: every face has |μ| = |b/a|"
        );
        assert_rel_near!(
            m.conformal_energy,
            2.0 * b.norm_sqr() * area,
            1e-12,
            "{name}"
        );
        assert_rel_near!(
            m.dirichlet_energy,
            (a.norm_sqr() + b.norm_sqr()) * area,
            1e-12,
            "{name}"
        );
        assert_rel_near!(
            m.image_area,
            (a.norm_sqr() - b.norm_sqr()) * area,
            1e-12,
            "{name}"
        );
        // an affine map scales every area alike
        assert!(m.area_distortion_log.mean_abs < 1e-12, "{name}");
        assert!(
            m.angle_distortion_deg.max > 1.0,
            "{name}: a shear changes angles"
        );
        assert_eq!(m.flipped_faces, 0);
    }
}

#[test]
fn mirrored_map_is_detected_and_scores_the_same() -> TestResult {
    let mesh = flat_disk(10, 6);
    // a holomorphic but non-affine map, so every metric is nonzero
    let map = planar_map(&mesh, |w| w + 0.3 * w * w + Complex64::new(0.1, 0.2));
    let mirrored: Vec<Complex64> = map.iter().map(|f| f.conj()).collect();
    let m = metrics(&mesh, &map);
    let r = metrics(&mesh, &mirrored);
    assert!(!m.orientation_reversed && r.orientation_reversed);
    assert!(m.conformal_energy > 1e-4 && m.angle_distortion_deg.mean > 0.1);
    let pairs = [
        (m.conformal_energy, r.conformal_energy),
        (m.dirichlet_energy, r.dirichlet_energy),
        (m.image_area, r.image_area),
        (m.angle_distortion_deg.mean, r.angle_distortion_deg.mean),
        (m.angle_distortion_deg.sd, r.angle_distortion_deg.sd),
        (m.angle_distortion_deg.max, r.angle_distortion_deg.max),
        (m.angle_distortion_deg.p95, r.angle_distortion_deg.p95),
        (m.beltrami_abs.mean, r.beltrami_abs.mean),
        (m.beltrami_abs.max, r.beltrami_abs.max),
        (
            m.area_distortion_log.mean_abs,
            r.area_distortion_log.mean_abs,
        ),
        (m.area_distortion_log.sd, r.area_distortion_log.sd),
        (m.circle_residual_max, r.circle_residual_max),
    ];
    for (k, (x, y)) in pairs.into_iter().enumerate() {
        assert_rel_near!(x, y, 1e-12, "metric #{k}");
    }
    assert_eq!((r.flipped_faces, r.degenerate_faces), (0, 0));
    assert_eq!(m.angle_histogram, r.angle_histogram);
    // the building blocks do not fix the orientation: a mirror costs E_D + |A|
    assert_rel_near!(image_area(&mesh, &mirrored)?, -m.image_area, 1e-13);
    assert_rel_near!(
        conformal_energy(&mesh, &mirrored)?,
        m.dirichlet_energy + m.image_area,
        1e-13
    );
    // nor does the metric when told not to: then every face is flipped
    let raw = planar_map_metrics(
        &mesh,
        &mirrored,
        &MetricsOptions::DEFAULT.with_fix_orientation(false),
    )?;
    assert!(!raw.orientation_reversed);
    assert_eq!(raw.flipped_faces, mesh.num_faces());
    assert_rel_near!(raw.image_area, -m.image_area, 1e-13);
    assert!(raw.beltrami_abs.mean > 1.0);
    Ok(())
}

/// A 4 × 4 grid whose corner vertex (1, 0) lies in exactly one face, that face, and the
/// other two corners of it.
fn grid_with_lonely_corner() -> (TriMesh, usize, [usize; 2]) {
    let mesh = square_grid(4, 4);
    let corner = 4; // (i, j) = (4, 0)
    let faces: Vec<_> = mesh
        .faces()
        .iter()
        .filter(|f| f.contains(&(corner as u32)))
        .collect();
    assert_eq!(faces.len(), 1);
    let others: Vec<usize> = faces[0]
        .iter()
        .filter(|&&v| v as usize != corner)
        .map(|&v| v as usize)
        .collect();
    (mesh, corner, [others[0], others[1]])
}

#[test]
fn one_folded_triangle_is_counted() {
    let (mesh, corner, [p, q]) = grid_with_lonely_corner();
    let mut map = planar_map(&mesh, |w| w);
    // reflect the corner across the line through the face's other two vertices
    let (a, b) = (map[p], map[q]);
    let d = (b - a) / (b - a).norm();
    let rel = (map[corner] - a) / d;
    map[corner] = a + rel.conj() * d;
    let m = metrics(&mesh, &map);
    assert_eq!(m.flipped_faces, 1);
    assert_eq!(m.degenerate_faces, 0);
    assert!(!m.orientation_reversed);
    assert!(m.beltrami_abs.max > 1.0, "a flipped face has |μ| > 1");
    assert!(m.conformal_energy > 0.0);
}

#[test]
fn collapsed_triangle_is_degenerate_and_the_report_stays_finite() -> TestResult {
    let (mesh, corner, [p, q]) = grid_with_lonely_corner();
    let mut map = planar_map(&mesh, |w| w);
    // the midpoint of two grid points with binary-exact coordinates: exactly collinear
    map[corner] = (map[p] + map[q]) * 0.5;
    let m = metrics(&mesh, &map);
    assert_eq!((m.degenerate_faces, m.flipped_faces), (1, 0));
    assert_eq!(m.measured_faces, mesh.num_faces() - 1);
    assert_eq!(
        m.angle_histogram.counts.iter().sum::<u64>(),
        3 * m.measured_faces as u64
    );
    // no NaN or infinity anywhere: serde_json would write them as null
    let json = serde_json::to_string(&m)?;
    assert!(!json.contains("null") || m.outer_loop.is_none(), "{json}");
    assert!(all_finite(&serde_json::to_value(&m)?));
    Ok(())
}

fn all_finite(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
        serde_json::Value::Array(a) => a.iter().all(all_finite),
        serde_json::Value::Object(o) => o.values().all(all_finite),
        serde_json::Value::Null => false,
        _ => true,
    }
}

#[test]
fn crowded_faces_are_not_degenerate() {
    // image areas around 1e-32 (a scaled copy) and 1e-23 (crowded next to 0.5, where the
    // coordinate differences keep only ~5 digits): what conformal maps do to thin limbs
    let mesh = flat_disk(6, 6);
    let m = metrics(&mesh, &planar_map(&mesh, |w| w * 1e-15));
    assert_eq!((m.degenerate_faces, m.flipped_faces), (0, 0));
    assert!(m.image_area > 0.0 && m.image_area < 1e-29);
    assert!(m.beltrami_abs.max < 1e-12);
    assert!(m.angle_distortion_deg.max < 1e-9);
    let m = metrics(&mesh, &planar_map(&mesh, |w| w * 1e-10 + 0.5));
    assert_eq!((m.degenerate_faces, m.flipped_faces), (0, 0));
    assert_rel_near!(m.image_area, 1e-20 * surface_area(&mesh), 1e-3);
    assert!(m.beltrami_abs.max < 1e-3);
}

#[test]
fn non_finite_and_malformed_maps_are_errors() {
    let mesh = flat_disk(4, 6);
    let mut map = planar_map(&mesh, |w| w);
    map[17] = Complex64::new(0.1, f64::NAN);
    let err = planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT).err();
    assert!(matches!(
        err,
        Some(MetricsError::NonFiniteValue { vertex: 17, .. })
    ));
    assert!(err.is_some_and(|e| e.to_string().contains("vertex 17")));
    assert!(matches!(
        dirichlet_energy(&mesh, &map),
        Err(MetricsError::NonFiniteValue { vertex: 17, .. })
    ));

    map[17] = Complex64::new(f64::INFINITY, 0.0);
    assert!(matches!(
        conformal_energy(&mesh, &map),
        Err(MetricsError::NonFiniteValue { vertex: 17, .. })
    ));
    map[17] = Complex64::new(0.0, 2.0 * MAP_ABS_LIMIT);
    assert!(matches!(
        image_area(&mesh, &map),
        Err(MetricsError::ValueTooLarge { vertex: 17, .. })
    ));
    assert!(matches!(
        planar_map_metrics(&mesh, &map[1..], &MetricsOptions::DEFAULT),
        Err(MetricsError::LengthMismatch {
            map_len: 60,
            vertices: 61
        })
    ));
    map[17] = Complex64::new(0.0, 0.0);
    assert!(matches!(
        planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT.with_outer_loop(1)),
        Err(MetricsError::OuterLoopOutOfRange { index: 1, loops: 1 })
    ));
}

#[test]
fn unit_disk_boundary_is_on_the_circle() {
    let mesh = flat_disk(16, 6);
    let m = metrics(&mesh, &planar_map(&mesh, |w| w));
    assert!(m.circle_residual_max < 1e-15, "{:e}", m.circle_residual_max);
    assert_eq!(m.outer_loop, Some(0));
    assert_eq!(m.boundary_circles.len(), 1);
    let c = m.boundary_circles[0];
    assert!(c.outer && c.vertices == 96 && c.center == [0.0, 0.0] && c.radius == 1.0);
    // a rotation keeps it there; a scaled map is off by the scale
    let m = metrics(
        &mesh,
        &planar_map(&mesh, |w| w * Complex64::from_polar(1.0, 0.7)),
    );
    assert!(m.circle_residual_max < 1e-15);
    let m = metrics(&mesh, &planar_map(&mesh, |w| w * 0.9));
    assert_near!(m.circle_residual_max, 0.1, 1e-15);
}

#[test]
fn hole_circle_is_recovered() {
    let (c, r) = (Complex64::new(0.2, 0.1), 0.3);
    let mesh = disk_with_holes(&[Circle::new(c.re, c.im, r)], 0.07);
    let m = metrics(&mesh, &planar_map(&mesh, |w| w));
    let outer = m.outer_loop.unwrap_or(usize::MAX);
    let hole = m.boundary_circles.iter().find(|l| !l.outer);
    let Some(hole) = hole else {
        panic!("no hole circle in {:?}", m.boundary_circles)
    };
    assert_eq!(m.boundary_circles[outer].vertices, 90);
    assert_near!(hole.center[0], c.re, 1e-12);
    assert_near!(hole.center[1], c.im, 1e-12);
    assert_near!(hole.radius, r, 1e-12);
    assert!(hole.residual_max < 1e-12);
    assert!(m.circle_residual_max < 1e-12);
    assert_perfect(&m, "identity of the disk with a hole");
}

#[test]
fn outer_loop_can_be_chosen_and_best_fit() -> TestResult {
    // both loops of an annulus have 32 vertices; loop 0 (the inner circle, vertex 0) wins ties
    let mesh = annulus(0.4, 1.0, 5, 32);
    let map = planar_map(&mesh, |w| w);
    let m = metrics(&mesh, &map);
    assert_eq!(m.outer_loop, Some(0));
    assert_near!(m.circle_residual_max, 0.6, 1e-15);
    let options = MetricsOptions::DEFAULT.with_outer_loop(1);
    let m = planar_map_metrics(&mesh, &map, &options)?;
    assert_eq!(m.outer_loop, Some(1));
    assert!(m.circle_residual_max < 1e-14);
    assert_near!(m.boundary_circles[0].radius, 0.4, 1e-14);
    // a disk map of another tool, normalized to the disk of radius ½ around ½ + ½i
    let moved: Vec<Complex64> = map
        .iter()
        .map(|f| f * 0.5 + Complex64::new(0.5, 0.5))
        .collect();
    let options = options.with_outer_circle(OuterCircle::BestFit);
    let m = planar_map_metrics(&mesh, &moved, &options)?;
    assert!(m.circle_residual_max < 1e-13);
    let outer = m.boundary_circles[1];
    assert_near!(outer.center[0], 0.5, 1e-14);
    assert_near!(outer.radius, 0.5, 1e-14);
    // the annulus is its own conformal map
    assert!(m.conformal_energy.abs() < 1e-13 * m.image_area);
    Ok(())
}

/// Deterministic, bounded, non-holomorphic test map of a mesh with coordinates `scale` wide.
fn wobbly_map(mesh: &TriMesh) -> Vec<Complex64> {
    let scale = mesh.bbox_diagonal();
    mesh.positions()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let w = Complex64::new(p[0], p[1] + 0.5 * p[2]) / scale;
            let jitter = Complex64::new((i as f64 * 12.9898).sin(), (i as f64 * 78.233).cos());
            w + 0.3 * w * w + 0.1 * w.conj() + 0.01 * jitter
        })
        .collect()
}

#[test]
fn dirichlet_energy_equals_the_laplacian_quadratic_form() -> TestResult {
    let mut meshes = vec![
        ("icosphere", icosphere(1.0, 3)),
        ("annulus", annulus(0.3, 1.0, 6, 30)),
    ];
    meshes.extend(
        woody("dirichlet_energy_equals_the_laplacian_quadratic_form").map(|m| ("woody", m)),
    );
    // a curved, badly non-Delaunay disk (14% negative cotangent weights), if present
    if let Some(path) = real_mesh_or_skip(
        "camelhead.obj",
        "dirichlet_energy_equals_the_laplacian_quadratic_form",
    ) {
        meshes.push(("camelhead", read_plain_obj(&path)?));
    }
    for (name, mesh) in &meshes {
        let map = wobbly_map(mesh);
        let per_face = dirichlet_energy(mesh, &map)?;
        let assembled = quadratic_form(&cotan_laplacian(mesh), &map);
        assert_rel_near!(per_face, assembled, 1e-12, "{name}");
        assert!(per_face > 0.0);
    }
    Ok(())
}

#[test]
fn boundary_area_equals_the_sum_of_face_areas() -> TestResult {
    let Some(mesh) = woody("boundary_area_equals_the_sum_of_face_areas") else {
        return Ok(());
    };
    let map = wobbly_map(&mesh);
    let faces: f64 = mesh
        .faces()
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| map[v as usize]);
            0.5 * ((b - a).conj() * (c - a)).im
        })
        .sum();
    assert_rel_near!(image_area(&mesh, &map)?, faces, 1e-12);
    Ok(())
}

#[test]
fn angle_statistics_match_a_direct_computation() -> TestResult {
    let mesh = match woody("angle_statistics_match_a_direct_computation") {
        Some(m) => m,
        None => flat_disk(10, 6),
    };
    let map = wobbly_map(&mesh);
    let m = planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT)?;
    assert_eq!(m.degenerate_faces, 0);
    // independent: acos of normalized dot products, full sort
    let mut d: Vec<f64> = Vec::new();
    for (f, mesh_angles) in mesh.faces().iter().zip(corner_angles(&mesh)) {
        let g = f.map(|v| map[v as usize]);
        for k in 0..3 {
            let (u, v) = (g[(k + 1) % 3] - g[k], g[(k + 2) % 3] - g[k]);
            let cos = (u.conj() * v).re / (u.norm() * v.norm());
            d.push(
                (mesh_angles[k] - cos.clamp(-1.0, 1.0).acos())
                    .abs()
                    .to_degrees(),
            );
        }
    }
    d.sort_by(f64::total_cmp);
    let n = d.len();
    let mean = d.iter().sum::<f64>() / n as f64;
    let sd = (d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let p95 = d[(0.95 * n as f64).ceil() as usize - 1];
    assert_rel_near!(m.angle_distortion_deg.mean, mean, 1e-9);
    assert_rel_near!(m.angle_distortion_deg.sd, sd, 1e-9);
    assert_rel_near!(m.angle_distortion_deg.max, d[n - 1], 1e-9);
    assert_rel_near!(m.angle_distortion_deg.p95, p95, 1e-9);
    // histogram against the edges
    for (k, &count) in m.angle_histogram.counts.iter().enumerate() {
        let (lo, hi) = (
            ANGLE_HISTOGRAM_EDGES_DEG[k],
            ANGLE_HISTOGRAM_EDGES_DEG[k + 1],
        );
        let expected = d
            .iter()
            .filter(|&&x| x >= lo && (x < hi || k == 12))
            .count();
        assert!(
            count.abs_diff(expected as u64) <= 1,
            "bin {k}: {count} vs {expected}"
        );
    }
    assert_eq!(m.angle_histogram.counts.iter().sum::<u64>(), n as u64);
    Ok(())
}

#[test]
fn closed_mesh_uses_face_areas_and_has_no_circles() -> TestResult {
    let mesh = icosphere(1.0, 2);
    // projection to the xy-plane: the upper and lower halves cancel
    let map: Vec<Complex64> = mesh.positions().iter().map(z).collect();
    let m = planar_map_metrics(&mesh, &map, &MetricsOptions::DEFAULT)?;
    assert!(m.image_area.abs() < 1e-14);
    assert!(m.boundary_circles.is_empty() && m.outer_loop.is_none());
    assert_eq!(m.circle_residual_max, 0.0);
    assert!(m.flipped_faces > 0 && m.flipped_faces < mesh.num_faces());
    Ok(())
}

#[test]
fn report_has_the_schema_field_names() -> TestResult {
    let mesh = flat_disk(3, 6);
    let v = serde_json::to_value(metrics(&mesh, &planar_map(&mesh, |w| w)))?;
    for key in [
        "conformal_energy",
        "dirichlet_energy",
        "image_area",
        "angle_distortion_deg",
        "beltrami_abs",
        "area_distortion_log",
        "flipped_faces",
        "degenerate_faces",
        "circle_residual_max",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    for key in ["mean", "sd", "max", "p95"] {
        assert!(v["angle_distortion_deg"].get(key).is_some(), "angle {key}");
    }
    for key in ["mean", "sd", "max"] {
        assert!(v["beltrami_abs"].get(key).is_some(), "beltrami {key}");
    }
    for key in ["mean_abs", "sd"] {
        assert!(v["area_distortion_log"].get(key).is_some(), "area {key}");
    }
    assert_eq!(
        v["angle_histogram"]["edges_deg"].as_array().map(Vec::len),
        Some(14)
    );
    Ok(())
}
