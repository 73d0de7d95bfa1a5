//! Tests of the global map on tori of revolution (analytic modulus) and the small
//! higher-genus fixtures.

use conformap_mesh::TriMesh;
use conformap_testkit::{fixture_path, jittered_torus, read_plain_obj};
use num_complex::Complex64;

use crate::{global_map, ConjugateMethod, GlobalMap, GlobalMapOptions};

/// The reduced modulus of a torus of revolution: `i · max(q, 1/q)`, `q = r/√(R² − r²)`.
fn analytic_tau(major: f64, minor: f64) -> f64 {
    let q = minor / (major * major - minor * minor).sqrt();
    q.max(1.0 / q)
}

fn tau_error(map: &GlobalMap, major: f64, minor: f64) -> f64 {
    let tau = map.tau.expect("genus 1");
    (tau - Complex64::new(0.0, analytic_tau(major, minor))).norm() / analytic_tau(major, minor)
}

/// The invariants every map must satisfy.
fn check_invariants(map: &GlobalMap) {
    assert!(map.seam_residual < 1e-9, "seam {:e}", map.seam_residual);
    assert_eq!(
        map.zeros.multiplicity_sum,
        2 * map.surface_genus as i64 - 2,
        "{:?}",
        map.zeros.zeros
    );
    assert_eq!(map.zeros.negative_clusters, 0);
    assert_eq!(map.zeros.folds_outside_zeros, 0);
    assert!(map.zeros.winding_residual < 1e-9);
    assert!(map.harmonic_residual < 1e-8, "{:e}", map.harmonic_residual);
    assert!(map.closedness_residual < 1e-9);
    assert!(
        (map.metrics.image_area - map.metrics.surface_area).abs() < 1e-9 * map.metrics.surface_area
            || map.double_covered
    );
}

#[test]
fn torus_modulus_within_half_a_percent_at_10k_faces() {
    for (major, minor, nm, nn) in [(3.0, 1.0, 122, 41), (2.0, 1.0, 100, 50)] {
        let mesh = jittered_torus(major, minor, nm, nn, 0.2, 11);
        assert!((9900..=10100).contains(&mesh.num_faces()));
        let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
        check_invariants(&map);
        let err = tau_error(&map, major, minor);
        assert!(
            err < 5e-3,
            "R={major} r={minor}: τ = {:?}, error {err:e}",
            map.tau
        );
        // genus 1: no zeros, no folds
        assert!(map.zeros.zeros.is_empty());
        assert_eq!(map.zeros.folded_faces, 0);
        assert!(map.metrics.angle_distortion_deg.mean < 1.5);
    }
}

#[test]
fn torus_modulus_converges_at_second_order() {
    let (major, minor) = (3.0, 1.0);
    let errs: Vec<f64> = [(30usize, 10usize), (60, 20), (120, 40)]
        .iter()
        .map(|&(nm, nn)| {
            let mesh = jittered_torus(major, minor, nm, nn, 0.0, 0);
            let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
            tau_error(&map, major, minor)
        })
        .collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(order > 1.8, "errors {errs:?}: order {order}");
    }
}

#[test]
fn both_conjugates_converge_and_exact_one_is_one_answer() {
    let (major, minor) = (2.0, 1.0);
    let mesh = jittered_torus(major, minor, 60, 30, 0.2, 3);
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    assert!(map.bilinear_residual < 1e-12, "{:e}", map.bilinear_residual);
    assert!(map.bilinear_residual_gu_yau > map.bilinear_residual);
    assert!(map.complex_structure_defect < 1e-2);
    assert_eq!(map.tau_gu_yau.len(), 2);
    let exact = analytic_tau(major, minor);
    for t in &map.tau_gu_yau {
        assert!((t.im - exact).abs() / exact < 2e-2, "{t}");
    }
    // the plain solve lays out a valid map too
    let plain = global_map(
        &mesh,
        &GlobalMapOptions::DEFAULT.with_conjugate(ConjugateMethod::GuYau),
    )
    .expect("map");
    check_invariants(&plain);
}

#[test]
fn eightsim_genus_two_has_two_zeros_worth_of_multiplicity() {
    let mesh = read_plain_obj(&fixture_path("eightsim.obj")).expect("fixture");
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    assert_eq!(map.surface_genus, 2);
    check_invariants(&map);
    // every basis form, laid out, is a valid map
    for k in 0..4 {
        let m = global_map(&mesh, &GlobalMapOptions::DEFAULT.with_form(Some(k))).expect("map");
        check_invariants(&m);
    }
    // the default form is the most uniform basis form
    let best = map
        .form_uniformity
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    assert_eq!(map.form_uniformity[map.form_index], best);
}

#[test]
fn punctured_torus_through_its_double_cover() {
    let mesh = read_plain_obj(&fixture_path("punctured_torus.obj")).expect("fixture");
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    assert!(map.double_covered);
    assert_eq!(map.surface_genus, 2); // 2g + b − 1
    check_invariants(&map);
}

