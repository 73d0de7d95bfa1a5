//! `conformap info MESH [--json]`: topology and validity of a mesh.

use std::path::PathBuf;

use conformap_io::RawMesh;
use conformap_mesh::{repair, RepairOptions, TriMesh};
use conformap_operators::{mesh_quality, surface_area};
use serde_json::json;

use std::fmt::Write;

use crate::failure::{repair_failure, Failure};
use crate::pipeline::{repair_input, Outcome};
use crate::report::{to_value, RepairsReport};

/// Arguments of `conformap info`.
#[non_exhaustive]
#[derive(Debug)]
pub struct InfoJob {
    /// The mesh (.obj, .gltf, .glb).
    pub mesh: PathBuf,
    /// Print JSON instead of text.
    pub json: bool,
    /// Describe the mesh as `disk --repair` would map it (after the repairs it needs).
    pub repair: bool,
}

impl InfoJob {
    /// Runs the job.
    ///
    /// # Errors
    /// A [`Failure`] with its exit class and hint; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        run(self)
    }
    /// The description of `mesh` as text, without repairs.
    pub fn new(mesh: impl Into<PathBuf>) -> Self {
        Self {
            mesh: mesh.into(),
            json: false,
            repair: false,
        }
    }

    /// As JSON (`json`) or as text.
    pub fn with_json(mut self, json: bool) -> Self {
        self.json = json;
        self
    }
}

/// Runs `conformap info`. Without `--repair`, an invalid mesh is an error whose hint says
/// what `--repair` would do about it; a valid one lists the repairs that would still apply
/// (`repairs_available`, e.g. keeping the largest of several components).
fn run(args: &InfoJob) -> Result<Outcome, Failure> {
    let raw = conformap_io::read_raw_mesh(&args.mesh)?;
    let value = if args.repair {
        let input = repair_input(raw)?;
        let mut value = describe(&input.mesh, &args.mesh);
        if let Some(log) = &input.repairs {
            value["repairs"] = to_value(&RepairsReport::new(log));
        }
        value
    } else {
        let preview = repair_preview(&raw);
        let loaded = raw.validate().map_err(|e| {
            let f = Failure::from(e);
            let hint = match f.hint() {
                Some(h) => format!("{h}\nhint: {preview}"),
                None => preview.clone(),
            };
            Failure::BadInput(f.to_string(), Some(hint))
        })?;
        let mut value = describe(&loaded.mesh, &args.mesh);
        value["repairs_available"] = json!(available_repairs(&loaded.mesh));
        value
    };
    let text = if args.json {
        serde_json::to_string_pretty(&value).unwrap_or_default()
    } else {
        text(&value)
    };
    Ok(Outcome {
        stdout: Some(text),
        ..Outcome::default()
    })
}

/// Everything `info` reports about a valid mesh, as JSON.
pub fn describe(mesh: &TriMesh, path: &std::path::Path) -> serde_json::Value {
    let loops: Vec<usize> = mesh.boundary_loops().iter().map(Vec::len).collect();
    let wc = mesh.well_conditioned();
    let q = mesh_quality(mesh);
    json!({
        "path": path.display().to_string(),
        "valid": true,
        "vertices": mesh.num_vertices(),
        "faces": mesh.num_faces(),
        "edges": mesh.num_edges(),
        "euler_characteristic": mesh.euler_characteristic(),
        "genus": mesh.genus(),
        "components": mesh.num_components(),
        "boundaries": loops.len(),
        "boundary_loop_sizes": loops,
        "topology": mesh.topology().to_string(),
        "bbox_diagonal": mesh.bbox_diagonal(),
        "surface_area": surface_area(mesh),
        "angle_min_deg": q.angle_min_deg,
        "angle_max_deg": q.angle_max_deg,
        "negative_cotan_edges": q.negative_cotan_edges,
        "negative_cotan_edge_fraction": q.negative_cotan_edge_fraction,
        "folded_edges": q.folded_edges,
        "coincident_vertices": conformap_io::coincident_vertices(mesh.positions()),
        "well_conditioned": {
            "holds": wc.holds(),
            "connected": wc.connected,
            "interior_connected": wc.interior_connected,
            "boundary_connected": wc.boundary_connected,
            "boundary_vertices_without_interior_neighbor":
                wc.boundary_vertices_without_interior_neighbor.len(),
        },
    })
}

