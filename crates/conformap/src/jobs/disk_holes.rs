//! `conformap disk` on a mesh with several boundary loops: the unit disk with circular holes
//! (`conformap_disk::koebe`: CEM Algorithm 2, Koebe's iteration, then the circle-domain
//! polish).
//!
//! `--outer K` picks the loop mapped onto the unit circle (default: the longest);
//! `--max-iter` caps the Koebe sweeps and `--tol` is their circle-residual tolerance;
//! `--method` does not apply (the first map is CEM, as in the paper). The report's `solver`
//! object is the Koebe report (`iterations` = sweeps, `energy_history` = the polish's
//! `E_C`, `residual` = the worst circle residual, plus the convergence history), and a
//! `circle_domain` object lists every loop's centre, radius and residual and, for two
//! loops, the conformal modulus.

use std::time::Instant;

use conformap_disk::{koebe, KoebeOptions};
use conformap_metrics::{planar_map_metrics, MetricsOptions};

use crate::failure::Failure;
use crate::pipeline::{disk_uv, planar_points, Input, Solved};
use crate::report::{
    ms_since, CircleDomainSection, MetricsSection, Sections, SolverDetail, SolverSection,
    StageTimings,
};

/// The Koebe options of `disk`'s `outer`, `max_iter` (the sweeps) and `tol`.
pub fn koebe_options(
    outer: Option<usize>,
    max_iter: Option<usize>,
    tol: Option<f64>,
) -> KoebeOptions {
    let mut options = KoebeOptions::DEFAULT.with_outer(outer);
    if let Some(n) = max_iter {
        options = options.with_max_sweeps(n);
    }
    if let Some(t) = tol {
        options = options.with_tol(t);
    }
    options
}

/// Maps `input` (connected, genus 0, several boundary loops) onto the unit disk with
/// circular holes.
pub fn solve(options: &KoebeOptions, input: &Input) -> Result<Solved, Failure> {
    let mesh = &input.mesh;
    let loops = mesh.boundary_loops().len();
    let result = koebe(mesh, options).map_err(|e| input.fail(e.into()))?;
    let r = &result.report;
    let t = Instant::now();
    let metrics_options = MetricsOptions::DEFAULT.with_outer_loop(r.outer_loop);
    let metrics = planar_map_metrics(mesh, &result.map, &metrics_options)?;
    let metrics_ms = ms_since(t);
    let summary = format!(
        "{} vertices, {} faces, {loops} boundary loops; disk with circular holes in {} \
         Koebe sweeps{}; worst circle residual {:.1e}, E_C = {:.6e}, mean angle distortion \
         {:.3}°, flipped faces {}{}",
        mesh.num_vertices(),
        mesh.num_faces(),
        r.sweeps,
        if r.converged { " (converged)" } else { "" },
        metrics.circle_residual_max,
        metrics.conformal_energy,
        metrics.angle_distortion_deg.mean,
        metrics.flipped_faces,
        result
            .modulus
            .map_or(String::new(), |m| format!(", modulus ln(R/r) = {m:.6}")),
    );
    let sections = Sections {
        circle_domain: Some(CircleDomainSection {
            circles: result.circles.clone(),
            modulus: result.modulus,
            normalization: "outer loop on the unit circle with its first vertex at angle 0; \
                            the reference hole (lowest loop index) centred at 0",
            outer_loop: r.outer_loop,
            reference_hole: result.reference_hole,
        }),
        ..Sections::default()
    };
    let tm = &r.timings_ms;
    Ok(Solved {
        picture_domain: None,
        method: "koebe".to_string(),
        uv: disk_uv(&result.map).into(),
        flat: (planar_points(&result.map), None),
        solver: SolverSection::new(result.summary(), SolverDetail::Koebe(Box::new(r.clone()))),
        param: None,
        sections,
        metrics: MetricsSection::planar(metrics),
        timings: StageTimings {
            assemble: tm.assemble,
            factor: tm.factor,
            solve: tm.total - tm.assemble - tm.factor,
            metrics: metrics_ms,
            ..StageTimings::default()
        },
        strict_violation: (!r.converged).then(|| {
            format!(
                "the disk with circular holes did not converge in {} Koebe sweeps",
                r.sweeps
            )
        }),
        summary,
    })
}
