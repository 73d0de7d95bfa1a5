//! Where a mesh element came from in its file, for error messages: the file element of
//! each vertex and face (PLY, STL, OFF, GIfTI, FreeSurfer), the glTF primitive of a welded
//! vertex or a face, or the OBJ line (kept in [`SourceInfo`]).

use conformap_mesh::MeshError;

use crate::error::{mesh_error_element, Element, Origin};
use crate::loaded::SourceInfo;

/// What a PLY, STL, OFF, GIfTI or FreeSurfer read keeps to name an element's origin.
#[derive(Debug, Clone, Default)]
pub(crate) struct ElementOrigins {
    /// What the file calls a vertex (`vertex`).
    pub(crate) vertex: &'static str,
    /// What the file calls a face (`face`, `facet`, `triangle`).
    pub(crate) face: &'static str,
    /// The file element of each mesh vertex; empty: the same index.
    pub(crate) vertex_of: Vec<usize>,
    /// The file element of each mesh face (a polygon gives several); empty: the same index.
    pub(crate) face_of: Vec<usize>,
}

impl ElementOrigins {
    /// Vertex `k` and face `k` are the file's `k`-th ones.
    pub(crate) fn identity(vertex: &'static str, face: &'static str) -> Self {
        Self {
            vertex,
            face,
            ..Self::default()
        }
    }

    pub(crate) fn origin(&self, element: Element) -> Option<Origin> {
        let pick = |of: &[usize], k: usize| {
            if of.is_empty() {
                Some(k)
            } else {
                of.get(k).copied()
            }
        };
        Some(match element {
            Element::Vertex(v) => Origin::Element {
                element: self.vertex,
                index: pick(&self.vertex_of, v)?,
            },
            Element::Face(f) => Origin::Element {
                element: self.face,
                index: pick(&self.face_of, f)?,
            },
        })
    }
}

/// What a glTF read keeps to name the origin of a welded vertex or a face.
#[derive(Debug, Clone, Default)]
pub(crate) struct GltfOrigins {
    pub(crate) prims: Vec<PrimRange>,
    /// For each welded vertex, its first file vertex.
    pub(crate) first_file: Vec<usize>,
}

/// One primitive's share of the concatenated file vertices and faces.
#[derive(Debug, Clone)]
pub(crate) struct PrimRange {
    pub(crate) mesh: usize,
    pub(crate) primitive: usize,
    pub(crate) vertex_start: usize,
    pub(crate) face_start: usize,
}

/// The primitive vertex of file vertex `v`.
pub(crate) fn vertex_origin(prims: &[PrimRange], v: usize) -> Option<Origin> {
    let p = prim_of(prims, |p| p.vertex_start, v)?;
    Some(Origin::GltfVertex {
        mesh: p.mesh,
        primitive: p.primitive,
        vertex: v - p.vertex_start,
    })
}

/// The primitive triangle of face `f`.
pub(crate) fn face_origin(prims: &[PrimRange], f: usize) -> Option<Origin> {
    let p = prim_of(prims, |p| p.face_start, f)?;
    Some(Origin::GltfTriangle {
        mesh: p.mesh,
        primitive: p.primitive,
        triangle: f - p.face_start,
    })
}

fn prim_of(
    prims: &[PrimRange],
    pick: impl Fn(&PrimRange) -> usize,
    k: usize,
) -> Option<&PrimRange> {
    let i = prims.partition_point(|p| pick(p) <= k);
    prims.get(i.checked_sub(1)?)
}

/// See [`RawMesh::origin_of`](crate::RawMesh::origin_of).
pub(crate) fn origin_in(
    src: &SourceInfo,
    origins: &GltfOrigins,
    elements: Option<&ElementOrigins>,
    error: &MeshError,
) -> Option<Origin> {
    let element = mesh_error_element(error)?;
    if let Some(e) = elements {
        return e.origin(element);
    }
    match (element, &src.vertex_lines, &src.face_lines) {
        (Element::Vertex(v), Some(lines), _) => lines.get(v).map(|&l| Origin::Line(l)),
        (Element::Face(f), _, Some(lines)) => lines.get(f).map(|&l| Origin::Line(l)),
        (Element::Vertex(v), None, _) => {
            let file = *origins.first_file.get(v)?;
            vertex_origin(&origins.prims, file)
        }
        (Element::Face(f), _, None) => face_origin(&origins.prims, f),
    }
}
