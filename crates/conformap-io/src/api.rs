//! The entry points: read by extension, write by extension (per-vertex, per-corner or
//! flat).

use std::path::Path;

use conformap_mesh::TriMesh;

use crate::atomic::{write_atomically, write_encoded_atomically};
use crate::corner_uv::CornerUv;
use crate::error::{IoError, WriteProblem};
use crate::freesurfer::encode_freesurfer;
use crate::gifti::{encode_gifti_data, encode_gifti_surface};
use crate::gltffile::encode_gltf;
use crate::loaded::{Format, LoadedMesh, SourceInfo, NO_VERTEX};
use crate::objfile::{encode_obj, encode_obj_with_corner_uv, encode_obj_with_uv};
use crate::plyfile::{encode_ply, PlyUv};
use crate::read::{read_raw_mesh, read_raw_mesh_from_bytes};

/// Reads a mesh from an `.obj`, `.gltf`, `.glb`, `.ply`, `.stl`, `.off` or `.gii` file or
/// a FreeSurfer surface (chosen by extension; a file whose extension names no format, such
/// as `lh.white`, by its first bytes: see [`Format::sniff`]).
///
/// OBJ: polygons are fan-triangulated; `vt`, `vn`, groups, objects and materials are
/// tolerated (no `.mtl` is loaded); several objects are merged with the file's global
/// vertex numbering. glTF/GLB: every triangle primitive of the default scene (node
/// transforms applied; without scenes, every mesh untransformed), with bit-identical
/// positions welded (see [`SourceInfo::weld_map`]); external `.bin` files and data URIs work.
/// PLY: the `vertex` element's `x y z` (and `texture_u texture_v`, `u v` or `s t`), the
/// `face` element's `vertex_indices` (polygons fan-triangulated), per-corner `texcoord`;
/// other elements skipped. STL: facets welded by bit-identical position, vertices in order
/// of first appearance ([`SourceInfo::weld_map`]). OFF: vertex and face lines (polygons
/// fan-triangulated). GIfTI: the point set and triangle arrays (every encoding and byte
/// order), transforms in [`SourceInfo::surface`]. FreeSurfer: the triangle surface, its
/// created-by line and volume geometry in [`SourceInfo::surface`].
///
/// # Errors
/// [`IoError`] naming the file and the line (OBJ) or mesh, primitive and accessor (glTF);
/// [`IoError::InvalidMesh`] when the triangles do not form a valid
/// [`TriMesh`](conformap_mesh::TriMesh).
///
/// # Examples
/// ```no_run
/// let loaded = conformap_io::read_mesh("fixtures/woody.obj")?;
/// assert_eq!(loaded.mesh.num_vertices(), 694);
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn read_mesh(path: impl AsRef<Path>) -> Result<LoadedMesh, IoError> {
    read_raw_mesh(path)?.validate()
}

/// Reads a mesh from bytes already in memory (for tests and fuzzing). Errors name the
/// file `<memory>`; a glTF that refers to external files is an error.
///
/// # Errors
/// As [`read_mesh`].
///
/// # Examples
/// ```
/// use conformap_io::{read_mesh_from_bytes, Format};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
/// let loaded = read_mesh_from_bytes(obj, Format::Obj)?;
/// assert_eq!(loaded.mesh.num_faces(), 1);
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn read_mesh_from_bytes(bytes: &[u8], format: Format) -> Result<LoadedMesh, IoError> {
    read_raw_mesh_from_bytes(bytes, format)?.validate()
}

