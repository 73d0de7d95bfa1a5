//! Map files (`PARAM` of `metrics` and `mobius`) and face-region files.

use std::path::{Path, PathBuf};

use conformap_io::CornerUv;

use conformap_mesh::TriMesh;
use num_complex::Complex64;

use crate::failure::Failure;
use crate::jobs::param_match::{match_faces, reorder_corners, seamed_flat};

/// Largest `||x| − 1|` of a point taken for a point of the unit sphere: the library's
/// [`conformap_sphere::MAP_RADIUS_TOL`] (1e-6), which maps stored as f32 (glTF, ~1e-7 of
/// rounding) meet and which the Möbius optimization accepts.
pub const UNIT_SPHERE_TOL: f64 = conformap_sphere::MAP_RADIUS_TOL;

/// Whether `p` lies on the unit sphere within [`UNIT_SPHERE_TOL`] (false for NaN).
pub fn on_unit_sphere(p: &[f64; 3]) -> bool {
    ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() <= UNIT_SPHERE_TOL
}

/// A map read by [`read_map_file`]: its positions and, when the file has them, its texture
/// coordinates (one per vertex, or per face corner for a seamed map).
#[derive(Debug, Clone)]
pub struct MapFile {
    /// The file.
    pub path: PathBuf,
    /// Vertex positions as written (a flat map's `(u, v, 0)`, a sphere map's points, or
    /// the 3D mesh beside texture coordinates).
    pub positions: Vec<[f64; 3]>,
    /// Texture coordinates, one per vertex.
    pub uv: Option<Vec<[f64; 2]>>,
    /// Texture coordinates per face corner, when they are not one per vertex (a seam).
    pub corner_uv: Option<CornerUv>,
}

/// A planar map: one value per vertex, or per face corner (`3 f + k`) for a seamed map.
#[derive(Debug, Clone, PartialEq)]
pub enum PlanarMap {
    /// One value per vertex.
    PerVertex(Vec<Complex64>),
    /// One value per face corner.
    PerCorner(Vec<Complex64>),
}

impl MapFile {
    /// The planar map it holds, with the name of its source for the report: per-vertex
    /// texture coordinates as `u = 2·vt_x − 1, v = 2·vt_y − 1` (the inverse of what `disk`
    /// writes); seamed texture coordinates as `(u, v) = vt`, per corner; else the
    /// positions' `(x, y)`.
    pub fn planar_map(&self) -> (PlanarMap, &'static str) {
        match (&self.uv, &self.corner_uv) {
            (Some(uv), _) => (
                PlanarMap::PerVertex(
                    uv.iter()
                        .map(|t| Complex64::new(2.0 * t[0] - 1.0, 2.0 * t[1] - 1.0))
                        .collect(),
                ),
                "texture coordinates",
            ),
            (None, Some(c)) => (
                PlanarMap::PerCorner(
                    (0..c.faces.len())
                        .flat_map(|f| (0..3).map(move |k| c.corner(f, k)))
                        .map(|t| Complex64::new(t[0], t[1]))
                        .collect(),
                ),
                "seamed texture coordinates",
            ),
            (None, None) => (
                PlanarMap::PerVertex(
                    self.positions
                        .iter()
                        .map(|p| Complex64::new(p[0], p[1]))
                        .collect(),
                ),
                "flat positions",
            ),
        }
    }

    /// The planar map with one value per vertex, for commands that need one (`mobius`).
    ///
    /// # Errors
    /// [`Failure::BadInput`] for a seamed map.
    pub fn planar(&self) -> Result<(Vec<Complex64>, &'static str), Failure> {
        match self.planar_map() {
            (PlanarMap::PerVertex(map), from) => Ok((map, from)),
            (PlanarMap::PerCorner(_), _) => Err(Failure::BadInput(
                format!(
                    "{}: the map has seams (a vertex has different texture coordinates in \
                     different faces); this command needs one value per vertex",
                    self.path.display()
                ),
                Some(
                    "pass a disk map (the -o or --flat output of `conformap disk`); a seamed \
                     map is judged by `conformap metrics`"
                        .to_string(),
                ),
            )),
        }
    }
}

