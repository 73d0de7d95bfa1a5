//! Tests of the optimal form on the small fixtures: derivatives against finite
//! differences, the multistart against the basis forms and dense sampling, the
//! eigenproblems against brute force, zero allocation by edge rings.

use conformap_mesh::TriMesh;
use conformap_testkit::{fixture_path, read_plain_obj};
use num_complex::Complex64;

use super::moments::Moments;
use super::products::{area_products, quadratic};
use super::search::random_directions;
use super::uniform::{energy, evaluate};
use super::Objective;
use crate::{global_map, GlobalMap, GlobalMapOptions};

fn eightsim() -> TriMesh {
    read_plain_obj(&fixture_path("eightsim.obj")).expect("eightsim fixture")
}

/// Signed layout areas of the input's faces for coefficients `lambda`, straight from the
/// basis forms' edge values (independent of the whitened products).
pub(crate) fn direct_areas(map: &GlobalMap, lambda: &[f64]) -> Vec<f64> {
    let forms = map.basis_forms();
    let val = |h: usize| -> Complex64 {
        let e = map.edges.edge_of[h] as usize;
        let s = map.edges.sign(h);
        forms
            .iter()
            .zip(lambda)
            .map(|(phi, l)| phi[e] * (s * l))
            .sum()
    };
    (0..map.input_faces)
        .map(|f| 0.5 * (val(3 * f).conj() * -val(3 * f + 2)).im)
        .collect()
}

pub(crate) fn direct_energy(map: &GlobalMap, s_share: &[f64], lambda: &[f64]) -> f64 {
    let a = direct_areas(map, lambda);
    let total: f64 = a.iter().sum();
    a.iter()
        .zip(s_share)
        .map(|(x, s)| (x / total - s).powi(2))
        .sum()
}

pub(crate) fn surface_shares(map: &GlobalMap) -> Vec<f64> {
    let s = conformap_operators::face_areas(&map.surface);
    let total: f64 = s[..map.input_faces].iter().sum();
    s[..map.input_faces].iter().map(|x| x / total).collect()
}

/// `(min, max)` of the direct uniformity energy over `count` seeded random unit
/// coefficient vectors (the independent sampling the optimum is checked against).
pub(crate) fn sampled_energy_range(
    map: &GlobalMap,
    s_share: &[f64],
    count: usize,
    seed: u64,
) -> (f64, f64) {
    random_directions(map.objective.coefficients.len(), count, seed)
        .into_iter()
        .map(|d| direct_energy(map, s_share, &unit(d)))
        .fold((f64::INFINITY, 0.0f64), |(l, h), x| (l.min(x), h.max(x)))
}

pub(crate) fn unit(v: Vec<f64>) -> Vec<f64> {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.into_iter().map(|x| x / n).collect()
}

#[test]
fn gradient_and_hessian_match_finite_differences() {
    let map = global_map(&eightsim(), &GlobalMapOptions::DEFAULT).expect("map");
    let p = area_products(
        &map.surface,
        &map.edges,
        &map.basis_forms(),
        map.input_faces,
    )
    .unwrap();
    let n = p.n;
    let moments = Moments::new(&p);
    for dir in random_directions(n, 3, 7) {
        let mu = unit(dir);
        let ev = evaluate(&moments, &mu);
        assert!((moments.energy(&mu) - energy(&p, &mu)).abs() < 1e-15);
        assert!((ev.energy - energy(&p, &mu)).abs() < 1e-15);
        let h = 1e-6;
        for i in 0..n {
            let (mut up, mut dn) = (mu.clone(), mu.clone());
            up[i] += h;
            dn[i] -= h;
            let fd = (energy(&p, &up) - energy(&p, &dn)) / (2.0 * h);
            assert!(
                (fd - ev.gradient[i]).abs()
                    < 1e-6 * ev.gradient.iter().map(|x| x.abs()).sum::<f64>(),
                "∂{i}: fd {fd:e} analytic {:e}",
                ev.gradient[i]
            );
            // Hessian column i by differences of the gradient (evaluate wants |μ| = 1, so
            // difference the homogeneous extension: ∇E(tμ) = ∇E(μ)/t)
            let (nu, nd) = (unit(up.clone()), unit(dn.clone()));
            let (lu, ld) = (
                up.iter().map(|x| x * x).sum::<f64>().sqrt(),
                dn.iter().map(|x| x * x).sum::<f64>().sqrt(),
            );
            let (gu, gd) = (
                evaluate(&moments, &nu).gradient,
                evaluate(&moments, &nd).gradient,
            );
            let scale: f64 = ev.hessian.iter().map(|x| x.abs()).fold(0.0, f64::max);
            for j in 0..n {
                let fd = (gu[j] / lu - gd[j] / ld) / (2.0 * h);
                assert!(
                    (fd - ev.hessian[j * n + i]).abs() < 1e-5 * scale,
                    "H[{j},{i}]: fd {fd:e} analytic {:e}",
                    ev.hessian[j * n + i]
                );
            }
        }
    }
    // the whitening: the total area form is the identity
    let c = p.sum_over(0..p.faces());
    for i in 0..n {
        for j in 0..n {
            let want = if i == j { 1.0 } else { 0.0 };
            assert!((c[i * n + j] - want).abs() < 1e-12);
        }
    }
    let mu = unit(vec![1.0, -2.0, 0.5, 3.0]);
    assert!((quadratic(&c, &mu) - 1.0).abs() < 1e-12);
}

