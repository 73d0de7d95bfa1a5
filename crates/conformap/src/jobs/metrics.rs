//! `conformap metrics MESH PARAM [--json]`: judge any map of a mesh, planar or on the
//! sphere.

use std::path::PathBuf;

use std::fmt::Write;

use conformap_metrics::{corner_map_metrics, planar_map_metrics, MetricsOptions};
use serde::Serialize;

use crate::failure::Failure;
use crate::jobs::param::{read_measured_map, sphere_points, MeasuredMap, PlanarMap};
use crate::pipeline::Outcome;
use crate::report::{InputInfo, MapQuality, Sorted};

/// The report of `conformap metrics --json` (written with its keys sorted at every depth:
/// [`Sorted`]).
#[derive(Debug, Clone, Serialize)]
#[non_exhaustive]
pub struct MetricsReport {
    /// The version of conformap that wrote it.
    pub conformap_version: &'static str,
    /// Always `metrics`.
    pub command: &'static str,
    /// `sphere` for a sphere map (measured on the sphere); absent for a planar map.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub domain: Option<&'static str>,
    /// The mesh.
    pub input: InputInfo,
    /// The map and where it was read from.
    pub param: MetricsParam,
    /// How good the map is: the planar or the sphere metrics.
    pub metrics: MapQuality,
}

/// The `param` object of a metrics report.
#[derive(Debug, Clone, Serialize)]
pub struct MetricsParam {
    /// Path as given (`<array>` from Python).
    pub path: String,
    /// Which data of the file held the map (`texture coordinates`, …).
    pub map_from: String,
    /// The map's own mesh, when the map file carries one refining the given mesh and the
    /// map was measured on it (absent otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub own_mesh: Option<OwnMesh>,
}

/// The `param.own_mesh` object: the mesh a map was measured on, and the mesh it refines.
#[derive(Debug, Clone, Serialize)]
pub struct OwnMesh {
    /// Its vertex count.
    pub vertices: usize,
    /// Its face count.
    pub faces: usize,
    /// The given mesh it refines.
    pub refines: MeshCounts,
}

/// The vertex and face counts of a mesh.
#[derive(Debug, Clone, Serialize)]
pub struct MeshCounts {
    /// Vertices.
    pub vertices: usize,
    /// Faces.
    pub faces: usize,
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
    /// (x, y) are the map. A sphere map is measured on the sphere: unit-sphere positions
    /// without texture coordinates (`sphere --flat`), or per-vertex texture coordinates of
    /// a closed genus-0 mesh, read as equirectangular (`sphere -o`). A map file that
    /// carries its own mesh refining MESH (`global -o` where it split boundary chords) is
    /// measured on that mesh.
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
        domain: None,
        input: InputInfo::new(mesh_path, mesh),
        param: MetricsParam {
            path: param.to_string(),
            map_from: source.to_string(),
            own_mesh: None,
        },
        metrics: MapQuality::Planar(metrics),
    })
}

/// The JSON of `conformap metrics --json` for the sphere map `points` of `mesh`: the
/// metrics of [`conformap_sphere::sphere_metrics`] (angles against the chord triangles,
/// flips by orientation against the outward normal, area shares), `"domain": "sphere"`.
///
/// # Errors
/// [`Failure::BadInput`] when the map does not fit the mesh (without the param's path).
pub fn sphere_metrics_report(
    mesh: &conformap_mesh::TriMesh,
    mesh_path: &std::path::Path,
    points: &[[f64; 3]],
    param: &str,
    source: &str,
) -> Result<MetricsReport, Failure> {
    let metrics = conformap_sphere::sphere_metrics(mesh, points).map_err(Failure::input)?;
    Ok(MetricsReport {
        conformap_version: env!("CARGO_PKG_VERSION"),
        command: "metrics",
        domain: Some("sphere"),
        input: InputInfo::new(mesh_path, mesh),
        param: MetricsParam {
            path: param.to_string(),
            map_from: source.to_string(),
            own_mesh: None,
        },
        metrics: MapQuality::Sphere(metrics),
    })
}

/// The keys of the text output, planar and sphere, in order.
const PLANAR_KEYS: [&str; 9] = [
    "conformal_energy",
    "dirichlet_energy",
    "image_area",
    "flipped_faces",
    "degenerate_faces",
    "circle_residual_max",
    "angle_distortion_deg",
    "beltrami_abs",
    "area_distortion_log",
];
const SPHERE_KEYS: [&str; 8] = [
    "radius_residual_max",
    "flipped_faces",
    "degenerate_faces",
    "uniformity_energy",
    "angle_distortion_deg",
    "beltrami_abs",
    "area_distortion_log",
    "cross_ratio_log",
];

/// Runs `conformap metrics`: the metrics as text or JSON, for stdout.
fn run(args: &MetricsJob) -> Result<Outcome, Failure> {
    let loaded = conformap_io::read_mesh(&args.mesh)?;
    let measured = read_measured_map(&args.param, &args.mesh, &loaded.mesh)?;
    let mesh = measured.mesh(&loaded.mesh);
    let param = args.param.display().to_string();
    let (mut report, source, keys) = match sphere_points(&measured.file, mesh) {
        Some((points, source)) => (
            sphere_metrics_report(mesh, &args.mesh, &points, &param, source),
            source,
            &SPHERE_KEYS[..],
        ),
        None => {
            let (map, source) = measured.file.planar_map();
            (
                metrics_report(mesh, &args.mesh, &map, &param, source),
                source,
                &PLANAR_KEYS[..],
            )
        }
    };
    if let Ok(r) = &mut report {
        r.param.own_mesh = own_mesh_note(&measured, &loaded.mesh);
    }
    let report = report.map_err(|f| f.in_file(&args.param))?;
    // the report as a value with its keys sorted at every depth (as it is written)
    let value = serde_json::to_value(Sorted(&report)).unwrap_or_default();
    let out = if args.json {
        serde_json::to_string_pretty(&value).unwrap_or_default()
    } else {
        text(args, &value, source, keys)
    };
    Ok(Outcome {
        stdout: Some(out),
        ..Outcome::default()
    })
}

/// The report's `param.own_mesh` when the map was measured on its own mesh.
fn own_mesh_note(measured: &MeasuredMap, given: &conformap_mesh::TriMesh) -> Option<OwnMesh> {
    let own = measured.own_mesh.as_ref()?;
    Some(OwnMesh {
        vertices: own.num_vertices(),
        faces: own.num_faces(),
        refines: MeshCounts {
            vertices: given.num_vertices(),
            faces: given.num_faces(),
        },
    })
}

/// The text output: what was measured, then one line per key.
fn text(args: &MetricsJob, value: &serde_json::Value, source: &str, keys: &[&str]) -> String {
    let mut out = String::new();
    let mut say = |line: String| {
        let _ = writeln!(out, "{line}");
    };
    let domain = if value["domain"] == "sphere" {
        "sphere map"
    } else {
        "map"
    };
    say(format!(
        "{domain} of {} from {} ({source})",
        args.mesh.display(),
        args.param.display()
    ));
    let own = &value["param"]["own_mesh"];
    if !own.is_null() {
        say(format!(
            "measured on the map's own mesh: {} vertices, {} faces (refining the {} and {} \
             of {})",
            own["vertices"],
            own["faces"],
            own["refines"]["vertices"],
            own["refines"]["faces"],
            args.mesh.display()
        ));
    }
    let m = &value["metrics"];
    for key in keys {
        say(format!("{key:22} {}", m[*key]));
    }
    out.pop();
    out
}