/// Writes `mesh` with one texture coordinate per vertex (`uv[k]` belongs to vertex `k`),
/// as `.obj` (`v`, `vt`, `f a/a b/b c/c`; exact round trip), `.gltf` (buffer embedded as a
/// data URI) or `.glb` (f32 `POSITION` and `TEXCOORD_0`, `u32` indices).
///
/// If `source` describes a glTF/GLB read from which `mesh` came unchanged, glTF output
/// keeps the file's vertex layout (its split vertices, with `uv` copied through the weld
/// map), so per-vertex data of the original file still lines up. Otherwise the mesh's own
/// vertices are written.
///
/// The file appears complete or not at all (written to a temporary sibling, then renamed).
///
/// # Errors
/// [`IoError::BadWriteInput`] if `uv.len()` differs from the vertex count or a value is
/// not finite (or, for glTF, not representable as f32); [`IoError::Write`] if the file
/// cannot be written; [`IoError::UnknownFormat`] for another extension.
pub fn write_mesh_with_uv(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    uv: &[[f64; 2]],
    source: Option<&SourceInfo>,
) -> Result<(), IoError> {
    let path = path.as_ref();
    let (format, bad) = write_target(path)?;
    if uv.len() != mesh.num_vertices() {
        return Err(bad(WriteProblem::UvCount {
            expected: mesh.num_vertices(),
            found: uv.len(),
        }));
    }
    check_finite(uv.iter().map(|t| t.as_slice())).map_err(bad)?;
    match format {
        Format::Obj => {
            let text = source.and_then(|s| s.vertex_text.as_deref());
            let encoded = encode_obj_with_uv(mesh.positions(), uv, mesh.faces(), text);
            write_encoded_atomically(path, &encoded)
        }
        Format::Gltf | Format::Glb => {
            let binary = format == Format::Glb;
            let bytes = match file_layout(mesh, uv, source) {
                Some((p, t, f)) => encode_gltf(binary, &p, Some(&t), f),
                None => encode_gltf(binary, mesh.positions(), Some(uv), mesh.faces()),
            };
            write_atomically(path, &bytes.map_err(bad)?)
        }
        Format::Ply => {
            check_ply_size(mesh.num_vertices()).map_err(bad)?;
            let bytes = encode_ply(mesh.positions(), mesh.faces(), PlyUv::PerVertex(uv));
            write_atomically(path, &bytes)
        }
        other => Err(bad(no_texture_coordinates(other))),
    }
}

/// The problem of writing texture coordinates to a format that has none.
pub(crate) fn no_texture_coordinates(format: Format) -> WriteProblem {
    WriteProblem::NotWritable {
        format: format.extension(),
        what: "texture coordinates (write the mesh with its map as .obj, .ply, .gltf or \
               .glb, and the map itself with --flat as .surf.gii or a FreeSurfer surface)",
    }
}

/// PLY indices are written as `int`.
pub(crate) fn check_ply_size(vertices: usize) -> Result<(), WriteProblem> {
    if vertices > i32::MAX as usize {
        return Err(WriteProblem::TooLarge);
    }
    Ok(())
}

/// Writes points and triangles with no texture coordinates: a flat map `(u, v, 0)`, points
/// on the unit sphere, or any mesh. Format by extension as in [`write_mesh_with_uv`], and
/// also `.ply` (binary, double), `.surf.gii` (GIfTI, float32) and FreeSurfer surfaces
/// (`lh.sphere`, float32).
///
/// GIfTI and FreeSurfer outputs follow the field's conventions: points that all lie on the
/// unit sphere (a sphere map; |‖p‖ − 1| ≤ [`UNIT_SPHERE_TOLERANCE`]) are written at radius
/// 100, as FreeSurfer's `?h.sphere`; a flat map is written as it is given, `(u, v, 0)`.
/// Triangles and vertex order are the caller's (the input's). See [`write_flat_like`] to
/// keep the input file's transforms or volume geometry.
///
/// # Errors
/// [`IoError::BadWriteInput`] if a face index is out of range or a coordinate is not
/// finite; [`IoError::Write`] if the file cannot be written.
///
/// # Examples
/// ```
/// let dir = std::env::temp_dir().join(format!("conformap-io-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let out = dir.join("flat.obj");
/// conformap_io::write_flat(&out, &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]])?;
/// let back = conformap_io::read_mesh(&out)?;
/// assert_eq!(back.mesh.positions()[1], [1.0, 0.0, 0.0]);
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn write_flat(
    path: impl AsRef<Path>,
    points: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> Result<(), IoError> {
    write_flat_like(path, points, faces, None)
}

/// How far from 1 the norm of every point may be for [`write_flat`] to take the points
/// for a sphere map (and write GIfTI and FreeSurfer surfaces at radius 100).
pub const UNIT_SPHERE_TOLERANCE: f64 = 1e-9;

/// FreeSurfer's sphere radius (`?h.sphere`), which GIfTI and FreeSurfer sphere maps get.
pub const SPHERE_RADIUS: f64 = 100.0;

/// [`write_flat`], keeping what `source` says about the input surface when the output is
/// of the same kind: a GIfTI input's coordinate transforms go into a GIfTI output, a
/// FreeSurfer input's volume geometry into a FreeSurfer output.
///
/// # Errors
/// As [`write_flat`].
pub fn write_flat_like(
    path: impl AsRef<Path>,
    points: &[[f64; 3]],
    faces: &[[u32; 3]],
    source: Option<&SourceInfo>,
) -> Result<(), IoError> {
    let path = path.as_ref();
    let (format, bad) = write_target(path)?;
    for (face, f) in faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= points.len()) {
            return Err(bad(WriteProblem::FaceIndex {
                face,
                index,
                vertex_count: points.len(),
            }));
        }
    }
    check_finite(points.iter().map(|p| p.as_slice())).map_err(bad)?;
    let meta = source
        .filter(|s| s.format == format)
        .and_then(|s| s.surface.as_ref());
    match format {
        Format::Obj => write_encoded_atomically(path, &encode_obj(points, faces)),
        Format::Gltf | Format::Glb => {
            let bytes = encode_gltf(format == Format::Glb, points, None, faces).map_err(bad)?;
            write_atomically(path, &bytes)
        }
        Format::Ply => {
            check_ply_size(points.len()).map_err(bad)?;
            write_atomically(path, &encode_ply(points, faces, PlyUv::None))
        }
        Format::Gifti => {
            let scaled = sphere_at_radius_100(points);
            let bytes = encode_gifti_surface(scaled.as_deref().unwrap_or(points), faces, meta);
            write_atomically(path, &bytes)
        }
        Format::FreeSurfer => {
            let scaled = sphere_at_radius_100(points);
            let bytes =
                encode_freesurfer(scaled.as_deref().unwrap_or(points), faces, meta).map_err(bad)?;
            write_atomically(path, &bytes)
        }
        Format::Stl | Format::Off => Err(bad(WriteProblem::NotWritable {
            format: format.extension(),
            what: "output from conformap (it reads them only): write .obj, .ply, .gltf, \
                   .glb, .surf.gii or a FreeSurfer surface",
        })),
    }
}

