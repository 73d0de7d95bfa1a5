//! `conformap mobius MESH PARAM --domain disk|sphere --objective uniform|emphasize ...`: the
//! optimal Möbius transformation of a disk or sphere map.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use conformap_global::{
    equirectangular_uv, optimize_disk_mobius, optimize_sphere_mobius,
    planar_cross_ratio_distortion, sphere_metrics, MobiusObjective, MobiusOptions,
    EMPHASIZE_MAX_AREA_SCALE, MAP_RADIUS_TOL,
};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use num_complex::Complex64;
use serde_json::json;

use crate::commands::sphere::global_failure;
use crate::commands::write_json;
use crate::failure::Failure;
use crate::report::{ms_since, InputInfo, StageTimings};

/// The domain of the map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Domain {
    /// A planar map in the unit disk; Möbius maps `(az + b)/(b̄z + ā)`.
    Disk,
    /// A map onto the unit sphere; Möbius maps `(az + b)/(cz + d)` through stereographic
    /// projection.
    Sphere,
}

/// The energy to optimize.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Objective {
    /// Minimize the uniformity energy Σ (image area share − surface area share)².
    Uniform,
    /// Maximize the image-area share of the faces in --region (with --max-area-scale).
    Emphasize,
    /// Maximize the mean log area magnification of the faces in --region (no cap needed).
    EmphasizeDensity,
}

/// Arguments of `conformap mobius`.
#[derive(Debug, Args)]
pub struct MobiusArgs {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map. Disk: texture coordinates (u = 2·vt_x − 1, v = 2·vt_y − 1, as `disk` writes)
    /// or a flat mesh whose (x, y) are the map. Sphere: a mesh whose positions are the
    /// unit-sphere points (`sphere --flat`), or else equirectangular texture coordinates
    /// (as `sphere -o` writes).
    pub param: PathBuf,
    /// Domain of the map.
    #[arg(long, value_enum)]
    pub domain: Domain,
    /// Energy to optimize.
    #[arg(long, value_enum)]
    pub objective: Objective,
    /// Faces to emphasize: a text file with one 0-based face index per line (blank lines and
    /// lines starting with # are skipped). Required with --objective emphasize.
    #[arg(long)]
    pub region: Option<PathBuf>,
    /// Largest area magnification the emphasizing Möbius map may apply (> 1; only for
    /// --objective emphasize): the share of an emphasized region has no maximum, it tends to
    /// 100 % as the map degenerates.
    #[arg(long, default_value_t = EMPHASIZE_MAX_AREA_SCALE)]
    pub max_area_scale: f64,
    /// Output mesh with the moved map as texture coordinates (disk: ((u+1)/2, (v+1)/2);
    /// sphere: equirectangular, as `sphere` writes).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write the moved map as a flat mesh ((u, v, 0), or the sphere points).
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// Reads a region file: one face index per line.
fn read_region(path: &Path, faces: usize) -> Result<Vec<usize>, Failure> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| Failure::input(format!("cannot read {}: {e}", path.display())))?;
    let mut region = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let f: usize = t.parse().map_err(|_| {
            Failure::BadInput(
                format!(
                    "{} line {}: {t:?} is not a face index",
                    path.display(),
                    k + 1
                ),
                Some("one 0-based face index per line; # starts a comment line".to_string()),
            )
        })?;
        if f >= faces {
            return Err(Failure::BadInput(
                format!(
                    "{} line {}: face {f} is out of range (the mesh has {faces} faces, 0..{})",
                    path.display(),
                    k + 1,
                    faces.saturating_sub(1)
                ),
                Some("face indices are 0-based, in the order of the mesh file".to_string()),
            ));
        }
        region.push(f);
    }
    Ok(region)
}

/// Inverse of [`equirectangular_uv`].
fn from_equirectangular(uv: [f64; 2]) -> [f64; 3] {
    let lon = std::f64::consts::TAU * uv[0] - std::f64::consts::PI;
    let lat = std::f64::consts::PI * uv[1] - std::f64::consts::FRAC_PI_2;
    [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()]
}

