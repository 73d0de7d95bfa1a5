//! glTF/GLB reading: scene traversal with node transforms, primitive expansion, welding.

use std::path::Path;

use gltf::mesh::Mode;
use gltf::{Gltf, Semantic};

use super::buffers::load_buffers;
use super::container::{check_container, gltf1_error};
use super::weld::{weld, Soup, INSTANCING_LIMIT, SOUP_FLOOR};
use crate::error::{IoError, GLTF_HINT};
use crate::loaded::Format;
use crate::origins::PrimRange;
use crate::raw::RawMesh;

type Matrix = [[f64; 4]; 4];

const IDENTITY: Matrix = [
    [1.0, 0.0, 0.0, 0.0],
    [0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0],
    [0.0, 0.0, 0.0, 1.0],
];
/// Reads glTF or GLB bytes without validating the welded mesh; external buffers are
/// resolved against `base` (none: only embedded data is allowed). `path` names the file in
/// errors.
pub(crate) fn read_gltf_raw(
    bytes: &[u8],
    path: &Path,
    base: Option<&Path>,
    format: Format,
) -> Result<RawMesh, IoError> {
    check_container(bytes, path, format)?;
    let gltf_err = |source| {
        gltf1_error(bytes, path).unwrap_or_else(|| IoError::Gltf {
            path: path.to_path_buf(),
            source,
        })
    };
    let Gltf { document, blob } = Gltf::from_slice_without_validation(bytes).map_err(gltf_err)?;
    if let Some(e) = gltf1_error_of(&document, path) {
        return Err(e);
    }
    validate(&document).map_err(gltf_err)?;
    let buffers = load_buffers(&document, base, blob, path)?;
    let soup = collect(&document, &buffers, path)?;
    Ok(weld(soup, path, format))
}

/// A document that parsed as glTF 2.0 but says it is another version.
fn gltf1_error_of(document: &gltf::Document, path: &Path) -> Option<IoError> {
    let version = &document.as_json().asset.version;
    if version.starts_with('2') {
        return None;
    }
    let json = format!(r#"{{"asset":{{"version":{version:?}}}}}"#);
    gltf1_error(json.as_bytes(), path).or_else(|| {
        let msg = format!("asset.version is \"{version}\"; only glTF 2.0 is supported");
        Some(super::container::container_error(path, msg))
    })
}

/// The `gltf` crate's validation (every index in range, required fields present), except
/// that a `POSITION` accessor without `min`/`max` is accepted: the spec requires them, but
/// exporters omit them and this reader does not use them.
fn validate(document: &gltf::Document) -> Result<(), gltf::Error> {
    use gltf::json::validation::{Checked, Error, Validate};
    let root = document.as_json();
    // gltf-json's primitive hook indexes `accessors[POSITION]` unchecked: check it first
    let positions = Checked::Valid(gltf::json::mesh::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(i) = prim.attributes.get(&positions) {
                if i.value() >= root.accessors.len() {
                    let path = gltf::json::Path::new()
                        .field("meshes")
                        .index(m)
                        .field("primitives")
                        .index(p)
                        .field("attributes")
                        .key("POSITION");
                    return Err(gltf::Error::Validation(vec![(
                        path,
                        Error::IndexOutOfBounds,
                    )]));
                }
            }
        }
    }
    let mut errors = Vec::new();
    root.validate(root, gltf::json::Path::new, &mut |path, error| {
        let path = path();
        let bounds = path.as_str().ends_with(".min") || path.as_str().ends_with(".max");
        if !(bounds && error == Error::Missing) {
            errors.push((path, error));
        }
    });
    if errors.is_empty() {
        Ok(())
    } else {
        Err(gltf::Error::Validation(errors))
    }
}

fn data_error(
    path: &Path,
    mesh: Option<usize>,
    primitive: Option<usize>,
    accessor: Option<usize>,
    problem: impl Into<String>,
) -> IoError {
    IoError::GltfData {
        path: path.to_path_buf(),
        mesh,
        primitive,
        accessor,
        problem: problem.into(),
        hint: GLTF_HINT,
    }
}