/// Writes `mesh` with a seamed map: OBJ keeps the `v` lines in the mesh's order and count
/// and writes `f v/vt` with one `vt` per entry of `uv.texcoords` (exact round trip);
/// glTF/GLB split the vertices along the seams (one vertex per distinct position and
/// texture coordinate, `TEXCOORD_0`), as glTF requires.
///
/// The file appears complete or not at all.
///
/// # Errors
/// [`IoError::BadWriteInput`] if `uv` is not a map of `mesh` ([`CornerUv::check`]) or a
/// value is not finite; [`IoError::Write`] if the file cannot be written;
/// [`IoError::UnknownFormat`] for another extension.
///
/// # Examples
/// ```
/// use conformap_io::{read_mesh, write_mesh_with_corner_uv, CornerUv};
/// # let dir = std::env::temp_dir().join(format!("conformap-io-corner-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir).unwrap();
/// let mesh = conformap_mesh::TriMesh::try_new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// ).unwrap();
/// // the second face's copy of vertex 0 sits elsewhere: a seam along edge 0–2
/// let uv = CornerUv {
///     texcoords: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]],
///     faces: vec![[0, 1, 2], [4, 2, 3]],
/// };
/// let out = dir.join("seamed.obj");
/// write_mesh_with_corner_uv(&out, &mesh, &uv)?;
/// let back = read_mesh(&out)?;
/// assert_eq!(back.corner_uv.as_ref(), Some(&uv));
/// assert!(back.uv.is_none()); // not one texture coordinate per vertex
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn write_mesh_with_corner_uv(
    path: impl AsRef<Path>,
    mesh: &TriMesh,
    uv: &CornerUv,
) -> Result<(), IoError> {
    let path = path.as_ref();
    let (format, bad) = write_target(path)?;
    uv.check(mesh.num_faces()).map_err(bad)?;
    match format {
        Format::Obj => {
            let encoded =
                encode_obj_with_corner_uv(mesh.positions(), &uv.texcoords, mesh.faces(), &uv.faces);
            write_encoded_atomically(path, &encoded)
        }
        Format::Gltf | Format::Glb => {
            let (pairs, faces) = uv.split(mesh.faces());
            let positions: Vec<[f64; 3]> = pairs
                .iter()
                .map(|&(v, _)| mesh.positions()[v as usize])
                .collect();
            let texcoords: Vec<[f64; 2]> = pairs
                .iter()
                .map(|&(_, t)| uv.texcoords[t as usize])
                .collect();
            let bytes = encode_gltf(format == Format::Glb, &positions, Some(&texcoords), &faces)
                .map_err(bad)?;
            write_atomically(path, &bytes)
        }
        Format::Ply => {
            check_ply_size(mesh.num_vertices()).map_err(bad)?;
            let bytes = encode_ply(mesh.positions(), mesh.faces(), PlyUv::PerCorner(uv));
            write_atomically(path, &bytes)
        }
        other => Err(bad(no_texture_coordinates(other))),
    }
}

