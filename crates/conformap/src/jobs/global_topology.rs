//! `conformap global MESH -o OUT --topology-opt [--max-slits N] [--slit-length F]`: the
//! topological optimization of Jin et al. §3.5 (`conformap_global::topology_opt`).
//!
//! What `-o` gets depends on the layout returned (the most uniform one seen, the report's
//! `topology_opt.returned`):
//! - a slit surface's (or, genus ≥ 1, the input's own) global map: written as `global`
//!   writes it — the input's vertices in the input's order, one `vt` per corner class
//!   (`f v/vt`). The slit mesh has the input's faces in the input's order, so its per-corner
//!   texture coordinates are the input's: the two sides of a slit simply get different `vt`;
//!   `--flat` gets the slit surface's fundamental domain.
//! - the starting sphere map (closed genus 0, when no slit paid): written as `sphere`
//!   writes it — one `vt` per face corner, the equirectangular projection of the sphere
//!   point split along the seam meridian;
//!   `--flat` the unit-sphere points; `--png` draws it as `sphere --png` does (the
//!   checkerboard through the sphere map, the sphere coloured by angle distortion), not
//!   the equirectangular texture as a flat map.
//! - the starting disk map (a disk, when no slit paid): written as `disk` writes it — one
//!   `vt = ((u+1)/2, (v+1)/2)` per vertex; `--flat` the disk points.
//!
//! The report's `topology_opt` section lists every step (slits added with their centre and
//! vertex path, genus of the double covering, energy and its ratio to the starting map's,
//! log-area spread, folds, time and factorization time).

use conformap_global::{topology_opt, BestLayout, TopologyOpt, TopologyOptOptions};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_sphere::sphere_metrics;

use crate::failure::Failure;
use crate::jobs::global_solved::map_solved;
use crate::pipeline::{disk_uv, planar_points, Input, PictureDomain, Solved};
use crate::report::{
    MetricsExtra, MetricsSection, SolverDetail, SolverSection, Sorted, StageTimings,
    TopologySection, TopologyStepsDetail,
};

/// Runs the loop and packs its best layout as `global` (or `sphere`) would.
pub(crate) fn solve(options: &TopologyOptOptions, input: &Input) -> Result<Solved, Failure> {
    let mesh = &input.mesh;
    let fail = |e: conformap_global::GlobalError| input.fail(e.into());
    let r = topology_opt(mesh, options).map_err(fail)?;
    let best = &r.steps[r.best_step];
    let start = &r.steps[0];
    let (mut solved, returned) = match &r.best {
        BestLayout::Global { map, slit } => {
            let layout_mesh = slit.as_ref().map_or(mesh, |s| &s.mesh);
            let seamed = map.seamed_layout(layout_mesh).map_err(fail)?;
            let solved = map_solved(mesh, map, seamed)?;
            let what = if slit.is_some() { "slits" } else { "input" };
            (solved, what)
        }
        BestLayout::Sphere(points) => (sphere_solved(input, points, &r)?, "sphere"),
        BestLayout::Disk(map) => (disk_solved(input, map, &r)?, "disk"),
        _ => {
            return Err(input.fail(Failure::Numerical(
                "unknown layout kind returned by the topological optimization".to_owned(),
            )))
        }
    };
    solved.sections.topology_opt = Some(Sorted(topology_section(options, &r, returned)));
    solved.method = format!("topology-opt+{}", solved.method);
    solved.summary = format!(
        "topological optimization: {} step(s), best step {} with {} slit(s) (energy {:.3e}, \
         {:.3}× the starting map's), returned {returned}; {}",
        r.steps.len() - 1,
        r.best_step,
        best.slits,
        best.energy,
        best.energy / start.energy,
        solved.summary
    );
    let factor: f64 = r.steps.iter().map(|s| s.factor_ms).sum();
    solved.timings.factor = factor;
    solved.timings.solve = (r.total_ms - factor - solved.timings.metrics).max(0.0);
    Ok(solved)
}

