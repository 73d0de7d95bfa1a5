//! The greedy loop of the topological optimization (Jin et al. 2004, §3.5): map, find the
//! extreme clusters, slit them all, map the slit surface by its most uniform holomorphic
//! form, repeat; keep the best layout seen, the starting map included.

use std::time::Instant;

use conformap_mesh::{SlitMesh, SlitPlanner, Topology, TriMesh};
use conformap_operators::{
    cotan_laplacian, Cholesky, CholeskyOptions, LaplacianBlocks, Ordering, Partition,
};
use serde::{Deserialize, Serialize};

use crate::forms::{global_map, global_map_ranked, GlobalMap};
use crate::topology_opt::clusters::{
    extreme_clusters, extreme_threshold, vertex_log_area_ratio, Cluster,
};
use crate::topology_opt::options::TopologyOptOptions;
use crate::GlobalError;
use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
use conformap_metrics::{log_ratio_stats, LogRatioStats};
use conformap_operators::planar::triangle_signed_area;
use conformap_operators::vec3::{cross, dot};
use conformap_sphere::{
    optimize_disk_mobius, optimize_sphere_mobius, planar_face_areas, sphere_face_areas, sphere_map,
    surface_shares, uniformity_from_areas, MobiusObjective, MobiusOptions, SphereOptions,
};

/// Cluster vertices tried as a slit centre, nearest to the cluster's centre first: `8`.
/// The nearest is the paper's extreme point; when it is blocked (next to an earlier slit)
/// or no slit fits there, the next ones are tried before the cluster is given up.
pub const CENTRE_CANDIDATES: usize = 8;

/// Times the extreme-area fraction is doubled (and the area-ratio cap dropped) when the
/// first step on a closed genus-0 surface finds one cluster only: `4` (up to 16× the
/// fraction). One slit alone is useless: its double covering is a sphere again. With no
/// cluster at all nothing is relaxed: the loop stops with the sphere map (on david_head the
/// forced slits cost 22× and 245× the sphere map's energy).
pub const FIRST_STEP_RELAXATIONS: usize = 4;

/// One slit of a step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct SlitRecord {
    /// The centre vertex (input numbering).
    pub centre: u32,
    /// The slit's vertex path (input numbering).
    pub vertices: Vec<u32>,
    /// Vertices of the extreme cluster it cuts.
    pub cluster_vertices: usize,
    /// Share of the surface area of that cluster.
    pub cluster_area_fraction: f64,
    /// Smallest log area ratio in the cluster.
    pub cluster_min_log_ratio: f64,
}

/// One step of the loop (step 0: the starting map, no slit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[non_exhaustive]
pub struct TopologyStep {
    /// The slits added at this step.
    pub added: Vec<SlitRecord>,
    /// Slits in all after this step.
    pub slits: usize,
    /// Genus of the closed surface the map lives on (0: the sphere map; the double
    /// covering of the slit surface otherwise).
    pub surface_genus: usize,
    /// Uniformity energy `Σ_f (a_f/Σa − S_f/ΣS)²` over the input's faces.
    pub energy: f64,
    /// `energy` over the starting map's.
    pub ratio_to_start: f64,
    /// Log area distortion `log((a_f/Σa)/(S_f/ΣS))` over the unfolded input faces.
    pub area_distortion_log: LogRatioStats,
    /// Folded faces at zeros of the form.
    pub folds_at_zeros: usize,
    /// Folded faces elsewhere (inverted faces of a sphere map).
    pub folds_outside_zeros: usize,
    /// Wall-clock time of the step (clusters, cut, map), milliseconds.
    pub time_ms: f64,
    /// Time of the step's factorizations, milliseconds (the yardstick).
    pub factor_ms: f64,
    /// Time of the choice of the form (edge values per face, the uniform search),
    /// milliseconds.
    pub objective_ms: f64,
    /// How the search evaluated the energy (`moments` or `direct`, see
    /// [`crate::ObjectiveReport::energy_model`]); empty for a sphere or disk map.
    #[serde(default)]
    pub energy_model: String,
    /// Newton iterations of the search over all its starts (0 for a sphere or disk map).
    #[serde(default)]
    pub newton_iterations: usize,
    /// Newton iterations on the search's coarse level, over all its starts (0 without one).
    #[serde(default)]
    pub coarse_iterations: usize,
    /// Hessians the search evaluated over all its starts and levels (fewer than its Newton
    /// iterations: kept across steps near an optimum; 0 for a sphere or disk map).
    #[serde(default)]
    pub hessians: usize,
    /// The global map's own timings by stage (all zero for a sphere or disk map).
    #[serde(default)]
    pub stages_ms: crate::GlobalTimings,
}

