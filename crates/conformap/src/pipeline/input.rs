//! Reading the mesh of a command: as read, or repaired with `--repair`.

use std::path::Path;

use conformap_io::{RawMesh, SourceInfo};
use conformap_mesh::{RepairLog, RepairOptions, TriMesh};

use crate::failure::{repair_failure, Failure};

/// A mesh to map: as read, or repaired.
#[derive(Debug)]
pub struct Input {
    /// The validated mesh.
    pub mesh: TriMesh,
    /// Where it came from.
    pub source: SourceInfo,
    /// What `--repair` changed (`None` without `--repair`).
    pub repairs: Option<RepairLog>,
    /// The path as given.
    pub path: std::path::PathBuf,
    /// Where a non-manifold input was split (`atlas` only, [`read_input_splitting`];
    /// `None`: read as it is).
    pub split: Option<SplitInput>,
}

/// A non-manifold input made manifold by `atlas` ([`conformap_atlas::split_non_manifold`]).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct SplitInput {
    /// Where it was split.
    pub report: conformap_atlas::SplitReport,
    /// For each vertex of [`Input::mesh`], the file's vertex it is a copy of.
    pub vertex_to_input: Vec<u32>,
}

impl Input {
    /// The file's own vertex layout, for writers that keep it (glTF seams), unless a repair
    /// changed the mesh.
    pub fn file_layout(&self) -> Option<&SourceInfo> {
        let unchanged = self.repairs.as_ref().is_none_or(|log| !log.changed());
        (unchanged && self.split.is_none()).then_some(&self.source)
    }

    /// A command failure about this input, prefixed by its path.
    pub fn fail(&self, f: Failure) -> Failure {
        f.in_file(&self.path)
    }
}

/// Reads `path`; with `repair`, reads it raw, applies every repair of
/// [`conformap_mesh::repair`] and validates the result. Errors name input elements and
/// file places either way.
pub fn read_input(path: &Path, repair: bool) -> Result<Input, Failure> {
    if !repair {
        let loaded = conformap_io::read_mesh(path).map_err(|e| refusal(path, e))?;
        return Ok(as_read(path, loaded));
    }
    repair_input(conformap_io::read_raw_mesh(path)?)
}

/// Reads `path` as [`read_input`] does without `--repair`, except that a mesh refused only
/// for a non-manifold vertex or edge is split there
/// ([`conformap_atlas::split_non_manifold`]) and validated again: the `atlas` command's
/// reading. Every other defect (and a non-manifold mesh that also has duplicate faces,
/// which splitting would turn into a component of their own) keeps its refusal.
///
/// # Errors
/// As [`read_input`]; for a split mesh, the validation's error on it.
pub fn read_input_splitting(path: &Path) -> Result<Input, Failure> {
    use conformap_mesh::MeshError as M;
    let e = match conformap_io::read_mesh(path) {
        Ok(loaded) => return Ok(as_read(path, loaded)),
        Err(e) => e,
    };
    let non_manifold = matches!(
        &e,
        conformap_io::IoError::InvalidMesh {
            source: M::NonManifoldVertex { .. } | M::NonManifoldEdge { .. },
            ..
        }
    );
    if !non_manifold {
        return Err(refusal(path, e));
    }
    let raw = conformap_io::read_raw_mesh(path)?;
    let Some(split) = split_non_manifold_mesh(&raw.positions, &raw.faces) else {
        return Err(refusal(path, e));
    };
    let (mesh, split) = split.map_err(|e| Failure::from(raw.invalid_mesh(e)))?;
    Ok(Input {
        mesh,
        source: raw.source,
        repairs: None,
        path: path.to_path_buf(),
        split: Some(split),
    })
}

