//! `conformap metrics MESH PARAM [--json]`: judge any planar map of a mesh.

use std::path::PathBuf;

use std::fmt::Write;

use conformap_metrics::{corner_map_metrics, planar_map_metrics, MetricsOptions};
use serde_json::json;

use crate::failure::Failure;
use crate::jobs::param::{read_map_file, PlanarMap};
use crate::pipeline::Outcome;
use crate::report::InputInfo;

/// Arguments of `conformap metrics`.
#[non_exhaustive]
#[derive(Debug)]
pub struct MetricsJob {
    /// The 3D mesh.
    pub mesh: PathBuf,
    /// The map: an OBJ/glTF with one texture coordinate per vertex (read as
    /// u = 2·vt_x − 1, v = 2·vt_y − 1, the inverse of what `disk` writes), a seamed map
    /// with texture coordinates per face corner (`f v/vt`, as `global` writes; read as
    /// (u, v) = vt, no circle fits), or a flat mesh without texture coordinates whose
    /// (x, y) are the map.
    pub param: PathBuf,
    /// Print JSON instead of text.
    pub json: bool,
}

impl MetricsJob {
    /// Runs the job.
    ///
    /// # Errors
    /// A [`Failure`] with its exit class and hint; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        run(self)
    }
    /// The metrics of the map `param` of `mesh`, as text.
    pub fn new(mesh: impl Into<PathBuf>, param: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            param: param.into(),
            json: false,
        }
    }

    /// As JSON (`json`) or as text.
    pub fn with_json(mut self, json: bool) -> Self {
        self.json = json;
        self
    }
}

/// The JSON of `conformap metrics --json` for the map `map` of `mesh` (read from
/// `mesh_path`), taken from `param` (its `source`: `texture coordinates`, …); the Python
/// package calls it on arrays.
///
/// # Errors
/// [`Failure::BadInput`] when the map does not fit the mesh (without the param's path).
pub fn metrics_report(
    mesh: &conformap_mesh::TriMesh,
    mesh_path: &std::path::Path,
    map: &PlanarMap,
    param: &str,
    source: &str,
) -> Result<serde_json::Value, Failure> {
    let metrics = match map {
        PlanarMap::PerVertex(map) => planar_map_metrics(mesh, map, &MetricsOptions::default()),
        PlanarMap::PerCorner(map) => corner_map_metrics(mesh, map, &MetricsOptions::default()),
    }
    .map_err(Failure::input)?;
    Ok(json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "metrics",
        "input": InputInfo::new(mesh_path, mesh),
        "param": { "path": param, "map_from": source },
        "metrics": metrics,
    }))
}

/// Runs `conformap metrics`: the metrics as text or JSON, for stdout.
fn run(args: &MetricsJob) -> Result<Outcome, Failure> {
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let param = read_map_file(&args.param, &args.mesh, mesh)?;
    let (map, source) = param.planar_map();
    let value = metrics_report(
        mesh,
        &args.mesh,
        &map,
        &args.param.display().to_string(),
        source,
    )
    .map_err(|f| f.in_file(&args.param))?;
    let mut out = String::new();
    if args.json {
        out = serde_json::to_string_pretty(&value).unwrap_or_default();
    } else {
        let m = &value["metrics"];
        let mut say = |line: String| {
            let _ = writeln!(out, "{line}");
        };
        say(format!(
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
            say(format!("{key:22} {}", m[key]));
        }
        say(format!(
            "{:22} {}",
            "angle_distortion_deg", m["angle_distortion_deg"]
        ));
        say(format!("{:22} {}", "beltrami_abs", m["beltrami_abs"]));
        say(format!(
            "{:22} {}",
            "area_distortion_log", m["area_distortion_log"]
        ));
        out.pop();
    }
    Ok(Outcome {
        stdout: Some(out),
        ..Outcome::default()
    })
}
