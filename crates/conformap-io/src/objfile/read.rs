//! OBJ reading: our scan for structure and lines, `tobj` for the numbers.

use std::path::Path;

use conformap_mesh::MeshError;

use super::scan::{scan, Scan, NO_UV};
use crate::error::{IoError, ObjProblem, Origin, UvProblem};
use crate::loaded::{Format, LoadedMesh, SourceInfo};
use crate::raw::RawMesh;

/// Reads and validates an OBJ file's bytes. `path` only names the file in errors.
pub(crate) fn read_obj(bytes: &[u8], path: &Path) -> Result<LoadedMesh, IoError> {
    read_obj_raw(bytes, path)?.validate()
}

/// Reads an OBJ file's bytes without validating the mesh. `path` only names the file in
/// errors.
pub(crate) fn read_obj_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let syntax = |(line, problem)| IoError::ObjSyntax {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        syntax((line, ObjProblem::NotUtf8))
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let scanned = scan(text, false).map_err(syntax)?;
    let invalid = |source, origin| IoError::InvalidMesh {
        path: path.to_path_buf(),
        origin,
        source,
    };
    if scanned.vertex_lines.is_empty() {
        return Err(invalid(MeshError::NoVertices, None));
    }
    let backend = |message: String| IoError::Backend {
        path: path.to_path_buf(),
        message,
    };
    // `..Default::default()`: LoadOptions grows fields under tobj's optional features
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: true,
        ignore_points: false,
        ignore_lines: false,
        ..Default::default()
    };
    let loaded = tobj::load_obj_buf(&mut scanned.tobj_text.as_bytes(), &options, |_| {
        Err(tobj::LoadError::GenericFailure)
    });
    let models = match loaded {
        Ok((models, _materials)) => models,
        Err(e) => {
            // tobj names no line: find the first one it would reject
            scan(text, true).map_err(syntax)?;
            return Err(backend(format!(
                "tobj rejected the text ({e}) at no line we found"
            )));
        }
    };
    let [model] = models.as_slice() else {
        return Err(backend(format!(
            "tobj returned {} models, not 1",
            models.len()
        )));
    };
    let positions = positions_in_file_order(&model.mesh, &scanned).map_err(backend)?;
    let uv = per_vertex_uv(&model.mesh, &scanned, positions.len()).map_err(backend)?;
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Obj);
    source.file_vertex_count = scanned.vertex_lines.len();
    source.notes = scanned.notes;
    source.vertex_lines = Some(scanned.vertex_lines);
    source.face_lines = Some(scanned.face_lines);
    Ok(RawMesh::new(positions, scanned.faces, uv, source, None))
}

/// Checks that `tobj` numbered the vertices in file order (thanks to the synthetic first
/// polygon) and triangulated the faces as the scan did; returns the positions.
fn positions_in_file_order(mesh: &tobj::Mesh, s: &Scan) -> Result<Vec<[f64; 3]>, String> {
    let n = s.vertex_lines.len();
    if mesh.positions.len() != 3 * n {
        return Err(format!(
            "{} coordinates for {n} vertices",
            mesh.positions.len()
        ));
    }
    let syn = s.synthetic_triangles;
    if mesh.indices.len() != 3 * (syn + s.faces.len()) {
        return Err(format!("{} face indices", mesh.indices.len()));
    }
    let expected_synthetic = (0..syn).flat_map(|t| {
        let last = n.saturating_sub(1) as u32;
        [0, (t as u32 + 1).min(last), (t as u32 + 2).min(last)]
    });
    let expected = expected_synthetic.chain(s.faces.iter().flatten().copied());
    if !mesh.indices.iter().copied().eq(expected) {
        return Err("vertex numbering differs from the file's".to_owned());
    }
    Ok(mesh
        .positions
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect())
}

/// A texture coordinate per vertex (`None` for a vertex no face uses).
type VertexUv = Vec<Option<[f64; 2]>>;

/// One texture coordinate per vertex, or why there is not. The outer error is a backend
/// inconsistency.
fn per_vertex_uv(
    mesh: &tobj::Mesh,
    s: &Scan,
    n: usize,
) -> Result<Result<VertexUv, UvProblem>, String> {
    let corners = s.face_uv.iter().flatten();
    if corners.clone().all(|&t| t == NO_UV) {
        return Ok(Err(UvProblem::Absent));
    }
    let skip = 3 * s.synthetic_triangles;
    let local = mesh.texcoord_indices.get(skip..).unwrap_or_default();
    if local.len() != 3 * s.faces.len() {
        return Err(format!("{} texture indices", mesh.texcoord_indices.len()));
    }
    let value = |l: u32| -> Option<[f64; 2]> {
        let i = 2 * l as usize;
        Some([*mesh.texcoords.get(i)?, *mesh.texcoords.get(i + 1)?])
    };
    // per vertex: (vt index, value, line) of its first corner
    let mut first: Vec<Option<(u32, [f64; 2], usize)>> = vec![None; n];
    for (c, &t) in corners.enumerate() {
        let (f, k) = (c / 3, c % 3);
        let line = s.face_lines[f];
        if t == NO_UV {
            return Ok(Err(UvProblem::Missing {
                origin: Origin::Line(line),
            }));
        }
        let uv = value(local[c]).ok_or("texture index past the data")?;
        let v = s.faces[f][k] as usize;
        match first.get_mut(v) {
            Some(slot @ None) => *slot = Some((t, uv, line)),
            Some(Some((t0, uv0, line0))) => {
                let same = *t0 == t
                    || (uv0[0].to_bits(), uv0[1].to_bits()) == (uv[0].to_bits(), uv[1].to_bits());
                if !same {
                    return Ok(Err(UvProblem::Seam {
                        vertex: v,
                        origin: Origin::Line(line),
                        first: Origin::Line(*line0),
                    }));
                }
            }
            None => return Err("face vertex past the positions".to_owned()),
        }
    }
    // a vertex no face uses has no texture coordinate
    Ok(Ok(first
        .into_iter()
        .map(|slot| slot.map(|(_, uv, _)| uv))
        .collect()))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    /// Why the synthetic first polygon exists: without it, `tobj` (even with
    /// `single_index: false`) numbers each object's vertices by first use, restarting per
    /// object. If this test starts failing, `tobj` changed and the workaround may go.
    #[test]
    fn tobj_alone_renumbers_vertices_per_object() {
        let text = "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 1 2\no b\nv 5 5 5\nf 4 1 2\n";
        let options = tobj::LoadOptions {
            triangulate: true,
            ..Default::default()
        };
        let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, |_| {
            Err(tobj::LoadError::GenericFailure)
        })
        .unwrap();
        assert_eq!(models.len(), 2);
        assert_eq!(models[0].mesh.indices, vec![0, 1, 2]); // file's 3 1 2, renumbered
        assert_eq!(models[0].mesh.positions[..3], [0.0, 1.0, 0.0]); // the 3rd `v` first
        assert_eq!(models[1].mesh.indices, vec![0, 1, 2]); // global 4 1 2, restarted
    }

    #[test]
    fn synthetic_polygon_keeps_file_order() {
        let text = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 1 2\no b\nv 5 5 5\nf 4 1 2\n";
        let loaded = super::read_obj(text, std::path::Path::new("t.obj"));
        // vertices 0..3 in file order; the faces are fine but the two share vertices 0, 1
        // and run edge 0-1 the same way, so validation names face 1 on line 8
        let err = loaded.unwrap_err();
        assert!(err.to_string().starts_with("t.obj:8: "), "{err}");
    }
}
