//! `#[ignore]`d checks of the optimal form on the real genus-2 and genus-4 meshes of
//! `../shared/meshes` (eight, fertility): the uniform optimum against the basis forms, a
//! dense sampling of the coefficient sphere and other seeds; the emphasized half against
//! sampling and brute force; zero allocation by edge rings. Run with
//! `cargo test --release -p conformap-global real_ -- --ignored --nocapture`.

use conformap_mesh::TriMesh;
use conformap_testkit::{read_plain_obj, shared_mesh_or_skip};

use super::tests::{half_region, sampled_energy_range, surface_shares};
use super::{FormSearchOptions, Objective};
use crate::{global_map, GlobalMapOptions};

/// Random unit vectors of the basis coefficients per mesh.
const DENSE_SAMPLES: usize = 4000;

/// Seeds besides the default whose best energy must agree with the default's.
const OTHER_SEEDS: [u64; 5] = [1, 2, 3, 4, 5];

fn shared(name: &str, test: &str) -> Option<TriMesh> {
    let path = shared_mesh_or_skip(name, test)?;
    Some(read_plain_obj(&path).expect("shared mesh"))
}

fn uniform_beats_sampling(name: &str) {
    let Some(mesh) = shared(name, "real_uniform_optimum") else {
        return;
    };
    let map = global_map(&mesh, &GlobalMapOptions::DEFAULT).expect("map");
    let o = &map.objective;
    let search = o.search.as_ref().expect("genus ≥ 2: a search");
    let least = o.opposite.as_ref().expect("the least-uniform comparison");
    for &e in &o.basis_uniformity {
        assert!(
            o.uniformity <= e,
            "{name}: basis form {e:e} below the optimum"
        );
    }
    let s = surface_shares(&map);
    let (lo, hi) = sampled_energy_range(&map, &s, DENSE_SAMPLES, 2024);
    assert!(
        o.uniformity <= lo,
        "{name}: sample {lo:e} < optimum {:e}",
        o.uniformity
    );
    assert!(
        least.energy >= hi,
        "{name}: sample {hi:e} > least uniform {:e}",
        least.energy
    );
    assert_eq!(search.unconverged, 0, "{name}: {search:?}");
    for seed in OTHER_SEEDS {
        let other = global_map(
            &mesh,
            &GlobalMapOptions::DEFAULT.with_search(
                FormSearchOptions::DEFAULT
                    .with_seed(seed)
                    .with_compare(false),
            ),
        )
        .expect("map");
        let e = other.objective.uniformity;
        assert!(
            (e - o.uniformity).abs() <= 1e-7 * o.uniformity,
            "{name}: seed {seed} found {e:e}, the default seed {:e}",
            o.uniformity
        );
    }
    eprintln!(
        "{name}: uniform {:.5e} (best basis {:.5e}, {DENSE_SAMPLES} samples {lo:.5e}..{hi:.5e}), \
         least {:.5e}, max/min {:.2}; starts {}, reached best {}, optima {:?} counts {:?}, \
         iterations {} (max {}); search {:.1} ms + {:.1} ms, area forms {:.1} ms",
        o.uniformity,
        o.basis_uniformity
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min),
        least.energy,
        o.max_min_ratio.unwrap_or(f64::NAN),
        search.starts,
        search.reached_best,
        search.local_optima,
        search.local_optimum_counts,
        search.iterations_total,
        search.iterations_max,
        search.time_ms,
        least.time_ms,
        o.products_ms,
    );
}

#[test]
#[ignore = "reads ../shared/meshes/eight.obj"]
fn real_uniform_optimum_on_eight() {
    uniform_beats_sampling("eight.obj");
}

#[test]
#[ignore = "reads ../shared/meshes/fertility.obj"]
fn real_uniform_optimum_on_fertility() {
    uniform_beats_sampling("fertility.obj");
}

