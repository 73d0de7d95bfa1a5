//! `conformap disk` on a mesh with several boundary loops: the unit disk with circular holes
//! (`conformap_disk::koebe`: CEM Algorithm 2, Koebe's iteration, then the circle-domain
//! polish).
//!
//! Only for connected genus-0 meshes with several loops ([`dispatch`]); every other
//! topology goes to the disk methods, which refuse it with their message. `--outer K`
//! picks the loop mapped onto the unit circle (default: the longest);
//! `--max-iter` caps the Koebe sweeps and `--tol` is their circle-residual tolerance;
//! `--method` does not apply (the first map is CEM, as in the paper). The report's `solver`
//! object is the Koebe report (`iterations` = sweeps, `energy_history` = the polish's
//! `E_C`, `residual` = the worst circle residual, plus the convergence history), and a
//! `circle_domain` object lists every loop's centre, radius and residual and, for two
//! loops, the conformal modulus.

use std::time::Instant;

use conformap_disk::{koebe, CircleDomainMap, KoebeError, KoebeOptions};
use conformap_mesh::{Topology, TriMesh};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use serde_json::json;

use crate::commands::disk::{estimate_peak_bytes, repairs_json, DiskArgs, Input, MemoryCheck};
use crate::commands::write_json;
use crate::failure::Failure;
use crate::report::{ms_since, InputInfo, StageTimings};

/// Runs the disk with circular holes when the mesh is connected, genus 0, with several
/// boundary loops (`Some` with the outcome); `None` for every other mesh, which the disk
/// methods handle (or refuse with their own message). `--outer` beyond the mesh's loops is
/// a usage error either way.
pub fn dispatch(
    args: &DiskArgs,
    input: &Input,
    read_ms: f64,
    memory: MemoryCheck,
    t_all: Instant,
) -> Option<Result<(), Failure>> {
    let mesh = &input.mesh;
    let loops = mesh.boundary_loops().len();
    if let Some(k) = args.outer.filter(|&k| k >= loops.max(1)) {
        return Some(Err(Failure::Usage(format!(
            "--outer {k}: the mesh has {loops} boundary loop(s), numbered from 0 \
             (`conformap info` lists them)"
        ))));
    }
    matches!(mesh.topology(), Topology::MultiplyConnected { .. })
        .then(|| run(args, input, read_ms, memory, t_all))
}

/// Maps `input` (several boundary loops) onto the unit disk with circular holes and writes
/// the outputs `args` asks for. `read_ms` and `t_all` are the caller's clock.
pub fn run(
    args: &DiskArgs,
    input: &Input,
    read_ms: f64,
    memory: MemoryCheck,
    t_all: Instant,
) -> Result<(), Failure> {
    let mesh = &input.mesh;
    let loops = mesh.boundary_loops().len();
    check_dense_memory(mesh, &memory).map_err(|f| f.in_file(&args.mesh))?;
    let mut options = KoebeOptions::DEFAULT.with_outer(args.outer);
    if let Some(n) = args.max_iter {
        options = options.with_max_sweeps(n);
    }
    if let Some(t) = args.tol {
        options = options.with_tol(t);
    }
    let result = koebe(mesh, &options).map_err(|e| koebe_failure(e).in_file(&args.mesh))?;
    let r = &result.report;
    if args.strict && !r.converged {
        return Err(Failure::Numerical(format!(
            "the disk with circular holes did not converge in {} Koebe sweeps (--strict); \
             nothing written",
            r.sweeps
        )));
    }
    let t = Instant::now();
    let metrics_options = MetricsOptions::DEFAULT.with_outer_loop(r.outer_loop);
    let metrics = planar_map_metrics(mesh, &result.map, &metrics_options)
        .map_err(|e| Failure::Numerical(e.to_string()))?;
    let metrics_ms = ms_since(t);

    let t = Instant::now();
    let uv: Vec<[f64; 2]> = result
        .map
        .iter()
        .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
        .collect();
    let unchanged = input.repairs.as_ref().is_none_or(|log| !log.changed());
    let source = unchanged.then_some(&input.source);
    conformap_io::write_mesh_with_uv(&args.output, mesh, &uv, source)?;
    if let Some(flat) = &args.flat {
        let pts: Vec<[f64; 3]> = result.map.iter().map(|z| [z.re, z.im, 0.0]).collect();
        conformap_io::write_flat(flat, &pts, mesh.faces())?;
    }
    if let (Some(path), Some(log)) = (&args.vertex_map, &input.repairs) {
        crate::commands::disk::write_vertex_map(path, log)?;
    }
    let write_ms = ms_since(t);

    let tm = &r.timings_ms;
    let timings = StageTimings {
        read: read_ms,
        assemble: tm.assemble,
        factor: tm.factor,
        analyse: 0.0,
        solve: tm.total - tm.assemble - tm.factor,
        metrics: metrics_ms,
        write: write_ms,
        total: ms_since(t_all),
    };
    let mut report = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "disk",
        "method": "koebe",
        "input": InputInfo::new(&args.mesh, mesh),
        "solver": solver_json(&result)?,
        "circle_domain": circle_domain_json(&result),
        "metrics": metrics,
        "memory": memory.to_json(),
        "timings_ms": timings,
    });
    if let Some(log) = &input.repairs {
        report["repairs"] = repairs_json(log);
    }
    if let Some(path) = &args.report {
        write_json(path, &report)?;
    }
    if let Some(log) = input.repairs.as_ref().filter(|l| l.changed()) {
        eprintln!(
            "{}: repaired: {}",
            args.mesh.display(),
            log.actions().join("; ")
        );
    }
    eprintln!(
        "{}: {} vertices, {} faces, {loops} boundary loops; disk with circular holes in {} \
         Koebe sweeps{}; worst circle residual {:.1e}, E_C = {:.6e}, mean angle distortion \
         {:.3}°, flipped faces {}{}; {:.0} ms",
        args.mesh.display(),
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
        timings.total
    );
    Ok(())
}

