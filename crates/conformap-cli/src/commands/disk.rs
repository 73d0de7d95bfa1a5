//! `conformap disk MESH -o OUT ...`: conformal map onto the unit disk.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use conformap_disk::{cem, harmonic_arc_length, CemOptions, DiskProblem, CEM_MAX_ITER, CEM_TOL};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use serde_json::json;

use crate::commands::write_json;
use crate::failure::Failure;
use crate::report::{ms_since, InputInfo, StageTimings};

/// The disk-map method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// CEM (Yueh et al. 2017): Angenent initial map and boundary iteration.
    Cem,
    /// Harmonic map to an arc-length circle (baseline; no boundary optimization).
    Harmonic,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Self::Cem => "cem",
            Self::Harmonic => "harmonic",
        }
    }
}

/// Arguments of `conformap disk`.
#[derive(Debug, Args)]
pub struct DiskArgs {
    /// The mesh (.obj, .gltf, .glb): one boundary loop, genus 0.
    pub mesh: PathBuf,
    /// Output mesh with texture coordinates vt = ((u+1)/2, (v+1)/2) (.obj, .gltf, .glb).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Method.
    #[arg(long, value_enum, default_value_t = Method::Cem)]
    pub method: Method,
    /// Iteration cap (CEM default 20, as in the papers).
    #[arg(long)]
    pub max_iter: Option<usize>,
    /// Relative energy tolerance (default 1e-6).
    #[arg(long)]
    pub tol: Option<f64>,
    /// Also write the raw map as a flat mesh (u, v, 0).
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Exit with code 3 (writing nothing) if the solver did not converge.
    #[arg(long)]
    pub strict: bool,
}

/// Runs `conformap disk`.
pub fn run(args: &DiskArgs) -> Result<(), Failure> {
    let t_all = Instant::now();
    if let Some(tol) = args.tol {
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(Failure::Usage(format!(
                "--tol must be a finite number ≥ 0, got {tol}"
            )));
        }
    }
    for out in std::iter::once(&args.output).chain(args.flat.iter()) {
        conformap_io::Format::from_path(out).map_err(|e| Failure::Usage(e.to_string()))?;
    }
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let read_ms = ms_since(t);

    let in_file = |e: conformap_disk::DiskError| Failure::from(e).in_file(&args.mesh);
    let mut problem = DiskProblem::new(mesh).map_err(in_file)?;
    let result = match args.method {
        Method::Harmonic => harmonic_arc_length(&problem),
        Method::Cem => {
            let options = CemOptions::DEFAULT
                .with_max_iter(args.max_iter.unwrap_or(CEM_MAX_ITER))
                .with_tol(args.tol.unwrap_or(CEM_TOL));
            cem(&mut problem, &options).map_err(in_file)?
        }
    };
    if args.strict && !result.report.converged {
        return Err(Failure::Numerical(format!(
            "{} did not converge in {} iterations (--strict); nothing written",
            args.method.name(),
            result.report.iterations
        )));
    }
    let t = Instant::now();
    let metrics = planar_map_metrics(mesh, &result.map, &MetricsOptions::default())
        .map_err(|e| Failure::Numerical(e.to_string()))?;
    let metrics_ms = ms_since(t);

    let t = Instant::now();
    let uv: Vec<[f64; 2]> = result
        .map
        .iter()
        .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
        .collect();
    conformap_io::write_mesh_with_uv(&args.output, mesh, &uv, Some(&loaded.source))?;
    if let Some(flat) = &args.flat {
        let pts: Vec<[f64; 3]> = result.map.iter().map(|z| [z.re, z.im, 0.0]).collect();
        conformap_io::write_flat(flat, &pts, mesh.faces())?;
    }
    let write_ms = ms_since(t);

    let s = &result.report;
    let timings = StageTimings {
        read: read_ms,
        assemble: s.timings_ms.assemble,
        factor: s.timings_ms.factor,
        solve: s.timings_ms.solve,
        metrics: metrics_ms,
        write: write_ms,
        total: ms_since(t_all),
    };
    let report = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "disk",
        "method": args.method.name(),
        "input": InputInfo::new(&args.mesh, mesh),
        "solver": s,
        "metrics": metrics,
        "timings_ms": timings,
    });
    if let Some(path) = &args.report {
        write_json(path, &report)?;
    }
    eprintln!(
        "{}: {} vertices, {} faces; {} in {} iterations{}; E_C = {:.6e}, mean angle distortion \
         {:.3}°, flipped faces {}; {:.0} ms",
        args.mesh.display(),
        mesh.num_vertices(),
        mesh.num_faces(),
        args.method.name(),
        s.iterations,
        if s.converged { " (converged)" } else { "" },
        metrics.conformal_energy,
        metrics.angle_distortion_deg.mean,
        metrics.flipped_faces,
        timings.total
    );
    Ok(())
}