/// The layout the loop returns.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum BestLayout {
    /// The uniformity-optimal Möbius disk map (a disk automorphism of the default CCEM map)
    /// of a disk input: one map value per input vertex, in the closed unit disk.
    Disk(Vec<num_complex::Complex64>),
    /// The uniformity-optimal Möbius sphere map of a closed genus-0 input: one unit vector
    /// per input vertex.
    Sphere(Vec<[f64; 3]>),
    /// A global map: of the input itself (genus ≥ 1, `slit: None`) or of the input cut
    /// along slits (its faces are the input's, in the input's order).
    Global {
        /// The map (of `slit.mesh`, or of the input).
        map: Box<GlobalMap>,
        /// The slit mesh mapped.
        slit: Option<SlitMesh>,
    },
}

/// The outcome of [`topology_opt`].
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct TopologyOpt {
    /// Every step, step 0 the starting map.
    pub steps: Vec<TopologyStep>,
    /// The step whose layout is returned (lowest energy).
    pub best_step: usize,
    /// That layout.
    pub best: BestLayout,
    /// The slit length used, in 3D units.
    pub slit_length: f64,
    /// Why the loop stopped.
    pub stop: String,
    /// Total wall-clock time, milliseconds.
    pub total_ms: f64,
}

/// What the loop needs from a map: per-face image areas of the input's faces and the
/// vertices to leave alone (zero clusters), in input numbering.
struct Measured {
    image: Vec<f64>,
    excluded: Vec<bool>,
    step: TopologyStep,
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn area_stats(image: &[f64], shares: &[f64]) -> LogRatioStats {
    let total: f64 = image.iter().filter(|a| **a > 0.0).sum();
    let logs: Vec<f64> = image
        .iter()
        .zip(shares)
        .filter(|(a, _)| **a > 0.0)
        .map(|(a, s)| (a / total / s).ln())
        .collect();
    log_ratio_stats(&logs)
}

/// How many faces of the double covering's first copy each face of `mapped` became: 1, plus
/// one per edge joining two boundary vertices through the interior (a chord, split at its
/// midpoint by `double_cover_surface`, whose faces follow in the input's order).
fn children_per_face(mapped: &TriMesh) -> Vec<usize> {
    let opp = mapped.opposite_halfedges();
    let bnd = mapped.boundary_flags();
    (0..mapped.num_faces())
        .map(|f| {
            1 + (0..3)
                .filter(|&k| {
                    let h = 3 * f + k;
                    let (a, b) = mapped.halfedge_vertices(h);
                    opp[h] != conformap_mesh::NO_HALFEDGE && bnd[a as usize] && bnd[b as usize]
                })
                .count()
        })
        .collect()
}

/// Measures a global map of `mesh` or of its slit mesh `slit` (`None`: the input itself).
/// When the double covering split boundary chords, each input face's image area is the sum
/// of its pieces', and the energy is measured over the input's faces.
fn measure_global(
    mesh: &TriMesh,
    map: &GlobalMap,
    slit: Option<&SlitMesh>,
    shares: &[f64],
) -> Measured {
    let uv = map.input_corner_uv();
    let piece = |f: usize| triangle_signed_area(uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]);
    let image: Vec<f64> = if map.split_edges == 0 {
        (0..mesh.num_faces()).map(piece).collect()
    } else {
        let mut next = 0;
        children_per_face(slit.map_or(mesh, |s| &s.mesh))
            .into_iter()
            .map(|c| {
                let a = (next..next + c).map(piece).sum();
                next += c;
                a
            })
            .collect()
    };
    let mut excluded = vec![false; mesh.num_vertices()];
    let mapped_vertices = slit.map_or(mesh.num_vertices(), |s| s.original.len());
    // chord midpoints (numbered after the mapped mesh's vertices) have no input vertex
    for v in 0..map.input_vertices.min(mapped_vertices) {
        if map.zeros.in_zero_cluster[v] {
            excluded[slit.map_or(v, |s| s.original[v] as usize)] = true;
        }
    }
    let (at, outside) = map.input_folds();
    let step = TopologyStep {
        added: Vec::new(),
        slits: 0,
        surface_genus: map.surface_genus,
        energy: uniformity_from_areas(&image, shares),
        ratio_to_start: 1.0,
        area_distortion_log: area_stats(&image, shares),
        folds_at_zeros: at,
        folds_outside_zeros: outside,
        time_ms: map.timings_ms.total,
        factor_ms: map.timings_ms.factor,
        objective_ms: map.timings_ms.objective,
        energy_model: map.objective.energy_model.clone(),
        newton_iterations: map
            .objective
            .search
            .as_ref()
            .map_or(0, |s| s.iterations_total),
        coarse_iterations: map
            .objective
            .search
            .as_ref()
            .map_or(0, |s| s.coarse_iterations),
        hessians: map
            .objective
            .search
            .as_ref()
            .map_or(0, |s| s.hessians_total),
        stages_ms: map.timings_ms,
    };
    Measured {
        image,
        excluded,
        step,
    }
}

