//! One module per subcommand.

pub mod disk;
pub mod disk_holes;
pub mod info;
pub mod metrics;
pub mod mobius;
pub mod sphere;

use std::path::Path;

use crate::failure::Failure;

/// Reads a map file (`PARAM` of `metrics` and `mobius`) without geometric validation: a
/// valid map crowds triangles far below the degenerate-area threshold of a 3D mesh
/// (alligator's disk map: area 1e-28; armadillo's sphere map: chord triangles of 2e-14),
/// so only its connectivity must match `mesh`'s, vertex for vertex and face for face.
///
/// Texture coordinates, when the file has them, must cover every vertex (the error names
/// the first that has none).
pub fn read_map_file(
    param: &Path,
    mesh_path: &Path,
    mesh: &conformap_mesh::TriMesh,
) -> Result<MapFile, Failure> {
    let raw = conformap_io::read_raw_mesh(param)?;
    let (pv, pf) = (raw.positions.len(), raw.faces.len());
    if pv != mesh.num_vertices() || pf != mesh.num_faces() {
        return Err(Failure::input(format!(
            "{} has {} vertices and {} faces but {} has {} and {}: the map must have the \
             mesh's vertices and faces",
            param.display(),
            pv,
            pf,
            mesh_path.display(),
            mesh.num_vertices(),
            mesh.num_faces()
        )));
    }
    if let Some(face) = (0..mesh.num_faces()).find(|&f| raw.faces[f] != mesh.faces()[f]) {
        return Err(Failure::input(format!(
            "face {face} of {} is {:?} but face {face} of {} is {:?}: the map must use the \
             mesh's faces in the same order",
            param.display(),
            raw.faces[face],
            mesh_path.display(),
            mesh.faces()[face]
        )));
    }
    let uv = match raw.uv {
        Some(uv) => Some(
            uv.into_iter()
                .enumerate()
                .map(|(vertex, t)| {
                    t.ok_or_else(|| {
                        Failure::input(format!(
                            "{}: vertex {vertex} has no texture coordinate",
                            param.display()
                        ))
                    })
                })
                .collect::<Result<Vec<_>, _>>()?,
        ),
        None => None,
    };
    Ok(MapFile {
        positions: raw.positions,
        uv,
    })
}

/// A map read by [`read_map_file`]: its positions and, when the file has them, one texture
/// coordinate per vertex.
pub struct MapFile {
    /// Vertex positions as written (a flat map's `(u, v, 0)`, a sphere map's points, or
    /// the 3D mesh beside texture coordinates).
    pub positions: Vec<[f64; 3]>,
    /// Texture coordinates, one per vertex.
    pub uv: Option<Vec<[f64; 2]>>,
}

/// Prints `text` and a newline to stdout; a closed pipe (`conformap info m.obj | head`) is
/// not an error worth a panic, so write errors are ignored.
pub fn say(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{text}");
}

/// Writes `value` as pretty JSON to `path` atomically (temporary sibling, then rename).
pub fn write_json(path: &Path, value: &serde_json::Value) -> Result<(), Failure> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Failure::Numerical(format!("cannot serialize the report: {e}")))?;
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    let result = std::fs::write(&tmp, text + "\n").and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Failure::input(format!(
            "cannot write {}: {e}",
            path.display()
        )));
    }
    Ok(())
}