/// Mesh instances (mesh index, world transform) of the default scene (else the first
/// scene), or every mesh untransformed if there is no scene.
fn instances(doc: &gltf::Document, path: &Path) -> Result<Vec<(usize, Matrix)>, IoError> {
    let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) else {
        return Ok(doc.meshes().map(|m| (m.index(), IDENTITY)).collect());
    };
    let mut visited = vec![false; doc.nodes().len()];
    let mut out = Vec::new();
    let mut stack: Vec<(gltf::Node, Matrix)> = scene.nodes().map(|n| (n, IDENTITY)).collect();
    stack.reverse();
    while let Some((node, parent)) = stack.pop() {
        let seen = visited
            .get_mut(node.index())
            .ok_or_else(|| data_error(path, None, None, None, "a node index is out of range"))?;
        if std::mem::replace(seen, true) {
            let msg = format!(
                "node {} is reached twice (a cycle or a shared node)",
                node.index()
            );
            return Err(data_error(path, None, None, None, msg));
        }
        let world = mul(&parent, &to_f64(node.transform().matrix()));
        if let Some(mesh) = node.mesh() {
            out.push((mesh.index(), world));
        }
        let mut children: Vec<_> = node.children().map(|c| (c, world)).collect();
        children.reverse();
        stack.extend(children);
    }
    Ok(out)
}

fn collect(doc: &gltf::Document, buffers: &[Vec<u8>], path: &Path) -> Result<Soup, IoError> {
    let bytes: usize = buffers.iter().map(Vec::len).sum();
    let mut soup = Soup {
        limit: (bytes / 12)
            .saturating_mul(INSTANCING_LIMIT)
            .saturating_add(SOUP_FLOOR),
        ..Soup::default()
    };
    let mut first_ignored = None;
    for (mesh_index, world) in instances(doc, path)? {
        let Some(mesh) = doc.meshes().nth(mesh_index) else {
            return Err(data_error(
                path,
                Some(mesh_index),
                None,
                None,
                "no such mesh",
            ));
        };
        for prim in mesh.primitives() {
            let ignored = add_primitive(&mut soup, &prim, mesh_index, &world, buffers, path)?;
            if let (None, Some(mode)) = (first_ignored, ignored) {
                first_ignored = Some((mesh_index, prim.index(), mode));
            }
        }
    }
    if let (true, Some((mesh, primitive, mode))) = (soup.faces.is_empty(), first_ignored) {
        let msg = format!(
            "the file has no triangles: its primitives are {} (as this one), which draw \
             lines or points, not a surface",
            mode_name(mode)
        );
        return Err(
            data_error(path, Some(mesh), Some(primitive), None, msg).with_hint(
                "export the surface as triangles (glTF mode TRIANGLES, 4); a line drawing or \
             point cloud has no conformal map",
            ),
        );
    }
    Ok(soup)
}

/// The glTF spec's name and number of a primitive mode.
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Points => "POINTS (mode 0)",
        Mode::Lines => "LINES (mode 1)",
        Mode::LineLoop => "LINE_LOOP (mode 2)",
        Mode::LineStrip => "LINE_STRIP (mode 3)",
        Mode::Triangles => "TRIANGLES (mode 4)",
        Mode::TriangleStrip => "TRIANGLE_STRIP (mode 5)",
        Mode::TriangleFan => "TRIANGLE_FAN (mode 6)",
    }
}

