//! `conformap sphere MESH -o OUT ...`: conformal map of a closed genus-0 mesh onto the unit
//! sphere.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use conformap_global::{
    equirectangular_uv, optimize_sphere_mobius, sphere_map, sphere_metrics, GlobalError,
    MobiusObjective, MobiusOptions, SphereOptions,
};
use serde_json::json;

use crate::commands::write_json;
use crate::failure::Failure;
use crate::report::{ms_since, InputInfo, StageTimings};

/// The Möbius normalization applied to the sphere map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SphereMobius {
    /// None: the map as computed (source of Angenent's dipole near the north pole).
    None,
    /// The Möbius map minimizing the uniformity energy (Jin et al. 2004, §3.4).
    Uniform,
}

/// Arguments of `conformap sphere`.
#[derive(Debug, Args)]
pub struct SphereArgs {
    /// The mesh (.obj, .gltf, .glb): closed, connected, genus 0.
    pub mesh: PathBuf,
    /// Output mesh: the input's 3D positions with texture coordinates by the equirectangular
    /// projection of the sphere point, u = (atan2(y, x) + π)/2π, v = (asin z + π/2)/π
    /// (.obj, .gltf, .glb). Faces straddling the meridian u = 0 ≡ 1 wrap in the texture.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Möbius normalization of the map.
    #[arg(long, value_enum, default_value_t = SphereMobius::None)]
    pub mobius: SphereMobius,
    /// Also write the unit-sphere points with the input faces.
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Exit with code 3 (writing nothing) if any triangle is inverted on the sphere.
    #[arg(long)]
    pub strict: bool,
}

/// A library error as a command failure: wrong topology, bad options and bad given maps or
/// regions are bad input (exit 1), everything else numerical (exit 3); `path` names the file.
pub fn global_failure(e: GlobalError, path: &Path) -> Failure {
    let hint = match &e {
        GlobalError::WrongTopology { .. } => Some(
            "`conformap info MESH` shows the topology: a sphere map needs a closed, connected \
             genus-0 mesh, a disk map one boundary loop"
                .to_string(),
        ),
        _ => None,
    };
    let p = path.display();
    match e {
        GlobalError::WrongTopology { .. }
        | GlobalError::MapLength { .. }
        | GlobalError::NonFiniteMap { .. }
        | GlobalError::NotOnSphere { .. }
        | GlobalError::NotInDisk { .. }
        | GlobalError::RegionFaceOutOfRange { .. }
        | GlobalError::DegenerateRegion { .. }
        | GlobalError::InvalidOption { .. } => Failure::BadInput(format!("{p}: {e}"), hint),
        other => Failure::Numerical(format!("{p}: {other}")),
    }
}

/// Runs `conformap sphere`.
pub fn run(args: &SphereArgs) -> Result<(), Failure> {
    let t_all = Instant::now();
    for out in std::iter::once(&args.output).chain(args.flat.iter()) {
        conformap_io::Format::from_path(out).map_err(|e| Failure::Usage(e.to_string()))?;
    }
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let read_ms = ms_since(t);

    let fail = |e| global_failure(e, &args.mesh);
    let map = sphere_map(mesh, &SphereOptions::DEFAULT).map_err(fail)?;
    let t = Instant::now();
    let before = sphere_metrics(mesh, &map.points).map_err(fail)?;
    let mut metrics_ms = ms_since(t);
    let (points, mobius_report, after, mobius_ms) = match args.mobius {
        SphereMobius::None => (map.points.clone(), None, before.clone(), 0.0),
        SphereMobius::Uniform => {
            let t = Instant::now();
            let best = optimize_sphere_mobius(
                mesh,
                &map.points,
                &MobiusObjective::Uniform,
                &MobiusOptions::DEFAULT,
            )
            .map_err(fail)?;
            let mobius_ms = ms_since(t);
            let t = Instant::now();
            let after = sphere_metrics(mesh, &best.points).map_err(fail)?;
            metrics_ms += ms_since(t);
            (best.points, Some(best.report), after, mobius_ms)
        }
    };
    if args.strict && after.flipped_faces > 0 {
        return Err(Failure::Numerical(format!(
            "{}: {} triangles are inverted on the sphere (--strict); nothing written",
            args.mesh.display(),
            after.flipped_faces
        )));
    }

    let t = Instant::now();
    let uv: Vec<[f64; 2]> = points.iter().map(|&p| equirectangular_uv(p)).collect();
    conformap_io::write_mesh_with_uv(&args.output, mesh, &uv, Some(&loaded.source))?;
    if let Some(flat) = &args.flat {
        conformap_io::write_flat(flat, &points, mesh.faces())?;
    }
    let write_ms = ms_since(t);

    let s = &map.report;
    let timings = StageTimings {
        read: read_ms,
        assemble: s.timings_ms.assemble,
        factor: s.timings_ms.factor,
        analyse: 0.0,
        solve: s.timings_ms.solve + mobius_ms,
        metrics: metrics_ms,
        write: write_ms,
        total: ms_since(t_all),
    };
    let method = match args.mobius {
        SphereMobius::None => s.method.clone(),
        SphereMobius::Uniform => format!("{}+mobius-uniform", s.method),
    };
    let mut metrics = serde_json::to_value(&after).unwrap_or_default();
    if let (Some(obj), Some(m)) = (metrics.as_object_mut(), &mobius_report) {
        obj.insert(
            "uniformity_energy_before_mobius".into(),
            json!(m.uniformity_before),
        );
        obj.insert(
            "angle_distortion_deg_before_mobius".into(),
            serde_json::to_value(before.angle_distortion_deg).unwrap_or_default(),
        );
    }
    let report = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "sphere",
        "method": method,
        "input": InputInfo::new(&args.mesh, mesh),
        "solver": {
            "iterations": s.stages.len() - 1,
            "converged": true,
            "energy_history": s.stages.iter().map(|r| r.mean_angle_distortion_deg).collect::<Vec<_>>(),
            "energy_history_is": "mean chord-angle distortion (degrees) after each stage",
            "residual": s.residual,
            "sphere": s,
            "mobius": mobius_report,
        },
        "metrics": metrics,
        "timings_ms": timings,
    });
    if let Some(path) = &args.report {
        write_json(path, &report)?;
    }
    eprintln!(
        "{}: {} vertices, {} faces; sphere map with {} correction(s){}; mean angle distortion \
         {:.3}°, inverted faces {}, uniformity energy {:.3e}; {:.0} ms",
        args.mesh.display(),
        mesh.num_vertices(),
        mesh.num_faces(),
        s.corrections,
        if args.mobius == SphereMobius::Uniform {
            " and uniform Möbius normalization"
        } else {
            ""
        },
        after.angle_distortion_deg.mean,
        after.flipped_faces,
        after.uniformity_energy,
        timings.total
    );
    Ok(())
}