/// The report's `topology_opt` section: every step, and which layout was `returned`.
fn topology_section(
    options: &TopologyOptOptions,
    r: &TopologyOpt,
    returned: &'static str,
) -> TopologySection {
    let (best, start) = (&r.steps[r.best_step], &r.steps[0]);
    TopologySection {
        returned,
        returned_is: "sphere: the starting uniform-Möbius sphere map (no slit paid); \
                      disk: the starting uniform-Möbius disk map (no slit paid); \
                      input: the input's own most uniform form; slits: the global map \
                      of the input cut along `slits`",
        best_step: r.best_step,
        start_energy: start.energy,
        best_energy: best.energy,
        ratio_to_start: best.energy / start.energy,
        slits: r.steps[1..=r.best_step]
            .iter()
            .flat_map(|s| s.added.iter().map(|a| a.vertices.clone()))
            .collect(),
        slit_length: r.slit_length,
        slit_length_fraction: options.slit_length,
        max_slits: options.max_slits,
        patience: options.patience,
        stop: r.stop.clone(),
        steps: r.steps.clone(),
        total_ms: r.total_ms,
    }
}

/// The solver section of a returned starting map: the uniformity energy of every step,
/// step 0 being the `start` (sphere or disk) map.
fn step_history(r: &TopologyOpt, start: &str) -> SolverSection {
    SolverSection::new(
        r.summary(),
        SolverDetail::TopologySteps(TopologyStepsDetail {
            energy_history_is: format!("uniformity energy of each step (step 0: the {start} map)"),
        }),
    )
}

/// The starting sphere map, as `sphere --mobius uniform` writes it.
fn sphere_solved(input: &Input, points: &[[f64; 3]], r: &TopologyOpt) -> Result<Solved, Failure> {
    let mesh = &input.mesh;
    let t = std::time::Instant::now();
    let m = sphere_metrics(mesh, points).map_err(|e| input.fail(e.into()))?;
    let metrics_ms = crate::report::ms_since(t);
    let solver = step_history(r, "sphere");
    let summary = format!(
        "{} vertices, {} faces; uniform-Möbius sphere map (mean angle distortion {:.3}°, \
         inverted faces {}, uniformity {:.3e})",
        mesh.num_vertices(),
        mesh.num_faces(),
        m.angle_distortion_deg.mean,
        m.flipped_faces,
        m.uniformity_energy
    );
    let strict_violation =
        (m.flipped_faces > 0).then(|| format!("{} faces inverted on the sphere", m.flipped_faces));
    Ok(Solved {
        picture_domain: Some(PictureDomain::Sphere),
        method: "sphere+mobius-uniform".to_owned(),
        uv: crate::jobs::sphere::sphere_tex_coords(mesh, points)
            .map_err(|e| input.fail(e.into()))?,
        flat: (points.to_vec(), None),
        solver,
        param: None,
        sections: crate::report::Sections::default(),
        metrics: MetricsSection::sphere(m),
        timings: StageTimings {
            metrics: metrics_ms,
            ..StageTimings::default()
        },
        strict_violation,
        summary,
    })
}

/// The starting disk map (the default disk map moved by its uniform-Möbius automorphism),
/// as `disk` writes a map.
fn disk_solved(
    input: &Input,
    map: &[num_complex::Complex64],
    r: &TopologyOpt,
) -> Result<Solved, Failure> {
    let mesh = &input.mesh;
    let t = std::time::Instant::now();
    let base = planar_map_metrics(mesh, map, &MetricsOptions::default())?;
    let metrics_ms = crate::report::ms_since(t);
    let solver = step_history(r, "disk");
    let summary = format!(
        "{} vertices, {} faces; uniform-Möbius disk map (mean angle distortion {:.3}°, \
         flipped faces {}, uniformity {:.3e})",
        mesh.num_vertices(),
        mesh.num_faces(),
        base.angle_distortion_deg.mean,
        base.flipped_faces,
        r.steps[0].energy
    );
    let strict_violation =
        (base.flipped_faces > 0).then(|| format!("{} faces flipped", base.flipped_faces));
    let metrics = MetricsSection::planar(base).and(MetricsExtra::Uniformity {
        uniformity_energy: r.steps[0].energy,
    });
    Ok(Solved {
        picture_domain: None,
        method: "disk+mobius-uniform".to_owned(),
        uv: disk_uv(map).into(),
        flat: (planar_points(map), None),
        solver,
        param: None,
        sections: crate::report::Sections::default(),
        metrics,
        timings: StageTimings {
            metrics: metrics_ms,
            ..StageTimings::default()
        },
        strict_violation,
        summary,
    })
}