#[test]
fn halftunnel_three_boundaries_double_cover_genus_two() {
    let mesh = read_plain_obj(&fixture_path("halftunnel.obj")).expect("fixture");
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    assert_eq!(map.surface_genus, 2); // 0 + 3 − 1
    check_invariants(&map);
}

#[test]
fn genus_zero_is_refused_naming_the_command() {
    let sphere = conformap_testkit::icosphere(1.0, 1);
    let err = global_map(&sphere, &GlobalMapOptions::DEFAULT).expect_err("genus 0");
    assert!(err.to_string().contains("conformap sphere"), "{err}");
    let mesh: TriMesh = conformap_mesh::doc_torus();
    let err = global_map(&mesh, &GlobalMapOptions::DEFAULT.with_form(Some(2))).expect_err("k");
    assert!(err.to_string().contains("form"));
}

/// The sparse cohomology basis (closed on every face, dual to the generators), and its
/// wedge and Gram matrices against the pairwise face and edge sums of the harmonic forms
/// they stand for, on `mesh` (closed) or its double covering (`mirror`).
fn check_sparse_products(mesh: &TriMesh, mirror: Option<(Vec<u32>, usize)>) {
    use crate::forms::cohomology::{
        cohomology_basis, edge_weights, inner_product, wedge, wedge_matrix,
    };
    use crate::forms::conjugate::gram_matrix;
    use crate::forms::harmonic::{storage, HarmonicFactor};
    use conformap_operators::CholeskyOptions;
    let basis = conformap_mesh::homology_basis(mesh, None).expect("basis");
    let (closed, root_residual) = cohomology_basis(mesh, &basis);
    assert_eq!(root_residual, 0.0);
    let edges = &basis.edges;
    for (i, form) in closed.iter().enumerate() {
        // a small part of the edges, in edge order, no zero stored
        assert!(
            form.len() < edges.len() / 4,
            "form {i}: {} values",
            form.len()
        );
        assert!(form.windows(2).all(|p| p[0].0 < p[1].0), "form {i}");
        assert!(form.iter().all(|&(_, x)| x != 0.0), "form {i}");
        let mut w = vec![0.0; edges.len()];
        for &(e, x) in form {
            w[e as usize] = x;
        }
        // closed on every face, exactly (integer values)
        for f in 0..mesh.num_faces() {
            let d: f64 = (3 * f..3 * f + 3).map(|h| edges.on_halfedge(&w, h)).sum();
            assert_eq!(d, 0.0, "form {i}, face {f}");
        }
        // dual to the generators: ∫ ω_i over loop j is δ_ij
        for (j, g) in basis.generators.iter().enumerate() {
            let p: f64 = g
                .halfedges
                .iter()
                .map(|&h| edges.on_halfedge(&w, h as usize))
                .sum();
            assert_eq!(p, f64::from(u8::from(i == j)), "form {i}, loop {j}");
        }
    }
    let w = wedge_matrix(mesh, edges, &closed);
    let weights = edge_weights(mesh, &basis);
    let options = CholeskyOptions::default();
    let factor = match &mirror {
        Some((m, copy)) => HarmonicFactor::mirrored(mesh, m, *copy, &options, None),
        None => HarmonicFactor::new(mesh, basis.root, &options),
    }
    .expect("factor");
    let store = storage(closed.len(), edges.len());
    let projected = factor
        .project(mesh, &basis, &weights, &closed, store)
        .expect("project");
    // coclosed on the whole surface (for a covering: from the two half-size solves)
    let residual = projected.codifferential_residual;
    assert!(residual < 1e-10, "{residual:e}");
    let h = projected.forms;
    let g = gram_matrix(&weights, &closed, &h);
    let n = h.len();
    let scale = (0..n).map(|i| g[i * n + i]).fold(0.0f64, f64::max);
    for i in 0..n {
        for j in 0..n {
            let ww = wedge(&basis, 0..mesh.num_faces(), &h[i], &h[j]);
            let gg = inner_product(&weights, &h[i], &h[j]);
            // the wedge of the basis is the intersection form: integers, exactly
            assert_eq!(w[i * n + j], w[i * n + j].round(), "W[{i},{j}]");
            assert!(
                (w[i * n + j] - ww).abs() < 1e-10,
                "W[{i},{j}] {} vs {ww}",
                w[i * n + j]
            );
            assert!(
                (g[i * n + j] - gg).abs() < 1e-10 * scale,
                "H[{i},{j}] {} vs {gg}",
                g[i * n + j]
            );
        }
    }
}

#[test]
fn sparse_wedge_and_gram_match_the_harmonic_forms_pairwise_sums() {
    let eightsim = read_plain_obj(&fixture_path("eightsim.obj")).expect("eightsim");
    check_sparse_products(&eightsim, None);
    let halftunnel = read_plain_obj(&fixture_path("halftunnel.obj")).expect("halftunnel");
    let dc = conformap_sphere::double_cover_surface(&halftunnel).expect("covering");
    check_sparse_products(&dc.mesh, Some((dc.mirror, dc.split_vertices)));
}