/// Slits at the extreme clusters of the map measured in `m`, on a copy of `planner`: at
/// most `budget`, at least `need` (else relaxing the thresholds when `relax`).
fn add_slits(
    mesh: &TriMesh,
    planner: &SlitPlanner,
    m: &Measured,
    options: &TopologyOptOptions,
    (length, budget, need, relax): (f64, usize, usize, bool),
) -> (SlitPlanner, Vec<SlitRecord>) {
    let adjacency = planner.adjacency();
    let log_ratio = vertex_log_area_ratio(mesh, &m.image);
    let (mut fraction, mut cap) = (
        options.extreme_area_fraction,
        options.max_extreme_area_ratio,
    );
    let rounds = if relax { FIRST_STEP_RELAXATIONS + 1 } else { 1 };
    let mut out = (planner.clone(), Vec::new());
    for _ in 0..rounds {
        let th = extreme_threshold(mesh, &log_ratio, &m.excluded, fraction, cap);
        let clusters = extreme_clusters(mesh, adjacency, &log_ratio, &m.excluded, th);
        let mut trial = planner.clone();
        let mut added = Vec::new();
        for c in &clusters {
            if added.len() >= budget {
                break;
            }
            if let Some(r) = slit_cluster(mesh, &mut trial, c, length) {
                added.push(r);
            }
        }
        let (enough, none) = (added.len() >= need, clusters.is_empty());
        out = (trial, added);
        // relax only to find a partner for a genuine extreme cluster: with none at all the
        // shape is compact and slits do not pay
        if enough || none {
            break;
        }
        fraction *= 2.0;
        cap = 1.0;
    }
    out
}

/// A slit at the cluster's centre vertex, or at the next vertex nearest to the centre.
fn slit_cluster(
    mesh: &TriMesh,
    planner: &mut SlitPlanner,
    c: &Cluster,
    length: f64,
) -> Option<SlitRecord> {
    for &v in c.by_distance.iter().take(CENTRE_CANDIDATES) {
        let Some(path) = planner.propose(mesh, v, length) else {
            continue;
        };
        if planner.add(path.clone()).is_ok() {
            return Some(SlitRecord {
                centre: v,
                vertices: path,
                cluster_vertices: c.by_distance.len(),
                cluster_area_fraction: c.area_fraction,
                cluster_min_log_ratio: c.min_log_ratio,
            });
        }
    }
    None
}

/// The elimination rank of every input vertex in the fill-reducing ordering of the input's
/// cotangent Laplacian (vertex 0 pinned, ranked last), analysed once for the whole loop;
/// `None` when `cholesky` asks for another ordering than the default policy or the analysis
/// fails (each slit surface then orders its own). Every slit surface's factorizations
/// inherit it ([`slit_ranks`]): the per-step ordering (AMD of both halves of the double
/// covering, most of their symbolic analysis) is gone (docs/benchmarks.md, issue 23).
fn input_ranks(mesh: &TriMesh, cholesky: &CholeskyOptions) -> Option<Vec<u64>> {
    if cholesky.ordering != Ordering::Auto {
        return None;
    }
    let l = cotan_laplacian(mesh);
    let part = Partition::new(mesh.num_vertices(), &[0]);
    let blocks = LaplacianBlocks::new(&l, &part);
    let perm = Cholesky::analyse_with(&blocks.ii, cholesky)
        .ok()?
        .permutation();
    let mut rank = vec![perm.len() as u64; mesh.num_vertices()];
    for (k, &p) in perm.iter().enumerate() {
        rank[part.interior[p] as usize] = k as u64;
    }
    Some(rank)
}