/// The `solver` object: the Koebe report with the schema's common fields.
fn solver_json(result: &CircleDomainMap) -> Result<serde_json::Value, Failure> {
    let r = &result.report;
    let mut v = serde_json::to_value(r)
        .map_err(|e| Failure::Numerical(format!("cannot serialize the report: {e}")))?;
    let energies = r
        .polish
        .as_ref()
        .map_or_else(Vec::new, |p| p.energy_history.clone());
    let residual = result
        .circles
        .iter()
        .fold(0.0f64, |a, c| a.max(c.residual_max));
    v["iterations"] = json!(r.sweeps);
    v["energy_history"] = json!(energies);
    v["residual"] = json!(residual);
    Ok(v)
}

/// The `circle_domain` object: outer loop, normalization, modulus, every loop's circle.
fn circle_domain_json(result: &CircleDomainMap) -> serde_json::Value {
    json!({
        "outer_loop": result.report.outer_loop,
        "reference_hole": result.reference_hole,
        "normalization": "outer loop on the unit circle with its first vertex at angle 0; \
                          the reference hole (lowest loop index) centred at 0",
        "modulus": result.modulus,
        "circles": result.circles,
    })
}

/// Exit codes of the Koebe method's failures: the mesh's topology or a bad `--outer` is bad
/// input (1), the rest numerical (3).
fn koebe_failure(e: KoebeError) -> Failure {
    match e {
        KoebeError::NotGenusZero { .. } => Failure::BadInput(
            e.to_string(),
            Some(
                "`conformap info MESH` shows the topology; a disk map needs genus 0 and at \
                 least one boundary loop"
                    .to_string(),
            ),
        ),
        KoebeError::OuterLoopOutOfRange { .. } | KoebeError::InvalidOption { .. } => {
            Failure::Usage(e.to_string())
        }
        KoebeError::Fill(_) => Failure::BadInput(e.to_string(), None),
        KoebeError::Disk(d) => Failure::from(d),
        other => Failure::Numerical(other.to_string()),
    }
}

/// Refuses the run if the dense Schur complement of every boundary vertex (the polish's,
/// `8 n_B²` bytes) would push the estimated peak above the memory limit.
fn check_dense_memory(mesh: &TriMesh, memory: &MemoryCheck) -> Result<(), Failure> {
    let boundary: usize = mesh.boundary_loops().iter().map(Vec::len).sum();
    let estimate = estimate_peak_bytes(mesh.num_vertices(), mesh.num_edges(), boundary, true);
    match memory.limit {
        Some((limit, from)) if estimate > limit => Err(Failure::BadInput(
            format!(
                "a disk with circular holes of this mesh ({} boundary vertices) needs an \
                 estimated {estimate} bytes at peak, more than the {limit} allowed ({from}); \
                 nothing was computed",
                boundary
            ),
            Some("free memory, or --max-memory SIZE if the estimate is too cautious".to_string()),
        )),
        _ => Ok(()),
    }
}