/// A mesh refused for a non-manifold vertex or edge, split there
/// ([`conformap_atlas::split_non_manifold`]) and validated again; `None` when it has
/// duplicate faces (splitting would make each copy a component of its own: the refusal
/// stands). `atlas`'s reading of a file ([`read_input_splitting`]) and of arrays.
///
/// # Errors
/// The validation's error on the split mesh.
pub fn split_non_manifold_mesh(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> Option<Result<(TriMesh, SplitInput), conformap_mesh::MeshError>> {
    let mut seen = std::collections::HashSet::with_capacity(faces.len());
    let duplicates = faces.iter().any(|t| {
        let mut k = *t;
        k.sort_unstable();
        !seen.insert(k)
    });
    if duplicates {
        return None;
    }
    let split = conformap_atlas::split_non_manifold(positions, faces);
    Some(TriMesh::try_new(split.positions, split.faces).map(|mesh| {
        (
            mesh,
            SplitInput {
                report: split.report,
                vertex_to_input: split.vertex_to_input,
            },
        )
    }))
}

/// The input of a mesh read from `path` as it is (no repair, no split).
fn as_read(path: &Path, loaded: conformap_io::LoadedMesh) -> Input {
    Input {
        mesh: loaded.mesh,
        source: loaded.source,
        repairs: None,
        path: path.to_path_buf(),
        split: None,
    }
}

/// The failure of reading `path` without `--repair`: when the mesh is non-manifold only
/// because of coincident vertices (a duplicated vertex that splits a fan), the hint says
/// that `--repair` welds them into a valid mesh (checked by running the repair,
/// [`weld_and_repair`]) instead of "no automatic repair is safe".
fn refusal(path: &Path, e: conformap_io::IoError) -> Failure {
    use conformap_mesh::MeshError as M;
    let non_manifold = matches!(
        &e,
        conformap_io::IoError::InvalidMesh {
            source: M::NonManifoldVertex { .. } | M::NonManifoldEdge { .. },
            ..
        }
    );
    let failure = Failure::from(e);
    if !non_manifold {
        return failure;
    }
    let Ok(raw) = conformap_io::read_raw_mesh(path) else {
        return failure;
    };
    let welded = match weld_and_repair(&raw.positions, &raw.faces) {
        Ok(fixed) if fixed.log.coincident_welded > 0 => fixed,
        _ => return failure,
    };
    if TriMesh::try_new(welded.positions, welded.faces).is_err() {
        return failure;
    }
    match failure {
        Failure::BadInput(message, _) => Failure::BadInput(
            message,
            Some(format!(
                "rerun with --repair: it welds {} coincident vertex(es) (bit-identical \
                 positions), which makes this a valid mesh (`conformap info --repair MESH` \
                 describes the result)",
                welded.log.coincident_welded
            )),
        ),
        other => other,
    }
}

/// Applies every repair of [`conformap_mesh::repair`] to `raw` and validates the result;
/// errors name input elements and their file places.
pub fn repair_input(mut raw: RawMesh) -> Result<Input, Failure> {
    // an OBJ is welded as a glTF is on reading: bit-identical positions become one vertex
    // (a triangle soup, a seam-split export); the log then speaks of the file's vertices
    // (a glTF is welded on reading already; [`weld_and_repair`] is the same steps)
    let weld =
        Some(conformap_io::weld_coincident(&raw.positions, &raw.faces)).filter(|w| w.merged() > 0);
    let file_lines = raw.source.vertex_lines.clone();
    if weld.is_some() {
        raw = raw.weld_coincident().0;
    }
    let fixed = conformap_mesh::repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT);
    raw.source.vertex_lines = file_lines;
    let mut fixed = match (fixed, &weld) {
        (Ok(f), _) => f,
        (Err(e), None) => return Err(repair_failure(&raw, e)),
        (Err(e), Some(_)) => {
            return Err(Failure::input(format!(
                "{}: {e}",
                raw.source.path.display()
            )))
        }
    };
    if let Some(w) = &weld {
        through_weld(&mut fixed.log, w);
    }
    raw.positions = Vec::new();
    raw.faces = Vec::new();
    let log = fixed.log;
    let mesh = TriMesh::try_new(fixed.positions, fixed.faces)
        .map_err(|e| Failure::from(raw.invalid_mesh(log.to_input_error(e))))?;
    let path = raw.source.path.clone();
    Ok(Input {
        mesh,
        source: raw.source,
        repairs: Some(log),
        path,
        split: None,
    })
}

/// `log` (of a repair of the welded mesh `w`) in the numbering of the mesh before the weld.
fn through_weld(log: &mut RepairLog, w: &conformap_io::Welded) {
    log.vertex_to_input = log
        .vertex_to_input
        .iter()
        .map(|&c| w.first[c as usize] as u32)
        .collect();
    log.input_to_vertex = w
        .map
        .iter()
        .map(|&c| log.input_to_vertex[c as usize])
        .collect();
    log.input_vertices = w.map.len();
    log.coincident_welded = w.merged();
}

/// The repairs of `--repair` on a triangle list: bit-identical positions welded into one
/// vertex (a triangle soup becomes a surface), then every repair of
/// [`conformap_mesh::repair`]; the log speaks of the vertices given. The one code path of
/// the repair's preview (`info`, the hints of refusals) and of the Python package's
/// `repair`, as [`repair_input`] runs it on a file.
///
/// # Errors
/// [`conformap_mesh::repair`]'s, about the welded mesh.
pub fn weld_and_repair(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> Result<conformap_mesh::Repaired, conformap_mesh::MeshError> {
    let w = conformap_io::weld_coincident(positions, faces);
    if w.merged() == 0 {
        return conformap_mesh::repair(positions, faces, &RepairOptions::DEFAULT);
    }
    let mut fixed = conformap_mesh::repair(&w.positions, &w.faces, &RepairOptions::DEFAULT)?;
    through_weld(&mut fixed.log, &w);
    Ok(fixed)
}

/// The repaired → input vertex map as text, one 0-based input vertex per line.
pub fn vertex_map_text(log: &RepairLog) -> String {
    vertex_list_text(&log.vertex_to_input)
}

/// A vertex map as text: one 0-based input vertex per line, for each output vertex.
pub fn vertex_list_text(vertex_to_input: &[u32]) -> String {
    let mut text = String::with_capacity(8 * vertex_to_input.len());
    for v in vertex_to_input {
        text.push_str(&v.to_string());
        text.push('\n');
    }
    text
}