/// A map file as `metrics` and `render` read it, with the mesh it is measured on.
#[derive(Debug, Clone)]
pub struct MeasuredMap {
    /// The map file.
    pub file: MapFile,
    /// The map's own mesh, when the file carries one that refines the given mesh (the
    /// `-o` output of `global` on a surface whose boundary chords it split: the given
    /// mesh's vertices first, at their positions, then the new ones); `None`: the map is
    /// measured on the given mesh.
    pub own_mesh: Option<TriMesh>,
}

impl MeasuredMap {
    /// The mesh the map is measured on: its own, or else `given`.
    pub fn mesh<'a>(&'a self, given: &'a TriMesh) -> &'a TriMesh {
        self.own_mesh.as_ref().unwrap_or(given)
    }
}

/// Reads the map `param` of `mesh` ([`read_map_file`]) or, when it does not fit `mesh`
/// but carries its own mesh refining it, with texture coordinates ([`MeasuredMap`]), the
/// map on its own mesh. Every map file a command writes with `-o` is read one way or the
/// other.
///
/// # Errors
/// [`read_map_file`]'s, for the given mesh, when the file carries no refining mesh.
pub fn read_measured_map(
    param: &Path,
    mesh_path: &Path,
    mesh: &TriMesh,
) -> Result<MeasuredMap, Failure> {
    let refused = match read_map_file(param, mesh_path, mesh) {
        Ok(file) => {
            return Ok(MeasuredMap {
                file,
                own_mesh: None,
            })
        }
        Err(e) => e,
    };
    let Some(own) = refining_mesh(param, mesh) else {
        return Err(refused);
    };
    match read_map_file(param, param, &own) {
        Ok(file) if file.uv.is_some() || file.corner_uv.is_some() => Ok(MeasuredMap {
            file,
            own_mesh: Some(own),
        }),
        _ => Err(refused),
    }
}