/// The ranks of the slit mesh's vertices: each input vertex keeps its rank (doubled), the
/// copies of a slit vertex come right after it.
fn slit_ranks(input: &[u64], slit: &SlitMesh) -> Vec<u64> {
    slit.original
        .iter()
        .enumerate()
        .map(|(v, &o)| 2 * input[o as usize] + u64::from(o as usize != v))
        .collect()
}

/// The starting map: the uniformity-optimal Möbius sphere map of a closed genus-0 mesh, or
/// the most uniform global map of a surface of genus ≥ 1 (or with ≥ 2 boundary loops).
fn start(
    mesh: &TriMesh,
    options: &TopologyOptOptions,
    shares: &[f64],
) -> Result<(Measured, BestLayout), GlobalError> {
    if mesh.topology() == Topology::Disk {
        return start_disk(mesh, shares);
    }
    if mesh.topology() != Topology::Sphere {
        let map = global_map(mesh, &options.global)?;
        let m = measure_global(mesh, &map, None, shares);
        return Ok((
            m,
            BestLayout::Global {
                map: Box::new(map),
                slit: None,
            },
        ));
    }
    let t = Instant::now();
    let map = sphere_map(mesh, &SphereOptions::DEFAULT)?;
    let best = optimize_sphere_mobius(
        mesh,
        &map.points,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    )?;
    let image = sphere_face_areas(mesh, &best.points)?;
    let inverted = mesh
        .faces()
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|v| best.points[v as usize]);
            dot(a, cross(b, c)) <= 0.0
        })
        .count();
    let factor_ms = map.report.timings_ms.factor;
    let measured = start_measured(mesh, image, shares, inverted, ms(t), factor_ms);
    Ok((measured, BestLayout::Sphere(best.points)))
}

/// Step 0 of the loop: the starting map (sphere or disk) with no slit, its image areas
/// `image` and `folded` faces.
fn start_measured(
    mesh: &TriMesh,
    image: Vec<f64>,
    shares: &[f64],
    folded: usize,
    time_ms: f64,
    factor_ms: f64,
) -> Measured {
    let step = TopologyStep {
        added: Vec::new(),
        slits: 0,
        surface_genus: 0,
        energy: uniformity_from_areas(&image, shares),
        ratio_to_start: 1.0,
        area_distortion_log: area_stats(&image, shares),
        folds_at_zeros: 0,
        folds_outside_zeros: folded,
        time_ms,
        factor_ms,
        objective_ms: 0.0,
        energy_model: String::new(),
        newton_iterations: 0,
        coarse_iterations: 0,
        hessians: 0,
        stages_ms: crate::GlobalTimings::default(),
    };
    Measured {
        image,
        excluded: vec![false; mesh.num_vertices()],
        step,
    }
}

/// The starting map of a disk: the default disk map (CCEM with BFGS, flip-free) moved by
/// its uniformity-optimal disk automorphism.
fn start_disk(mesh: &TriMesh, shares: &[f64]) -> Result<(Measured, BestLayout), GlobalError> {
    let t = Instant::now();
    let disk = compute_disk_map(mesh, DiskMethod::default(), &DiskOptions::DEFAULT)?;
    let best = optimize_disk_mobius(
        mesh,
        &disk.map,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    )?;
    let image = planar_face_areas(mesh, &best.map)?;
    let folded = image.iter().filter(|a| **a <= 0.0).count();
    let factor_ms = disk.report.timings_ms.factor;
    let measured = start_measured(mesh, image, shares, folded, ms(t), factor_ms);
    Ok((measured, BestLayout::Disk(best.map)))
}