/// One line saying what `--repair` would do to `raw` and whether the result would be valid.
fn repair_preview(raw: &RawMesh) -> String {
    // the repairs as `--repair` runs them (the OBJ weld included), on a copy
    match repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT) {
        Err(e) => format!("--repair cannot fix it: {}", repair_failure(raw, e)),
        Ok(_) => match repair_input(raw.clone()) {
            Ok(input) => {
                let actions = input.repairs.map(|l| l.actions()).unwrap_or_default();
                let what = if actions.is_empty() {
                    "nothing to repair".to_string()
                } else {
                    actions.join("; ")
                };
                format!(
                    "with --repair: {what}; the result is valid, {} (`conformap info \
                     --repair` describes it)",
                    input.mesh.topology()
                )
            }
            Err(f) => format!("with --repair: the result is still invalid: {f}"),
        },
    }
}

/// The repairs `--repair` would still apply to a valid mesh: welding coincident vertices (a
/// triangle soup) and keeping the largest component (a valid mesh has no duplicate,
/// flipped or unreferenced element); the same code as the repair
/// ([`crate::pipeline::input::weld_and_repair`]).
pub fn available_repairs(mesh: &TriMesh) -> Vec<String> {
    match crate::pipeline::input::weld_and_repair(mesh.positions(), mesh.faces()) {
        Ok(r) => r.log.actions(),
        Err(e) => vec![format!("cannot repair: {e}")],
    }
}

/// The text form of `info`'s description.
fn text(v: &serde_json::Value) -> String {
    let mut out = String::new();
    let mut say = |line: &str| {
        let _ = writeln!(out, "{line}");
    };
    let g = |k: &str| v.get(k).cloned().unwrap_or(serde_json::Value::Null);
    say(&format!(
        "mesh:        {}",
        g("path").as_str().unwrap_or("")
    ));
    say(&format!(
        "topology:    {}",
        g("topology").as_str().unwrap_or("")
    ));
    say(&format!("vertices:    {}", g("vertices")));
    say(&format!("faces:       {}", g("faces")));
    say(&format!("edges:       {}", g("edges")));
    say(&format!("euler char.: {}", g("euler_characteristic")));
    say(&format!("genus:       {}", g("genus")));
    say(&format!("components:  {}", g("components")));
    say(&format!(
        "boundaries:  {} (sizes {})",
        g("boundaries"),
        g("boundary_loop_sizes")
    ));
    say(&format!(
        "bbox diag.:  {:.6e}",
        g("bbox_diagonal").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "area:        {:.6e}",
        g("surface_area").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "angles:      {:.2}° .. {:.2}°",
        g("angle_min_deg").as_f64().unwrap_or(f64::NAN),
        g("angle_max_deg").as_f64().unwrap_or(f64::NAN)
    ));
    say(&format!(
        "non-Delaunay edges (negative cotangent weight): {} ({:.1}%)",
        g("negative_cotan_edges"),
        100.0 * g("negative_cotan_edge_fraction").as_f64().unwrap_or(0.0)
    ));
    if g("coincident_vertices").as_u64().unwrap_or(0) > 0 {
        say(&format!(
            "coincident vertices: {} (bit-identical positions not shared by faces; --repair \
             welds them, as the glTF reader does)",
            g("coincident_vertices")
        ));
    }
    if g("folded_edges").as_u64().unwrap_or(0) > 0 {
        say(&format!(
            "geometric folds (adjacent normals more than 154° apart): {} edges; the maps' \
             flip-free guards handle them, a remesh removes them",
            g("folded_edges")
        ));
    }
    say(&format!(
        "CEM well-conditioned (Definition 1): {}",
        v["well_conditioned"]["holds"]
    ));
    let list = |key: &str| -> Vec<String> {
        v[key]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|s| s.as_str().map(str::to_string))
                    .collect()
            })
            .unwrap_or_default()
    };
    let available = list("repairs_available");
    if !available.is_empty() {
        say(&format!("with --repair: {}", available.join("; ")));
    }
    if v.get("repairs").is_some() {
        let applied = v["repairs"]["applied"]
            .as_array()
            .map(|a| {
                a.iter()
                    .filter_map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join("; ")
            })
            .unwrap_or_default();
        let applied = if applied.is_empty() {
            "nothing".to_string()
        } else {
            applied
        };
        say(&format!("repaired:    {applied}"));
    }
    out.pop();
    out
}
