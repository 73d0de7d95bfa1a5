//! The scene's triangle soup and its welding into one validated mesh.

use std::path::Path;

use crate::coincident::classes;
use crate::corner_uv::CornerUv;
use crate::error::{Origin, UvProblem};
use crate::loaded::{Format, SourceInfo};
use crate::origins::{vertex_origin, GltfOrigins, PrimRange};
use crate::raw::RawMesh;

/// Node instancing may repeat a primitive, so the scene can be far larger than the file.
/// The soup may hold at most `INSTANCING_LIMIT ×` the vertices the buffers could store
/// uninstanced (12 bytes each), plus [`SOUP_FLOOR`]; beyond that the file is rejected
/// rather than allowed to exhaust memory.
pub(crate) const INSTANCING_LIMIT: usize = 64;
/// See [`INSTANCING_LIMIT`].
pub(crate) const SOUP_FLOOR: usize = 1 << 20;

/// The triangle primitives of the scene, concatenated, before welding.
#[derive(Default)]
pub(crate) struct Soup {
    /// Most file vertices allowed (see [`INSTANCING_LIMIT`]).
    pub(crate) limit: usize,
    pub(crate) positions: Vec<[f64; 3]>,
    pub(crate) uv: Vec<Option<[f64; 2]>>,
    pub(crate) faces: Vec<[u32; 3]>,
    pub(crate) prims: Vec<PrimRange>,
    pub(crate) notes: Vec<String>,
}

/// Welds bit-identical positions of referenced file vertices (first occurrence wins) and
/// checks the texture coordinates; validation is left to [`RawMesh::validate`].
pub(crate) fn weld(mut soup: Soup, path: &Path, format: Format) -> RawMesh {
    let nfile = soup.positions.len();
    let mut referenced = vec![false; nfile];
    for &i in soup.faces.iter().flatten() {
        referenced[i as usize] = true;
    }
    let (map, first_file) = classes(&soup.positions, Some(&referenced));
    let positions: Vec<[f64; 3]> = first_file.iter().map(|&i| soup.positions[i]).collect();
    let faces: Vec<[u32; 3]> = soup
        .faces
        .iter()
        .map(|f| f.map(|i| map[i as usize]))
        .collect();
    let mut notes = std::mem::take(&mut soup.notes);
    let unreferenced = referenced.iter().filter(|r| !**r).count();
    if unreferenced > 0 {
        notes.push(format!(
            "{unreferenced} file vertices are used by no triangle; dropped"
        ));
    }
    if first_file.len() + unreferenced < nfile {
        notes.push(format!(
            "welded {} file vertices into {} (bit-identical positions)",
            nfile - unreferenced,
            first_file.len()
        ));
    }
    let uv = weld_uv(&soup, &map, &referenced, first_file.len())
        .map(|uv| uv.into_iter().map(Some).collect());
    // per corner: the file vertices' coordinates under the file's faces (seams included)
    let corner_uv = soup
        .faces
        .iter()
        .flatten()
        .all(|&i| soup.uv[i as usize].is_some())
        .then(|| CornerUv {
            texcoords: soup.uv.iter().map(|t| t.unwrap_or([0.0, 0.0])).collect(),
            faces: soup.faces.clone(),
        })
        .filter(|c| !c.faces.is_empty());
    let mut source = SourceInfo::new(path.to_path_buf(), format);
    source.file_vertex_count = nfile;
    source.weld_map = Some(map);
    source.file_faces = Some(soup.faces);
    source.notes = notes;
    let origins = GltfOrigins {
        prims: soup.prims,
        first_file,
    };
    RawMesh::new(positions, faces, uv, source, Some(origins)).with_corner_uv(corner_uv)
}

/// One texture coordinate per welded vertex, or the first seam / missing one.
fn weld_uv(
    soup: &Soup,
    map: &[u32],
    referenced: &[bool],
    n: usize,
) -> Result<Vec<[f64; 2]>, UvProblem> {
    let used = |i: &usize| referenced[*i];
    if (0..soup.uv.len())
        .filter(used)
        .all(|i| soup.uv[i].is_none())
    {
        return Err(UvProblem::Absent);
    }
    // every soup vertex lies in some primitive's range; the fallback is never used
    let origin = |i: usize| {
        vertex_origin(&soup.prims, i).unwrap_or(Origin::GltfVertex {
            mesh: 0,
            primitive: 0,
            vertex: i,
        })
    };
    let mut first: Vec<Option<([f64; 2], usize)>> = vec![None; n];
    for i in (0..soup.uv.len()).filter(used) {
        let t = soup.uv[i].ok_or(UvProblem::Missing { origin: origin(i) })?;
        let v = map[i] as usize;
        match first[v] {
            None => first[v] = Some((t, i)),
            Some((t0, i0)) => {
                if t0.map(f64::to_bits) != t.map(f64::to_bits) {
                    return Err(UvProblem::Seam {
                        vertex: v,
                        origin: origin(i),
                        first: origin(i0),
                    });
                }
            }
        }
    }
    first
        .into_iter()
        .map(|s| s.map(|(t, _)| t).ok_or(UvProblem::Absent))
        .collect()
}
