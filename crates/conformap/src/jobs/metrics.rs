//! `conformap metrics MESH PARAM [--json]`: judge any planar map of a mesh.

use std::path::PathBuf;

use std::fmt::Write;

use conformap_metrics::{corner_map_metrics, planar_map_metrics, MapMetrics, MetricsOptions};
use serde::Serialize;

use crate::failure::Failure;
use crate::jobs::param::{read_map_file, PlanarMap};
use crate::pipeline::Outcome;
use crate::report::{InputInfo, Sorted};

/// The report of `conformap metrics --json` (written with its keys sorted at every depth:
/// [`Sorted`]).
#[derive(Debug, Clone, Serialize)]
#[non_exhaustive]
pub struct MetricsReport {
    /// The version of conformap that wrote it.
    pub conformap_version: &'static str,
    /// Always `metrics`.
    pub command: &'static str,
    /// The mesh.
    pub input: InputInfo,
    /// The map and where it was read from.
    pub param: MetricsParam,
    /// How good the map is.
    pub metrics: MapMetrics,
}

/// The `param` object of a metrics report.
#[derive(Debug, Clone, Serialize)]
pub struct MetricsParam {
    /// Path as given (`<array>` from Python).
    pub path: String,
    /// Which data of the file held the map (`texture coordinates`, …).
    pub map_from: String,
}

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
) -> Result<MetricsReport, Failure> {
    let metrics = match map {
        PlanarMap::PerVertex(map) => planar_map_metrics(mesh, map, &MetricsOptions::default()),
        PlanarMap::PerCorner(map) => corner_map_metrics(mesh, map, &MetricsOptions::default()),
    }
    .map_err(Failure::input)?;
    Ok(MetricsReport {
        conformap_version: env!("CARGO_PKG_VERSION"),
        command: "metrics",
        input: InputInfo::new(mesh_path, mesh),
        param: MetricsParam {
            path: param.to_string(),
            map_from: source.to_string(),
        },
        metrics,
    })
}

/// Runs `conformap metrics`: the metrics as text or JSON, for stdout.
fn run(args: &MetricsJob) -> Result<Outcome, Failure> {
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let mesh = &loaded.mesh;
    let param = read_map_file(&args.param, &args.mesh, mesh)?;
    let (map, source) = param.planar_map();
    let report = metrics_report(
        mesh,
        &args.mesh,
        &map,
        &args.param.display().to_string(),
        source,
    )
    .map_err(|f| f.in_file(&args.param))?;
    let mut out = String::new();
    if args.json {
        out = serde_json::to_string_pretty(&Sorted(&report)).unwrap_or_default();
    } else {
        let m = &report.metrics;
        let mut say = |line: String| {
            let _ = writeln!(out, "{line}");
        };
        say(format!(
            "map of {} from {} ({source})",
            args.mesh.display(),
            args.param.display()
        ));
        let numbers = [
            ("conformal_energy", json_text(&m.conformal_energy)),
            ("dirichlet_energy", json_text(&m.dirichlet_energy)),
            ("image_area", json_text(&m.image_area)),
            ("flipped_faces", json_text(&m.flipped_faces)),
            ("degenerate_faces", json_text(&m.degenerate_faces)),
            ("circle_residual_max", json_text(&m.circle_residual_max)),
            ("angle_distortion_deg", json_text(&m.angle_distortion_deg)),
            ("beltrami_abs", json_text(&m.beltrami_abs)),
            ("area_distortion_log", json_text(&m.area_distortion_log)),
        ];
        for (key, value) in numbers {
            say(format!("{key:22} {value}"));
        }
        out.pop();
    }
    Ok(Outcome {
        stdout: Some(out),
        ..Outcome::default()
    })
}

/// `value` as compact JSON with sorted keys (the text output shows the statistics so).
fn json_text(value: &impl Serialize) -> String {
    serde_json::to_string(&Sorted(value)).unwrap_or_default()
}
