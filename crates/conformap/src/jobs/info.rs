//! `conformap info MESH [--json]`: topology and validity of a mesh.

use std::path::PathBuf;

use conformap_io::RawMesh;
use conformap_mesh::{repair, RepairOptions, TriMesh};
use conformap_operators::{mesh_quality, surface_area};
use serde::Serialize;

use std::fmt::Write;

use crate::failure::{repair_failure, Failure};
use crate::pipeline::{repair_input, Outcome};
use crate::report::{RepairsReport, Sorted};

/// Everything `info` reports about a valid mesh (`info --json` writes it with its keys
/// sorted at every depth: [`Sorted`]).
#[derive(Debug, Clone, Serialize)]
#[non_exhaustive]
pub struct MeshInfo {
    /// Path as given.
    pub path: String,
    /// Always `true`: an invalid mesh is an error, not a description.
    pub valid: bool,
    /// Vertex count.
    pub vertices: usize,
    /// Face count.
    pub faces: usize,
    /// Edge count.
    pub edges: usize,
    /// `V − E + F`.
    pub euler_characteristic: i64,
    /// Genus (null for several components).
    pub genus: Option<i64>,
    /// Connected components.
    pub components: usize,
    /// Boundary loops.
    pub boundaries: usize,
    /// Vertices of each boundary loop.
    pub boundary_loop_sizes: Vec<usize>,
    /// The topology in words (`disk`, `sphere`, `genus 2`, …).
    pub topology: String,
    /// Diagonal of the bounding box.
    pub bbox_diagonal: f64,
    /// Total area.
    pub surface_area: f64,
    /// Smallest corner angle, degrees.
    pub angle_min_deg: f64,
    /// Largest corner angle, degrees.
    pub angle_max_deg: f64,
    /// Interior edges of negative cotangent weight (non-Delaunay).
    pub negative_cotan_edges: usize,
    /// Their share of the interior edges.
    pub negative_cotan_edge_fraction: f64,
    /// Edges whose two face normals are more than 154° apart.
    pub folded_edges: usize,
    /// Vertices at a bit-identical position to an earlier one, not shared by faces.
    pub coincident_vertices: usize,
    /// CEM's well-conditioning (Definition 1).
    pub well_conditioned: WellConditionedInfo,
    /// What `--repair` changed (with `--repair`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repairs: Option<RepairsReport>,
    /// The repairs `--repair` would still apply (without `--repair`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub repairs_available: Option<Vec<String>>,
}

/// CEM's well-conditioning of a mesh (Definition 1), as `info` reports it.
#[derive(Debug, Clone, Serialize)]
pub struct WellConditionedInfo {
    /// Whether every condition holds.
    pub holds: bool,
    /// The mesh is connected.
    pub connected: bool,
    /// Its interior vertices are connected.
    pub interior_connected: bool,
    /// Its boundary is connected.
    pub boundary_connected: bool,
    /// Boundary vertices without an interior neighbour.
    pub boundary_vertices_without_interior_neighbor: usize,
}

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
    let info = if args.repair {
        let input = repair_input(raw)?;
        let mut info = describe(&input.mesh, &args.mesh);
        info.repairs = input.repairs.map(RepairsReport);
        info
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
        let mut info = describe(&loaded.mesh, &args.mesh);
        info.repairs_available = Some(available_repairs(&loaded.mesh));
        info
    };
    let text = if args.json {
        serde_json::to_string_pretty(&Sorted(&info)).unwrap_or_default()
    } else {
        text(&info)
    };
    Ok(Outcome {
        stdout: Some(text),
        ..Outcome::default()
    })
}

/// Everything `info` reports about a valid mesh (no repairs).
pub fn describe(mesh: &TriMesh, path: &std::path::Path) -> MeshInfo {
    let loops: Vec<usize> = mesh.boundary_loops().iter().map(Vec::len).collect();
    let wc = mesh.well_conditioned();
    let q = mesh_quality(mesh);
    MeshInfo {
        path: path.display().to_string(),
        valid: true,
        vertices: mesh.num_vertices(),
        faces: mesh.num_faces(),
        edges: mesh.num_edges(),
        euler_characteristic: mesh.euler_characteristic(),
        genus: mesh.genus(),
        components: mesh.num_components(),
        boundaries: loops.len(),
        boundary_loop_sizes: loops,
        topology: mesh.topology().to_string(),
        bbox_diagonal: mesh.bbox_diagonal(),
        surface_area: surface_area(mesh),
        angle_min_deg: q.angle_min_deg,
        angle_max_deg: q.angle_max_deg,
        negative_cotan_edges: q.negative_cotan_edges,
        negative_cotan_edge_fraction: q.negative_cotan_edge_fraction,
        folded_edges: q.folded_edges,
        coincident_vertices: conformap_io::coincident_vertices(mesh.positions()),
        well_conditioned: WellConditionedInfo {
            holds: wc.holds(),
            connected: wc.connected,
            interior_connected: wc.interior_connected,
            boundary_connected: wc.boundary_connected,
            boundary_vertices_without_interior_neighbor: wc
                .boundary_vertices_without_interior_neighbor
                .len(),
        },
        repairs: None,
        repairs_available: None,
    }
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

/// `value` as compact JSON (`null` for a genus of several components).
fn json_text(value: &impl Serialize) -> String {
    serde_json::to_string(value).unwrap_or_default()
}

/// The text form of `info`'s description.
fn text(v: &MeshInfo) -> String {
    let mut out = String::new();
    let mut say = |line: &str| {
        let _ = writeln!(out, "{line}");
    };
    say(&format!("mesh:        {}", v.path));
    say(&format!("topology:    {}", v.topology));
    say(&format!("vertices:    {}", v.vertices));
    say(&format!("faces:       {}", v.faces));
    say(&format!("edges:       {}", v.edges));
    say(&format!("euler char.: {}", v.euler_characteristic));
    say(&format!("genus:       {}", json_text(&v.genus)));
    say(&format!("components:  {}", v.components));
    say(&format!(
        "boundaries:  {} (sizes {})",
        v.boundaries,
        json_text(&v.boundary_loop_sizes)
    ));
    say(&format!("bbox diag.:  {:.6e}", v.bbox_diagonal));
    say(&format!("area:        {:.6e}", v.surface_area));
    say(&format!(
        "angles:      {:.2}° .. {:.2}°",
        v.angle_min_deg, v.angle_max_deg
    ));
    say(&format!(
        "non-Delaunay edges (negative cotangent weight): {} ({:.1}%)",
        v.negative_cotan_edges,
        100.0 * v.negative_cotan_edge_fraction
    ));
    if v.coincident_vertices > 0 {
        say(&format!(
            "coincident vertices: {} (bit-identical positions not shared by faces; --repair \
             welds them, as the glTF reader does)",
            v.coincident_vertices
        ));
    }
    if v.folded_edges > 0 {
        say(&format!(
            "geometric folds (adjacent normals more than 154° apart): {} edges; the maps' \
             flip-free guards handle them, a remesh removes them",
            v.folded_edges
        ));
    }
    say(&format!(
        "CEM well-conditioned (Definition 1): {}",
        v.well_conditioned.holds
    ));
    let available = v.repairs_available.as_deref().unwrap_or_default();
    if !available.is_empty() {
        say(&format!("with --repair: {}", available.join("; ")));
    }
    if let Some(RepairsReport(log)) = &v.repairs {
        let applied = log.actions().join("; ");
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