/// Adds one primitive's triangles to the soup; returns its mode if that is not a triangle
/// mode (the primitive is then ignored, with a note).
fn add_primitive(
    soup: &mut Soup,
    prim: &gltf::Primitive<'_>,
    mesh: usize,
    world: &Matrix,
    buffers: &[Vec<u8>],
    path: &Path,
) -> Result<Option<Mode>, IoError> {
    let p = prim.index();
    let err = |acc: Option<usize>, msg: String| data_error(path, Some(mesh), Some(p), acc, msg);
    let mode = prim.mode();
    if !matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    ) {
        soup.notes.push(format!(
            "mesh {mesh}, primitive {p}: mode {} is not triangles; ignored",
            mode_name(mode)
        ));
        return Ok(Some(mode));
    }
    let pos_acc = prim
        .get(&Semantic::Positions)
        .ok_or_else(|| err(None, "primitive has no POSITION attribute".into()))?;
    let positions = super::accessor::read_floats::<3>(&pos_acc, buffers, false)
        .map_err(|m| err(Some(pos_acc.index()), format!("POSITION: {m}")))?;
    let n = positions.len();
    if soup.positions.len().saturating_add(n) > soup.limit {
        let msg = format!(
            "node instancing expands the scene past {} vertices",
            soup.limit
        );
        return Err(err(Some(pos_acc.index()), msg));
    }
    let uv = match prim.get(&Semantic::TexCoords(0)) {
        Some(acc) => {
            let uv = super::accessor::read_floats::<2>(&acc, buffers, true)
                .map_err(|m| err(Some(acc.index()), format!("TEXCOORD_0: {m}")))?;
            if uv.len() != n {
                let msg = format!("TEXCOORD_0 has {} elements for {n} positions", uv.len());
                return Err(err(Some(acc.index()), msg));
            }
            Some(uv)
        }
        None => None,
    };
    let indices = match prim.indices() {
        Some(acc) => {
            let idx = super::accessor::read_indices(&acc, buffers)
                .map_err(|m| err(Some(acc.index()), format!("indices: {m}")))?;
            if let Some(bad) = idx.iter().find(|&&i| i as usize >= n) {
                let msg = format!("index {bad} is out of range ({n} positions)");
                return Err(err(Some(acc.index()), msg));
            }
            idx
        }
        None => (0..n as u32).collect(),
    };
    let (mut tris, skipped) = expand(&indices, mode);
    if skipped > 0 {
        soup.notes.push(format!(
            "mesh {mesh}, primitive {p}: {skipped} degenerate strip/fan triangle(s) or \
             trailing index(es) skipped"
        ));
    }
    if det3(world) < 0.0 {
        // a mirroring transform flips the winding (glTF spec 3.7.4)
        tris.iter_mut().for_each(|t| t.swap(1, 2));
    }
    let start = soup.positions.len();
    let base = u32::try_from(start + n).map_err(|_| err(None, "too many vertices".into()))?;
    let base = base - n as u32;
    soup.prims.push(PrimRange {
        mesh,
        primitive: p,
        vertex_start: start,
        face_start: soup.faces.len(),
    });
    soup.positions
        .extend(positions.iter().map(|q| transform(world, q)));
    match uv {
        Some(uv) => soup.uv.extend(uv.iter().map(|t| Some([t[0], 1.0 - t[1]]))),
        None => soup.uv.extend(std::iter::repeat_n(None, n)),
    }
    soup.faces
        .extend(tris.iter().map(|t| [t[0] + base, t[1] + base, t[2] + base]));
    Ok(None)
}

/// Triangles of a primitive (local indices) and how many were skipped: strip/fan
/// triangles that repeat a vertex (stitching), or indices past the last full triangle.
fn expand(idx: &[u32], mode: Mode) -> (Vec<[u32; 3]>, usize) {
    let raw: Vec<[u32; 3]> = match mode {
        Mode::TriangleStrip => (0..idx.len().saturating_sub(2))
            .map(|i| {
                let (a, b, c) = (idx[i], idx[i + 1], idx[i + 2]);
                if i % 2 == 0 {
                    [a, b, c]
                } else {
                    [b, a, c]
                }
            })
            .collect(),
        Mode::TriangleFan => (1..idx.len().saturating_sub(1))
            .map(|i| [idx[i], idx[i + 1], idx[0]])
            .collect(),
        _ => {
            let tris: Vec<[u32; 3]> = idx.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            let rest = idx.len() % 3;
            return (tris, rest);
        }
    };
    let total = raw.len();
    let kept: Vec<[u32; 3]> = raw
        .into_iter()
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    let skipped = total - kept.len();
    (kept, skipped)
}

fn to_f64(m: [[f32; 4]; 4]) -> Matrix {
    m.map(|col| col.map(f64::from))
}

/// Column-major product `a · b`.
fn mul(a: &Matrix, b: &Matrix) -> Matrix {
    let mut out = [[0.0; 4]; 4];
    for (c, col) in out.iter_mut().enumerate() {
        for (r, x) in col.iter_mut().enumerate() {
            *x = (0..4).map(|k| a[k][r] * b[c][k]).sum();
        }
    }
    out
}

fn transform(m: &Matrix, p: &[f64; 3]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (r, x) in out.iter_mut().enumerate() {
        *x = m[0][r] * p[0] + m[1][r] * p[1] + m[2][r] * p[2] + m[3][r];
    }
    out
}

fn det3(m: &Matrix) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2])
        - m[1][0] * (m[0][1] * m[2][2] - m[2][1] * m[0][2])
        + m[2][0] * (m[0][1] * m[1][2] - m[1][1] * m[0][2])
}