/// Runs `conformap mobius`.
pub fn run(args: &MobiusArgs) -> Result<(), Failure> {
    let t_all = Instant::now();
    for out in std::iter::once(&args.output).chain(args.flat.iter()) {
        conformap_io::Format::from_path(out).map_err(|e| Failure::Usage(e.to_string()))?;
    }
    match (args.objective, &args.region) {
        (Objective::Emphasize | Objective::EmphasizeDensity, None) => {
            return Err(Failure::Usage(
                "--objective emphasize needs --region FACES.txt".to_string(),
            ))
        }
        (Objective::Uniform, Some(_)) => {
            return Err(Failure::Usage(
                "--region is only used with --objective emphasize or emphasize-density".to_string(),
            ))
        }
        _ => {}
    }
    if !(args.max_area_scale > 1.0 && args.max_area_scale.is_finite()) {
        return Err(Failure::Usage(format!(
            "--max-area-scale must be a finite number > 1, got {}",
            args.max_area_scale
        )));
    }
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    // connectivity checked, geometry not; non-finite values are refused by the
    // optimization, which names the vertex
    let param = crate::commands::read_map_file(&args.param, &args.mesh, mesh)?;
    let objective = match (&args.objective, &args.region) {
        (Objective::Emphasize, Some(path)) => MobiusObjective::Emphasize {
            region: read_region(path, mesh.num_faces())?,
        },
        (Objective::EmphasizeDensity, Some(path)) => MobiusObjective::EmphasizeDensity {
            region: read_region(path, mesh.num_faces())?,
        },
        _ => MobiusObjective::Uniform,
    };
    let read_ms = ms_since(t);
    let options = MobiusOptions::DEFAULT.with_max_area_scale(args.max_area_scale);
    let fail = |e| global_failure(e, &args.param);

    let (uv, flat, mobius, metrics, metrics_ms, map_from) = match args.domain {
        Domain::Disk => {
            let (map, from): (Vec<Complex64>, &str) = match &param.uv {
                Some(uv) => (
                    uv.iter()
                        .map(|t| Complex64::new(2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0))
                        .collect(),
                    "texture coordinates",
                ),
                None => (
                    param
                        .positions
                        .iter()
                        .map(|p| Complex64::new(p[0], p[1]))
                        .collect(),
                    "flat positions",
                ),
            };
            let best = optimize_disk_mobius(mesh, &map, &objective, &options).map_err(fail)?;
            let t = Instant::now();
            let before = planar_map_metrics(mesh, &map, &MetricsOptions::default())
                .map_err(|e| Failure::input(format!("{}: {e}", args.param.display())))?;
            let after = planar_map_metrics(mesh, &best.map, &MetricsOptions::default())
                .map_err(|e| Failure::Numerical(e.to_string()))?;
            let cr = (
                planar_cross_ratio_distortion(mesh, &map).map_err(fail)?,
                planar_cross_ratio_distortion(mesh, &best.map).map_err(fail)?,
            );
            let mut m = serde_json::to_value(&after).unwrap_or_default();
            if let Some(obj) = m.as_object_mut() {
                obj.insert(
                    "uniformity_energy".into(),
                    json!(best.report.uniformity_after),
                );
                obj.insert(
                    "uniformity_energy_before".into(),
                    json!(best.report.uniformity_before),
                );
                obj.insert(
                    "angle_distortion_deg_before".into(),
                    serde_json::to_value(before.angle_distortion_deg).unwrap_or_default(),
                );
                obj.insert(
                    "cross_ratio_log".into(),
                    serde_json::to_value(cr.1).unwrap_or_default(),
                );
                obj.insert(
                    "cross_ratio_log_before".into(),
                    serde_json::to_value(cr.0).unwrap_or_default(),
                );
            }
            let metrics_ms = ms_since(t);
            let uv: Vec<[f64; 2]> = best
                .map
                .iter()
                .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
                .collect();
            let flat: Vec<[f64; 3]> = best.map.iter().map(|z| [z.re, z.im, 0.0]).collect();
            (uv, flat, best.report, m, metrics_ms, from)
        }
        Domain::Sphere => {
            let on_sphere = param.positions.iter().all(|p| {
                ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() <= MAP_RADIUS_TOL
            });
            let (points, from): (Vec<[f64; 3]>, &str) = match (&param.uv, on_sphere) {
                (_, true) => (param.positions.clone(), "sphere positions"),
                (Some(uv), false) => (
                    uv.iter().map(|&t| from_equirectangular(t)).collect(),
                    "equirectangular texture coordinates",
                ),
                (None, false) => {
                    return Err(Failure::input(format!(
                        "{}: neither are its positions on the unit sphere nor has it texture \
                         coordinates: pass the --flat or -o output of `conformap sphere`",
                        args.param.display()
                    )))
                }
            };
            let best = optimize_sphere_mobius(mesh, &points, &objective, &options).map_err(fail)?;
            let t = Instant::now();
            let before = sphere_metrics(mesh, &points).map_err(fail)?;
            let after = sphere_metrics(mesh, &best.points).map_err(fail)?;
            let mut m = serde_json::to_value(&after).unwrap_or_default();
            if let Some(obj) = m.as_object_mut() {
                obj.insert(
                    "uniformity_energy_before".into(),
                    json!(before.uniformity_energy),
                );
                obj.insert(
                    "angle_distortion_deg_before".into(),
                    serde_json::to_value(before.angle_distortion_deg).unwrap_or_default(),
                );
                obj.insert(
                    "cross_ratio_log_before".into(),
                    serde_json::to_value(before.cross_ratio_log).unwrap_or_default(),
                );
            }
            let metrics_ms = ms_since(t);
            let uv = best.points.iter().map(|&p| equirectangular_uv(p)).collect();
            (uv, best.points, best.report, m, metrics_ms, from)
        }
    };

    let t = Instant::now();
    conformap_io::write_mesh_with_uv(&args.output, mesh, &uv, Some(&loaded.source))?;
    if let Some(path) = &args.flat {
        conformap_io::write_flat(path, &flat, mesh.faces())?;
    }
    let write_ms = ms_since(t);
    let timings = StageTimings {
        read: read_ms,
        assemble: 0.0,
        factor: 0.0,
        analyse: 0.0,
        solve: mobius.time_ms,
        metrics: metrics_ms,
        write: write_ms,
        total: ms_since(t_all),
    };
    let best = &mobius.starts[mobius.best_start.min(mobius.starts.len().saturating_sub(1))];
    let report = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "mobius",
        "method": format!("newton-{}", mobius.objective),
        "input": InputInfo::new(&args.mesh, mesh),
        "param": { "path": args.param.display().to_string(), "map_from": map_from },
        "solver": {
            "iterations": best.iterations,
            "converged": mobius.converged,
            "energy_history": mobius.starts.iter().map(|s| s.energy).collect::<Vec<_>>(),
            "energy_history_is": "the objective at the optimum of each start",
            "residual": 0.0,
            "mobius": &mobius,
        },
        "metrics": metrics,
        "timings_ms": timings,
    });
    if let Some(path) = &args.report {
        write_json(path, &report)?;
    }
    let cap = if args.objective == Objective::Emphasize {
        format!(
            ", area magnification cap {}{}",
            args.max_area_scale,
            if mobius.cap_active { ", reached" } else { "" }
        )
    } else {
        String::new()
    };
    let what = match (mobius.region_share_before, mobius.region_share_after) {
        (Some(b), Some(a)) => format!(
            "emphasized region's image share {:.2} % → {:.2} % (surface share {:.2} %{cap})",
            100.0 * b,
            100.0 * a,
            100.0 * mobius.region_surface_share.unwrap_or(0.0),
        ),
        _ => format!(
            "uniformity energy {:.4e} → {:.4e}",
            mobius.uniformity_before, mobius.uniformity_after
        ),
    };
    let limited = match mobius.flip_limited {
        Some(t) => format!(
            " (boost shortened to {t:.3} of the optimum: a longer one inverts crowded faces)"
        ),
        None => String::new(),
    };
    eprintln!(
        "{}: optimal {} Möbius map: {what}{limited}; {:.0} ms",
        args.mesh.display(),
        mobius.domain,
        timings.total
    );
    Ok(())
}