/// Topological optimization (Jin et al. 2004, §3.5): starting from the uniformity-optimal
/// Möbius sphere map (closed genus 0), the uniformity-optimal disk automorphism of the
/// default disk map (a disk) or the most uniform holomorphic form (genus ≥ 1 or several
/// boundary loops),
/// greedily slits the surface at all extreme clusters of the current map at once (see
/// `clusters.rs`), maps the slit surface through its double covering by its most uniform
/// form ([`global_map`]), and repeats on the latest slit surface until
/// [`TopologyOptOptions::max_slits`], no new cluster, a failed map, or
/// [`TopologyOptOptions::patience`] steps without a new best. The energy is not monotone in
/// the slit count, so the best layout seen is returned — the starting map included: the
/// result is never less uniform than it.
///
/// # Errors
/// [`GlobalError::WrongTopology`] for several components;
/// [`GlobalError::InvalidOption`] for a slit length that is not positive and finite;
/// the errors of the starting map ([`conformap_sphere::sphere_map`], [`GlobalError::Disk`],
/// [`global_map`]). A failed map of
/// a slit surface ends the loop instead (see [`TopologyOpt::stop`]).
pub fn topology_opt(
    mesh: &TriMesh,
    options: &TopologyOptOptions,
) -> Result<TopologyOpt, GlobalError> {
    let t_all = Instant::now();
    let found = mesh.topology();
    let usable = matches!(
        found,
        Topology::Sphere
            | Topology::Disk
            | Topology::MultiplyConnected { .. }
            | Topology::ClosedHigherGenus { .. }
            | Topology::OpenHigherGenus { .. }
    );
    if !usable {
        return Err(GlobalError::WrongTopology {
            operation: "topological optimization",
            expected: "one connected surface (closed genus 0, a disk, genus ≥ 1 or several \
                       boundary loops)",
            found,
        });
    }
    if !(options.slit_length > 0.0 && options.slit_length.is_finite()) {
        return Err(GlobalError::InvalidOption {
            name: "slit_length",
            reason: "must be a positive fraction of the bounding-box diagonal",
        });
    }
    let shares = surface_shares(mesh);
    let (mut current, mut best) = start(mesh, options, &shares)?;
    let e0 = current.step.energy;
    let length = options.slit_length * mesh.bbox_diagonal();
    let first_need = if found == Topology::Sphere { 2 } else { 1 };
    let mut steps = vec![current.step.clone()];
    let (mut best_step, mut best_energy, mut since_best) = (0, e0, 0);
    let mut planner = SlitPlanner::new(mesh);
    let rank = input_ranks(mesh, &options.global.cholesky);
    let stop = loop {
        let have = planner.slits().len();
        if have >= options.max_slits {
            break format!("reached {} slits (max_slits)", options.max_slits);
        }
        if since_best >= options.patience {
            break format!("{since_best} steps without a new best (patience)");
        }
        let t = Instant::now();
        let need = if have == 0 { first_need } else { 1 };
        let budget = options.max_slits - have;
        let (next, added) = add_slits(
            mesh,
            &planner,
            &current,
            options,
            (length, budget, need, have == 0 && need > 1),
        );
        if added.len() < need {
            break "no new extreme cluster to slit".to_owned();
        }
        planner = next;
        let cut = planner.cut(mesh)?;
        let slit_rank = rank.as_ref().map(|r| slit_ranks(r, &cut));
        let map = match global_map_ranked(&cut.mesh, &options.global, slit_rank.as_deref()) {
            Ok(map) => map,
            Err(e) => break format!("the map of the slit surface failed: {e}"),
        };
        let mut m = measure_global(mesh, &map, Some(&cut), &shares);
        m.step.added = added;
        m.step.slits = planner.slits().len();
        m.step.ratio_to_start = m.step.energy / e0;
        m.step.time_ms = ms(t);
        steps.push(m.step.clone());
        if m.step.energy < best_energy {
            (best_step, best_energy, since_best) = (steps.len() - 1, m.step.energy, 0);
            best = BestLayout::Global {
                map: Box::new(map),
                slit: Some(cut),
            };
        } else {
            since_best += 1;
        }
        current = m;
    };
    Ok(TopologyOpt {
        steps,
        best_step,
        best,
        slit_length: length,
        stop,
        total_ms: ms(t_all),
    })
}
