//! `conformap metrics MESH PARAM [--json]`: judge any planar map of a mesh.

use std::path::PathBuf;

use clap::Args;
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use num_complex::Complex64;
use serde_json::json;

use crate::commands::say;
use crate::failure::Failure;
use crate::report::InputInfo;

/// Arguments of `conformap metrics`.
#[derive(Debug, Args)]
pub struct MetricsArgs {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (read as
    /// u = 2·vt_x − 1, v = 2·vt_y − 1, the inverse of what `disk` writes), or a flat mesh
    /// without texture coordinates whose (x, y) are the map.
    pub param: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `conformap metrics`.
pub fn run(args: &MetricsArgs) -> Result<(), Failure> {
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let param = crate::commands::read_map_file(&args.param, &args.mesh, mesh)?;
    let (map, source): (Vec<Complex64>, &str) = match &param.uv {
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
    let metrics = planar_map_metrics(mesh, &map, &MetricsOptions::default())
        .map_err(|e| Failure::input(format!("{}: {e}", args.param.display())))?;
    let value = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "metrics",
        "input": InputInfo::new(&args.mesh, mesh),
        "param": { "path": args.param.display().to_string(), "map_from": source },
        "metrics": metrics,
    });
    if args.json {
        say(&serde_json::to_string_pretty(&value).unwrap_or_default());
    } else {
        let m = &value["metrics"];
        say(&format!(
            "map of {} from {} ({source})",
            args.mesh.display(),
            args.param.display()
        ));
        for key in [
            "conformal_energy",
            "dirichlet_energy",
            "image_area",
            "flipped_faces",
            "degenerate_faces",
            "circle_residual_max",
        ] {
            say(&format!("{key:22} {}", m[key]));
        }
        say(&format!(
            "{:22} {}",
            "angle_distortion_deg", m["angle_distortion_deg"]
        ));
        say(&format!("{:22} {}", "beltrami_abs", m["beltrami_abs"]));
        say(&format!(
            "{:22} {}",
            "area_distortion_log", m["area_distortion_log"]
        ));
    }
    Ok(())
}