/// The points scaled to radius 100 if they all lie on the unit sphere; `None` otherwise.
fn sphere_at_radius_100(points: &[[f64; 3]]) -> Option<Vec<[f64; 3]>> {
    let on_sphere = |p: &[f64; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        (r - 1.0).abs() <= UNIT_SPHERE_TOLERANCE
    };
    (!points.is_empty() && points.iter().all(on_sphere)).then(|| {
        points
            .iter()
            .map(|p| p.map(|x| x * SPHERE_RADIUS))
            .collect()
    })
}

/// Writes per-vertex values (angle distortion, log area ratio...) as a GIfTI data file
/// (`.shape.gii` or `.func.gii`) that neuroimaging viewers load as overlays on the surface:
/// one float32 array per column, in the surface's vertex order, named by its metadata
/// `Name`.
///
/// # Errors
/// [`IoError::BadWriteInput`] if the name does not end in `.gii`, there is no column, or
/// the columns differ in length; [`IoError::Write`] if the file cannot be written.
///
/// # Examples
/// ```
/// let dir = std::env::temp_dir().join(format!("conformap-io-data-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let out = dir.join("lh.quality.shape.gii");
/// conformap_io::write_vertex_data(&out, &[("angle_distortion_deg", &[0.5, 1.0, 2.0])])?;
/// assert!(std::fs::read_to_string(&out).unwrap().contains("angle_distortion_deg"));
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn write_vertex_data(
    path: impl AsRef<Path>,
    columns: &[(&str, &[f64])],
) -> Result<(), IoError> {
    let path = path.as_ref();
    let (format, bad) = write_target(path)?;
    if format != Format::Gifti {
        return Err(bad(WriteProblem::NotWritable {
            format: format.extension(),
            what: "per-vertex data arrays (name the file .shape.gii or .func.gii)",
        }));
    }
    let Some((_, first)) = columns.first() else {
        return Err(bad(WriteProblem::Empty));
    };
    if let Some((_, c)) = columns.iter().find(|(_, c)| c.len() != first.len()) {
        return Err(bad(WriteProblem::UvCount {
            expected: first.len(),
            found: c.len(),
        }));
    }
    write_atomically(path, &encode_gifti_data(columns))
}

/// The format of an output `path` (by its extension), and the maker of the
/// [`IoError::BadWriteInput`] error naming that path.
pub(crate) fn write_target(
    path: &Path,
) -> Result<(Format, impl Fn(WriteProblem) -> IoError + Copy + '_), IoError> {
    let format = Format::from_path(path)?;
    let bad = move |problem| IoError::BadWriteInput {
        path: path.to_path_buf(),
        problem,
    };
    Ok((format, bad))
}

pub(crate) fn check_finite<'a>(rows: impl Iterator<Item = &'a [f64]>) -> Result<(), WriteProblem> {
    for (vertex, row) in rows.enumerate() {
        if let Some(&value) = row.iter().find(|x| !x.is_finite()) {
            return Err(WriteProblem::NonFinite { vertex, value });
        }
    }
    Ok(())
}

type Layout<'s> = (Vec<[f64; 3]>, Vec<[f64; 2]>, &'s [[u32; 3]]);

/// The glTF file's own vertex layout, if `source` is a glTF read that `mesh` still matches
/// (same faces through the weld map, every file vertex used).
fn file_layout<'s>(
    mesh: &TriMesh,
    uv: &[[f64; 2]],
    source: Option<&'s SourceInfo>,
) -> Option<Layout<'s>> {
    let src = source?;
    let (map, file_faces) = (src.weld_map.as_ref()?, src.file_faces.as_ref()?);
    let n = mesh.num_vertices();
    if map.iter().any(|&m| m == NO_VERTEX || m as usize >= n)
        || file_faces.len() != mesh.num_faces()
    {
        return None;
    }
    let same = file_faces.iter().zip(mesh.faces()).all(|(ff, mf)| {
        ff.iter()
            .zip(mf)
            .all(|(&i, &m)| map.get(i as usize) == Some(&m))
    });
    if !same {
        return None;
    }
    let positions = map.iter().map(|&m| mesh.positions()[m as usize]).collect();
    let uv = map.iter().map(|&m| uv[m as usize]).collect();
    Some((positions, uv, file_faces))
}