/// The mesh in `param` when it refines `mesh`: more vertices, the first ones at `mesh`'s
/// positions (within 1e-9 of its bounding-box diagonal: a text file's rounding).
fn refining_mesh(param: &Path, mesh: &TriMesh) -> Option<TriMesh> {
    let own = conformap_io::read_mesh(param).ok()?.mesh;
    if own.num_vertices() <= mesh.num_vertices() {
        return None;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in mesh.positions() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    let close = |a: &[f64; 3], b: &[f64; 3]| {
        (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt() <= 1e-9 * diagonal
    };
    let same = mesh
        .positions()
        .iter()
        .zip(own.positions())
        .all(|(a, b)| close(a, b));
    same.then_some(own)
}

/// The sphere map in `file`, with the name of its source, when it holds one: positions
/// on the unit sphere ([`on_unit_sphere`]) without texture coordinates (`sphere --flat`),
/// or per-vertex texture coordinates on a closed genus-0 `mesh`, read as equirectangular
/// (`sphere -o`; a closed surface has no planar map with one value per vertex).
pub fn sphere_points(file: &MapFile, mesh: &TriMesh) -> Option<(Vec<[f64; 3]>, &'static str)> {
    let closed_genus0 = mesh.boundary_loops().is_empty() && mesh.genus() == Some(0);
    match (&file.uv, &file.corner_uv) {
        (None, None) if file.positions.iter().all(on_unit_sphere) => {
            Some((file.positions.clone(), "unit-sphere positions"))
        }
        (Some(uv), _) if closed_genus0 => Some((
            uv.iter()
                .map(|&t| conformap_sphere::from_equirectangular_uv(t))
                .collect(),
            "equirectangular texture coordinates",
        )),
        (None, Some(corners)) if closed_genus0 => Some((
            corner_sphere_points(mesh, corners)?,
            "equirectangular texture coordinates per corner",
        )),
        _ => None,
    }
}

/// One unit-sphere point per vertex from equirectangular texture coordinates per corner
/// (split at the seam meridian, polar corners at their face's mean `u`, as `sphere -o`
/// writes them): [`conformap_sphere::sphere_points_from_corner_uv`], the reading `render`
/// and `mobius` use; `None` for a seamed planar map (an atlas).
fn corner_sphere_points(mesh: &TriMesh, corners: &CornerUv) -> Option<Vec<[f64; 3]>> {
    conformap_sphere::sphere_points_from_corner_uv(mesh, &corners.texcoords, &corners.faces)
}

/// Reads a map file without geometric validation: a valid map crowds triangles far below
/// the degenerate-area threshold of a 3D mesh (alligator's disk map: area 1e-28;
/// armadillo's sphere map: chord triangles of 2e-14), so only its connectivity must match
/// `mesh`'s: its vertices in the mesh's order and the mesh's faces, in any order and
/// starting at any corner ([`match_faces`]); or a seamed flat layout (`global --flat`, see
/// [`seamed_flat`]).
///
/// Texture coordinates, when the file has them, must cover every vertex (the error names
/// the first that has none).
pub fn read_map_file(param: &Path, mesh_path: &Path, mesh: &TriMesh) -> Result<MapFile, Failure> {
    let mut raw = conformap_io::read_raw_mesh(param)?;
    if raw.uv.is_none() && raw.corner_uv.is_none() {
        if let Some((corner, positions)) = seamed_flat(&raw.positions, &raw.faces, mesh) {
            return Ok(MapFile {
                path: param.to_path_buf(),
                positions,
                uv: None,
                corner_uv: Some(corner),
            });
        }
    }
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
    match match_faces(&raw.faces, mesh.faces()) {
        Ok(None) => {}
        // a per-vertex map needs only the vertex order; a seamed one follows its faces
        Ok(Some(order)) => raw.corner_uv = raw.corner_uv.map(|c| reorder_corners(c, &order)),
        Err(face) => {
            return Err(Failure::BadInput(
                format!(
                    "face {face} of {} ({:?}) is not a face of {}: the map must have the \
                     mesh's faces (in any order, starting at any corner) and its vertices \
                     in the mesh's order",
                    mesh_path.display(),
                    mesh.faces()[face],
                    param.display(),
                ),
                Some(
                    "write the map with the mesh's vertices in the mesh's order (a \
                     re-triangulated or re-indexed map file does not match)"
                        .to_string(),
                ),
            ))
        }
    }
    if let Some(problem @ conformap_io::UvProblem::Missing { .. }) = &raw.uv_problem {
        return Err(conformap_io::IoError::NotPerVertexUv {
            path: param.to_path_buf(),
            problem: problem.clone(),
        }
        .into());
    }
    let corner_uv = if raw.uv.is_none() {
        raw.corner_uv
    } else {
        None
    };
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
    let file = MapFile {
        path: param.to_path_buf(),
        positions: raw.positions,
        uv,
        corner_uv,
    };
    check_finite(&file)?;
    Ok(file)
}

/// Refuses a map file with a NaN or infinite value, naming the vertex (or texture
/// coordinate) of the first.
fn check_finite(file: &MapFile) -> Result<(), Failure> {
    let finite = |x: &[f64]| x.iter().all(|c| c.is_finite());
    let bad = if let Some(v) = file.positions.iter().position(|p| !finite(p)) {
        Some(format!("the position of vertex {v}"))
    } else if let Some(v) = file.uv.iter().flatten().position(|t| !finite(t)) {
        Some(format!("the texture coordinate of vertex {v}"))
    } else {
        file.corner_uv
            .iter()
            .flat_map(|c| c.texcoords.iter())
            .position(|t| !finite(t))
            .map(|k| format!("texture coordinate {k} (0-based vt index)"))
    };
    match bad {
        None => Ok(()),
        Some(what) => Err(Failure::BadInput(
            format!(
                "{}: {what} is not finite (NaN or infinity)",
                file.path.display()
            ),
            Some(
                "the map is broken at that vertex (the tool that wrote it failed there): \
                 recompute the map, or fix that value in the file"
                    .to_string(),
            ),
        )),
    }
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
        region.push(region_face(
            f,
            faces,
            &format!("{} line {}", path.display(), k + 1),
        )?);
    }
    Ok(region)
}

/// Checks one face index of a region against the mesh's `faces`; `place` says where it
/// was given (`FACES.txt line 3`, or `region[2]` for the Python package's arrays).
///
/// # Errors
/// [`Failure::BadInput`] when `f` is not below `faces`.
pub fn region_face(f: usize, faces: usize, place: &str) -> Result<usize, Failure> {
    if f >= faces {
        return Err(Failure::BadInput(
            format!(
                "{place}: face {f} is out of range (the mesh has {faces} faces, 0..{})",
                faces.saturating_sub(1)
            ),
            Some("face indices are 0-based, in the order of the mesh file".to_string()),
        ));
    }
    Ok(f)
}