/// Samples of the Euclidean unit sphere of the basis coefficients.
const SAMPLES: usize = 5000;

#[test]
fn uniform_optimum_beats_basis_forms_and_dense_sampling_on_eightsim() {
    let mesh = eightsim();
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    let least = global_map(
        &mesh,
        &GlobalMapOptions::DEFAULT.with_objective(Objective::LeastUniform),
    )
    .expect("map");
    let s = surface_shares(&map);
    let o = &map.objective;
    let search = o.search.as_ref().expect("genus 2: a search");
    // the reported energy is the laid-out form's (measured on the layout) and the direct one
    assert!((o.uniformity - map.metrics.uniformity_energy).abs() < 1e-9 * o.uniformity);
    assert!((direct_energy(&map, &s, &o.coefficients) - o.uniformity).abs() < 1e-12);
    assert!((search.energy - o.uniformity).abs() < 1e-12);
    for (k, &e) in o.basis_uniformity.iter().enumerate() {
        assert!(
            o.uniformity <= e,
            "basis form {k}: {e:e} < {:e}",
            o.uniformity
        );
    }
    let (lo, hi) = sampled_energy_range(&map, &s, SAMPLES, 99);
    assert!(
        o.uniformity <= lo,
        "sample {lo:e} < optimum {:e}",
        o.uniformity
    );
    let lo_o = &least.objective;
    assert!(
        lo_o.uniformity >= hi,
        "sample {hi:e} > least uniform {:e}",
        lo_o.uniformity
    );
    // both runs compare the extremes and agree on them
    let ratio = o.max_min_ratio.unwrap();
    assert!((ratio - lo_o.max_min_ratio.unwrap()).abs() < 1e-9 * ratio);
    assert!(ratio > 1.0);
    assert_eq!(search.unconverged, 0, "{search:?}");
    assert!(search.reached_best >= 2, "{search:?}");
    eprintln!(
        "eightsim: E uniform {:.6e} (basis best {:.6e}, samples {lo:.6e}..{hi:.6e}), least {:.6e}, \
         ratio {ratio:.3}; starts {}, reached best {}, optima {:?} counts {:?}, iterations {} \
         (max {}), {:.1} ms",
        o.uniformity,
        o.basis_uniformity.iter().cloned().fold(f64::INFINITY, f64::min),
        lo_o.uniformity,
        search.starts,
        search.reached_best,
        search.local_optima,
        search.local_optimum_counts,
        search.iterations_total,
        search.iterations_max,
        search.time_ms
    );
}

