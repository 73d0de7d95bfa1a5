//! Map files (`PARAM` of `metrics` and `mobius`) and face-region files.

use std::path::Path;

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use crate::failure::Failure;

/// A map read by [`read_map_file`]: its positions and, when the file has them, one texture
/// coordinate per vertex.
#[derive(Debug)]
pub struct MapFile {
    /// Vertex positions as written (a flat map's `(u, v, 0)`, a sphere map's points, or
    /// the 3D mesh beside texture coordinates).
    pub positions: Vec<[f64; 3]>,
    /// Texture coordinates, one per vertex.
    pub uv: Option<Vec<[f64; 2]>>,
}

impl MapFile {
    /// The planar map it holds: `u = 2·vt_x − 1, v = 2·vt_y − 1` from texture coordinates
    /// (the inverse of what `disk` writes), else the positions' `(x, y)`; with the name of
    /// its source for the report.
    pub fn planar(&self) -> (Vec<Complex64>, &'static str) {
        match &self.uv {
            Some(uv) => (
                uv.iter()
                    .map(|t| Complex64::new(2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0))
                    .collect(),
                "texture coordinates",
            ),
            None => (
                self.positions
                    .iter()
                    .map(|p| Complex64::new(p[0], p[1]))
                    .collect(),
                "flat positions",
            ),
        }
    }
}

/// Reads a map file without geometric validation: a valid map crowds triangles far below
/// the degenerate-area threshold of a 3D mesh (alligator's disk map: area 1e-28;
/// armadillo's sphere map: chord triangles of 2e-14), so only its connectivity must match
/// `mesh`'s, vertex for vertex and face for face.
///
/// Texture coordinates, when the file has them, must cover every vertex (the error names
/// the first that has none).
pub fn read_map_file(param: &Path, mesh_path: &Path, mesh: &TriMesh) -> Result<MapFile, Failure> {
    let raw = conformap_io::read_raw_mesh(param)?;
    let (pv, pf) = (raw.positions.len(), raw.faces.len());
    if pv != mesh.num_vertices() || pf != mesh.num_faces() {
        return Err(Failure::BadInput(
            format!(
                "{} has {} vertices and {} faces but {} has {} and {}: the map must have the \
                 mesh's vertices and faces",
                param.display(),
                pv,
                pf,
                mesh_path.display(),
                mesh.num_vertices(),
                mesh.num_faces()
            ),
            Some(
                "pass the map written for this mesh (the -o or --flat output of the command \
                 that mapped it), not another mesh's"
                    .to_string(),
            ),
        ));
    }
    if let Some(face) = (0..mesh.num_faces()).find(|&f| raw.faces[f] != mesh.faces()[f]) {
        return Err(Failure::BadInput(
            format!(
                "face {face} of {} is {:?} but face {face} of {} is {:?}: the map must use the \
                 mesh's faces in the same order",
                param.display(),
                raw.faces[face],
                mesh_path.display(),
                mesh.faces()[face]
            ),
            Some(
                "write the map with the mesh's own faces in the mesh's order (a re-exported or \
                 re-triangulated map file does not match)"
                    .to_string(),
            ),
        ));
    }
    let uv = match raw.uv {
        Some(uv) => Some(
            uv.into_iter()
                .enumerate()
                .map(|(vertex, t)| {
                    t.ok_or_else(|| {
                        Failure::BadInput(
                            format!(
                                "{}: vertex {vertex} has no texture coordinate",
                                param.display()
                            ),
                            Some(
                                "give every vertex one texture coordinate (f v/vt with one vt \
                                 per vertex), or pass the map as a flat mesh"
                                    .to_string(),
                            ),
                        )
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

/// Reads a region file: one 0-based face index per line (blank lines and lines starting
/// with `#` are skipped).
pub fn read_region(path: &Path, faces: usize) -> Result<Vec<usize>, Failure> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Failure::BadInput(
            format!("cannot read {}: {e}", path.display()),
            Some("check the path and that the file is readable text".to_string()),
        )
    })?;
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