fn emphasized_half(name: &str) {
    let Some(mesh) = shared(name, "real_emphasized_half") else {
        return;
    };
    let half = half_region(&mesh, mesh.num_faces());
    for maximize in [true, false] {
        let objective = Objective::Emphasize {
            faces: half.clone(),
            maximize,
        };
        let map =
            global_map(&mesh, &GlobalMapOptions::DEFAULT.with_objective(objective)).expect("map");
        let em = map.objective.emphasis.clone().expect("emphasis");
        let chosen = if maximize { em.share_max } else { em.share_min };
        assert!((em.share - chosen).abs() < 1e-12, "{name}: {em:?}");
        eprintln!(
            "{name} half ({} faces, {:.4} of the surface): {} share {:.6} (range {:.6}..{:.6})",
            em.region_faces,
            em.surface_share,
            if maximize {
                "emphasized"
            } else {
                "de-emphasized"
            },
            em.share,
            em.share_min,
            em.share_max
        );
        assert!(em.share_min < em.surface_share && em.surface_share < em.share_max);
    }
}

#[test]
#[ignore = "reads ../shared/meshes/eight.obj and fertility.obj"]
fn real_emphasized_half_on_eight_and_fertility() {
    emphasized_half("eight.obj");
    emphasized_half("fertility.obj");
}

/// Zero allocation on `name` for each target set: every target's edge-ring distance to the
/// nearest zero of the result. Returns the distances.
fn zero_ring_distances(name: &str, target_sets: &[&[usize]]) -> Vec<usize> {
    let Some(mesh) = shared(name, "real_zero_allocation") else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for &targets in target_sets {
        let map = global_map(
            &mesh,
            &GlobalMapOptions::DEFAULT.with_objective(Objective::Zeros {
                vertices: targets.to_vec(),
            }),
        )
        .expect("map");
        let z = map.objective.zeros.as_ref().expect("zeros");
        assert!(z.exact_expected);
        assert_eq!(z.method, "exact");
        for t in &z.targets {
            eprintln!(
                "{name} targets {targets:?}: v{} ring distance {:?} to zero {:?}, |ω| {:.3e} \
                 (median {:.3e}), uniformity {:.3e}",
                t.vertex,
                t.ring_distance,
                t.nearest_zero,
                t.residual,
                z.median_stretch,
                map.objective.uniformity
            );
            out.push(t.ring_distance.unwrap_or(usize::MAX));
        }
    }
    out
}

#[test]
#[ignore = "reads ../shared/meshes/eight.obj"]
fn real_zero_allocation_one_target_on_eight() {
    let d = zero_ring_distances("eight.obj", &[&[100], &[900], &[1800], &[2700], &[3400]]);
    assert!(d.iter().all(|&d| d <= 2), "{d:?}");
}

/// Ten pairs of targets spread over fertility. Measured: 16 of the 20 targets get a zero
/// within 2 edge rings, the other four within 3–5 (v2000, v3300, v1900, v3900): with those
/// pairs every form vanishing at both targets is small over a whole region around them
/// (median `|ω|` 2–5 % of the uniform forms'), so the discrete zero's place is loose.
#[test]
#[ignore = "reads ../shared/meshes/fertility.obj"]
fn real_zero_allocation_two_targets_on_fertility() {
    let d = zero_ring_distances(
        "fertility.obj",
        &[
            &[100, 3000],
            &[500, 2500],
            &[1500, 4000],
            &[2000, 4400],
            &[250, 1250],
            &[700, 3700],
            &[1100, 2100],
            &[3300, 4300],
            &[50, 2250],
            &[1900, 3900],
        ],
    );
    if d.is_empty() {
        return;
    }
    let near = d.iter().filter(|&&x| x <= 2).count();
    assert!(
        near * 5 >= d.len() * 4,
        "{near} of {} within 2 rings: {d:?}",
        d.len()
    );
    assert!(d.iter().all(|&x| x <= 5), "{d:?}");
}