/// The faces whose centroid lies below the area centroid along the longest bounding-box
/// axis: "half of the surface split by a plane through the area centroid".
pub(crate) fn half_region(mesh: &TriMesh, faces: usize) -> Vec<usize> {
    let pos = mesh.positions();
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in pos {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let axis = (0..3)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let areas = conformap_operators::face_areas(mesh);
    let centroid = |f: usize| {
        let t = mesh.faces()[f];
        t.iter().map(|&v| pos[v as usize][axis]).sum::<f64>() / 3.0
    };
    let total: f64 = areas[..faces].iter().sum();
    let c = (0..faces).map(|f| areas[f] * centroid(f)).sum::<f64>() / total;
    (0..faces).filter(|&f| centroid(f) < c).collect()
}

fn direct_share(map: &GlobalMap, region: &[bool], lambda: &[f64]) -> f64 {
    let a = direct_areas(map, lambda);
    let total: f64 = a.iter().sum();
    a.iter()
        .zip(region)
        .filter(|(_, &r)| r)
        .map(|(x, _)| x)
        .sum::<f64>()
        / total
}

/// Compass search on the unit sphere of `λ` from `start`: steps along ± each axis, halved
/// when none improves, down to `1e-9`.
fn compass_max(f: impl Fn(&[f64]) -> f64, start: &[f64]) -> f64 {
    let n = start.len();
    let mut x = unit(start.to_vec());
    let mut best = f(&x);
    let mut step = 0.1;
    while step > 1e-9 {
        let mut improved = false;
        for i in 0..n {
            for sgn in [1.0, -1.0] {
                let mut y = x.clone();
                y[i] += sgn * step;
                let y = unit(y);
                let v = f(&y);
                if v > best {
                    best = v;
                    x = y;
                    improved = true;
                }
            }
        }
        if !improved {
            step *= 0.5;
        }
    }
    best
}

#[test]
fn emphasized_half_matches_sampling_and_brute_force_on_eightsim() {
    let mesh = eightsim();
    let half = half_region(&mesh, mesh.num_faces());
    let mask = conformap_sphere::region_mask(mesh.num_faces(), &half).unwrap();
    for maximize in [true, false] {
        let objective = Objective::Emphasize {
            faces: half.clone(),
            maximize,
        };
        let map =
            global_map(&mesh, &GlobalMapOptions::DEFAULT.with_objective(objective)).expect("map");
        let em = map.objective.emphasis.clone().expect("emphasis");
        let sign = if maximize { 1.0 } else { -1.0 };
        // the chosen form's share, measured on its layout
        let uv = map.input_corner_uv();
        let la = crate::forms::quality::layout_areas(uv, map.input_faces);
        let layout_share = la
            .iter()
            .zip(&mask)
            .filter(|(_, &r)| r)
            .map(|(x, _)| x)
            .sum::<f64>()
            / la.iter().sum::<f64>();
        assert!(
            (layout_share - em.share).abs() < 1e-9,
            "{layout_share} vs {}",
            em.share
        );
        let samples: Vec<(f64, Vec<f64>)> = random_directions(4, SAMPLES, 5)
            .into_iter()
            .map(|d| {
                let l = unit(d);
                (direct_share(&map, &mask, &l), l)
            })
            .collect();
        let best = samples
            .iter()
            .max_by(|a, b| (sign * a.0).total_cmp(&(sign * b.0)))
            .unwrap();
        assert!(sign * best.0 <= sign * em.share + 1e-12);
        let brute = sign * compass_max(|l| sign * direct_share(&map, &mask, l), &best.1);
        assert!(
            (brute - em.share).abs() < 1e-9,
            "brute {brute} eigen {}",
            em.share
        );
        eprintln!(
            "eightsim half ({} faces, {:.4} of the area): {} share {:.6} (max {:.6}, min {:.6}), \
             best sample {:.6}, brute force {:.12} vs {:.12}",
            em.region_faces,
            em.surface_share,
            if maximize { "max" } else { "min" },
            em.share,
            em.share_max,
            em.share_min,
            best.0,
            brute,
            em.share
        );
    }
}

#[test]
fn zero_allocation_lands_within_two_rings_on_eightsim() {
    let mesh = eightsim();
    for target in [10usize, 60, 120, 170] {
        let map = global_map(
            &mesh,
            &GlobalMapOptions::DEFAULT.with_objective(Objective::Zeros {
                vertices: vec![target],
            }),
        )
        .expect("map");
        let z = map.objective.zeros.as_ref().expect("zeros");
        assert!(z.exact_expected);
        let t = &z.targets[0];
        eprintln!(
            "eightsim target {target}: ring distance {:?} to zero {:?}, |ω| {:.3e} (median {:.3})",
            t.ring_distance, t.nearest_zero, t.residual, z.median_stretch
        );
        assert!(t.ring_distance.unwrap() <= 2, "{t:?}");
        assert!(t.residual < 0.2 * z.median_stretch, "{t:?}");
        assert_eq!(map.zeros.multiplicity_sum, 2);
    }
}

#[test]
fn genus_one_has_nothing_to_choose() {
    let torus = conformap_mesh::doc_torus();
    let map = global_map(&torus, &GlobalMapOptions::DEFAULT).expect("map");
    let o = &map.objective;
    assert!(o.search.is_none());
    assert_eq!(o.max_min_ratio, Some(1.0));
    let e = &o.basis_uniformity;
    assert!((e[0] - e[1]).abs() < 1e-9 * e[0], "{e:?}");
    let zeros = global_map(
        &torus,
        &GlobalMapOptions::DEFAULT.with_objective(Objective::Zeros { vertices: vec![0] }),
    );
    assert!(matches!(
        zeros,
        Err(crate::GlobalError::InvalidOption { .. })
    ));
}

#[test]
fn surfaces_with_boundary_are_optimized_on_the_users_copy() {
    let mesh = read_plain_obj(&fixture_path("halftunnel.obj")).expect("fixture");
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    assert!(map.double_covered);
    let o = &map.objective;
    // the energy the search minimized is the one measured on the user's copy of the layout
    assert!((o.uniformity - map.metrics.uniformity_energy).abs() < 1e-9 * o.uniformity);
    for &e in &o.basis_uniformity {
        assert!(o.uniformity <= e);
    }
    let bad = global_map(
        &mesh,
        &GlobalMapOptions::DEFAULT.with_objective(Objective::Zeros {
            vertices: vec![mesh.num_vertices()],
        }),
    );
    assert!(matches!(
        bad,
        Err(crate::GlobalError::ZeroTargetOutOfRange { .. })
    ));
}

#[test]
fn vertex_values_fit_holomorphic_forms_and_vanish_at_exact_targets() {
    let mesh = eightsim();
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    let forms = map.basis_forms();
    let p = area_products(&map.surface, &map.edges, &forms, map.input_faces).unwrap();
    // the fit φ(e) ≈ c·ẽ of the chosen (uniform) form explains most of the star's values at
    // a vertex away from zeros (it would explain none with the frame's orientation flipped)
    let mu = p.whiten(&map.objective.coefficients);
    let v = 5;
    let c = super::targets::vertex_values(&map.surface, &map.edges, &forms, &p, v);
    let cv: Complex64 = c.iter().zip(&mu).map(|(c, m)| c * m).sum();
    let (mut phi2, mut len2) = (0.0, 0.0);
    for (e, &h) in map.edges.halfedge.iter().enumerate() {
        let (a, b) = map.surface.halfedge_vertices(h as usize);
        if a as usize == v || b as usize == v {
            let (pa, pb) = (
                map.surface.positions()[a as usize],
                map.surface.positions()[b as usize],
            );
            len2 += (0..3).map(|i| (pa[i] - pb[i]).powi(2)).sum::<f64>();
            let z: Complex64 = p
                .whitened_edge(&forms, e)
                .iter()
                .zip(&mu)
                .map(|(z, m)| z * m)
                .sum();
            phi2 += z.norm_sqr();
        }
    }
    let explained = cv.norm_sqr() * len2 / phi2;
    assert!(
        explained > 0.8,
        "the fit explains {explained:.3} of the star's |φ|²"
    );
    let targets = [10usize, 120];
    let m = super::targets::condition_gram(&map.surface, &map.edges, &forms, &p, &targets[..1]);
    let basis = super::targets::null_space(&m, p.n, p.n - 2);
    for col in 0..p.n - 2 {
        let nu: Vec<f64> = (0..p.n - 2)
            .map(|k| if k == col { 1.0 } else { 0.0 })
            .collect();
        let mu = super::targets::lift(&basis, &nu, p.n);
        // in the null space of the conditions, against their scale (the trace)
        let trace: f64 = (0..p.n).map(|i| m[i * p.n + i]).sum();
        assert!(quadratic(&m, &mu) <= 1e-12 * trace);
        assert!((mu.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
    }
    let zeros = global_map(
        &mesh,
        &GlobalMapOptions::DEFAULT.with_objective(Objective::Zeros {
            vertices: vec![targets[0]],
        }),
    )
    .expect("map");
    let z = zeros.objective.zeros.as_ref().expect("zeros");
    assert_eq!(z.method, "exact");
    // Σ|ω(v_i)|² per unit area at rounding level, against ~|ω|² ≈ 1/area elsewhere
    // (measured 4.7e-19 with the whitening by matrix products, 1e-20 before: both 1e-16
    // of the median |ω|² ≈ 0.3)
    assert!(z.eigenvalue < 1e-16, "{z:?}");
    assert!(zeros.objective.search.is_some());
}

#[test]
fn direct_face_sums_match_the_moments_and_reach_the_same_optimum() {
    use super::faces::{use_moments, FaceForms};
    use super::products::AreaProducts;
    use super::search::{multistart, FormSearchOptions};
    let map = global_map(&eightsim(), &GlobalMapOptions::DEFAULT).expect("map");
    let ff = FaceForms::new(
        &map.surface,
        &map.edges,
        &map.basis_forms(),
        map.input_faces,
    )
    .unwrap();
    let n = ff.n;
    let moments = Moments::from_faces(&ff);
    let p = AreaProducts::from_faces(&ff);
    for dir in random_directions(n, 4, 11) {
        let mu = unit(dir);
        let (d, m) = (evaluate(&ff, &mu), evaluate(&moments, &mu));
        assert!((d.energy - m.energy).abs() < 1e-12 * d.energy);
        assert!((ff.energy(&mu) - energy(&p, &mu)).abs() < 1e-15);
        assert!((ff.energy(&mu) - d.energy).abs() < 1e-15);
        let gs = d.gradient.iter().map(|x| x.abs()).fold(0.0, f64::max);
        for (a, b) in d.gradient.iter().zip(&m.gradient) {
            assert!((a - b).abs() < 1e-9 * gs, "gradient {a:e} vs {b:e}");
        }
        let hs = d.hessian.iter().map(|x| x.abs()).fold(0.0, f64::max);
        for (a, b) in d.hessian.iter().zip(&m.hessian) {
            assert!((a - b).abs() < 1e-9 * hs, "hessian {a:e} vs {b:e}");
        }
        // the O(F n) first-order pass is the aggregates' energy and gradient
        let (e1, g1) = ff.first_order(&mu);
        assert!((e1 - d.energy).abs() < 1e-13 * d.energy);
        for (a, b) in g1.iter().zip(&d.gradient) {
            assert!(
                (a - b).abs() < 1e-12 * gs,
                "first-order gradient {a:e} vs {b:e}"
            );
        }
        // the great circle's trigonometric form is the energy on the circle
        let w = {
            let r: Vec<f64> = random_directions(n, 1, 5).remove(0);
            let along: f64 = r.iter().zip(&mu).map(|(a, b)| a * b).sum();
            unit(r.iter().zip(&mu).map(|(a, b)| a - along * b).collect())
        };
        let c = ff.great_circle(&mu, &w);
        for theta in [0.0, 0.3, -1.1, 1.5] {
            let (s, co) = f64::sin_cos(theta);
            let on: Vec<f64> = mu.iter().zip(&w).map(|(a, b)| co * a + s * b).collect();
            let (s2, c2) = f64::sin_cos(2.0 * theta);
            let trig = c[0]
                + 2.0 * c[1] * c2
                + 2.0 * c[2] * s2
                + c[3] * c2 * c2
                + c[4] * s2 * s2
                + 2.0 * c[5] * c2 * s2;
            assert!(
                (trig - ff.energy(&on)).abs() < 1e-12 * ff.energy(&on),
                "circle {trig:e} vs {:e}",
                ff.energy(&on)
            );
        }
    }
    let basis: Vec<Vec<f64>> = (0..n)
        .map(|k| {
            ff.whiten(
                &(0..n)
                    .map(|i| f64::from(u8::from(i == k)))
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    let options = FormSearchOptions::DEFAULT.with_starts(8);
    let (d, m) = (
        multistart(&ff, &[], &basis, None, false, &options),
        multistart(&moments, &[], &basis, None, false, &options),
    );
    assert!(
        (d.energy - m.energy).abs() < 1e-10 * m.energy,
        "{d:?} {m:?}"
    );
    // the basis forms' energies of the edge-value pass are the direct sums'
    for (k, b) in basis.iter().enumerate() {
        assert!((ff.basis_energy[k] - ff.energy(b)).abs() < 1e-12 * ff.energy(b));
    }
    assert!((d.energy - map.objective.uniformity).abs() < 1e-10 * d.energy);
    assert_eq!(d.unconverged, 0);
    // the two-level search (a third of the faces first, then all) reaches the same optimum
    let coarse = ff.sample(3);
    assert_eq!(coarse.faces(), ff.faces().div_ceil(3));
    let coarse_model: &dyn super::uniform::EnergyModel = &coarse;
    let two = multistart(&ff, &[coarse_model], &basis, None, false, &options);
    assert!((two.energy - m.energy).abs() < 1e-10 * m.energy, "{two:?}");
    assert!(two.coarse_iterations > 0 && two.unconverged == 0, "{two:?}");
    // three levels (a ninth, a third, all): the same optimum, Hessians kept or seeded
    let coarsest = ff.sample(9);
    let coarsest_model: &dyn super::uniform::EnergyModel = &coarsest;
    let three = multistart(
        &ff,
        &[coarsest_model, coarse_model],
        &basis,
        None,
        false,
        &options,
    );
    assert!(
        (three.energy - m.energy).abs() < 1e-10 * m.energy,
        "{three:?}"
    );
    assert_eq!(three.unconverged, 0, "{three:?}");
    // at most one Hessian per Newton step plus one per search (3 levels of all starts)
    let searches = 3 * (basis.len() + options.starts);
    assert!(
        three.hessians_total > 0
            && three.hessians_total <= three.coarse_iterations + three.iterations_total + searches,
        "{three:?}"
    );
    // the cost model: the default search of a genus-2 surface on the moments, genus 23
    // with the topological optimization's 4 starts (armadillo's 86k faces) on the faces
    assert!(use_moments(map.input_faces, 4, 2 * (4 + 48)));
    assert!(!use_moments(86_482, 46, 4));
    assert_eq!(map.objective.energy_model, "moments");
}

#[test]
fn face_forms_from_harmonic_forms_and_their_conjugation_equal_those_of_the_basis() {
    use super::faces::FaceForms;
    let map = global_map(&eightsim(), &GlobalMapOptions::DEFAULT).expect("map");
    let forms = &map.basis_forms();
    let n = forms.len();
    // a_k = h_k + i Σ_j Λ_jk h_j: h the real parts, Λ recovered by least squares
    let h: Vec<Vec<f64>> = forms
        .iter()
        .map(|a| a.iter().map(|z| z.re).collect())
        .collect();
    let mut gram: Vec<f64> = (0..n * n)
        .map(|k| h[k / n].iter().zip(&h[k % n]).map(|(a, b)| a * b).sum())
        .collect();
    let mut rhs: Vec<f64> = (0..n * n)
        .map(|k| {
            let (col, j) = (k / n, k % n);
            h[j].iter().zip(&forms[col]).map(|(a, z)| a * z.im).sum()
        })
        .collect();
    conformap_operators::solve_dense_spd(&mut gram, n, &mut rhs, n, 1).expect("gram");
    let lambda: Vec<f64> = (0..n * n).map(|k| rhs[(k % n) * n + k / n]).collect();
    let rebuilt = crate::forms::periods::holomorphic_basis(&h, &lambda);
    let scale = forms.iter().flatten().map(|z| z.norm()).fold(0.0, f64::max);
    let off = rebuilt
        .iter()
        .flatten()
        .zip(forms.iter().flatten())
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    assert!(
        off < 1e-9 * scale,
        "the basis is h + i hΛ: {off:e} of {scale:e}"
    );
    let direct = FaceForms::from_harmonic(&map.surface, &map.edges, &h, &lambda, map.input_faces)
        .expect("from the harmonic forms");
    let reference = FaceForms::new(&map.surface, &map.edges, &rebuilt, map.input_faces)
        .expect("from the basis");
    assert_eq!(direct.basis_energy.len(), n);
    for (a, b) in direct.basis_energy.iter().zip(&reference.basis_energy) {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs(),
            "basis energy {a:e} vs {b:e}"
        );
    }
    for dir in random_directions(n, 6, 5) {
        let mu = unit(dir);
        let (a, b) = (direct.energy(&mu), reference.energy(&mu));
        assert!((a - b).abs() <= 1e-12 * b.abs(), "energy {a:e} vs {b:e}");
    }
}
