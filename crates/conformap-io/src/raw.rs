//! A mesh as its file gives it, before validation ([`RawMesh`]), for callers that repair a
//! mesh before validating it (the CLI's `--repair`); [`read_raw_mesh`](crate::read_raw_mesh)
//! reads one and [`read_mesh`](crate::read_mesh) is that followed by
//! [`RawMesh::validate`].

use conformap_mesh::{MeshError, TriMesh};

use crate::corner_uv::CornerUv;
use crate::error::{IoError, Origin, UvProblem};
use crate::loaded::{LoadedMesh, SourceInfo};
use crate::origins::origin_in;
pub(crate) use crate::origins::{ElementOrigins, GltfOrigins};

/// A mesh as the file gives it, parsed but not validated: positions and triangles may have
/// any defect [`TriMesh::try_new`] rejects except an empty file (an error already).
///
/// Numbering is that of [`LoadedMesh`]: for OBJ, vertex `k` is the file's `k`-th `v` line
/// and face `k` the `k`-th triangle; for glTF, vertices are welded (bit-identical positions
/// merged, vertices no triangle uses left out; see [`SourceInfo::weld_map`]).
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct RawMesh {
    /// Vertex positions (possibly non-finite).
    pub positions: Vec<[f64; 3]>,
    /// Triangles (indices are in range; faces may be degenerate, duplicated, non-manifold or
    /// inconsistently oriented).
    pub faces: Vec<[u32; 3]>,
    /// The texture coordinate of each vertex (`None` for a vertex no face uses), when the
    /// file gives one per vertex; `None` otherwise (see [`Self::uv_problem`]).
    pub uv: Option<Vec<Option<[f64; 2]>>>,
    /// Why [`Self::uv`] is `None`; `None` when it is `Some`.
    pub uv_problem: Option<UvProblem>,
    /// The texture coordinate of every face corner, when every corner has one (seamed maps
    /// included); `None` when some corner has none.
    pub corner_uv: Option<CornerUv>,
    /// Where the mesh came from and how its elements map to the file.
    pub source: SourceInfo,
    /// glTF: the primitive ranges and the file vertex of each welded vertex, to name an
    /// element's origin. Empty for OBJ (lines are in `source`).
    origins: GltfOrigins,
    /// PLY, STL, OFF, GIfTI, FreeSurfer: the file element of each vertex and face.
    elements: Option<ElementOrigins>,
}

impl RawMesh {
    pub(crate) fn new(
        positions: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        uv: Result<Vec<Option<[f64; 2]>>, UvProblem>,
        source: SourceInfo,
        origins: Option<GltfOrigins>,
    ) -> Self {
        let (uv, uv_problem) = match uv {
            Ok(uv) => (Some(uv), None),
            Err(p) => (None, Some(p)),
        };
        Self {
            positions,
            faces,
            uv,
            uv_problem,
            corner_uv: None,
            source,
            origins: origins.unwrap_or_default(),
            elements: None,
        }
    }

    /// Sets the file elements that vertices and faces come from (formats other than OBJ
    /// and glTF).
    pub(crate) fn with_elements(mut self, elements: ElementOrigins) -> Self {
        self.elements = Some(elements);
        self
    }

    /// Sets [`Self::corner_uv`].
    pub(crate) fn with_corner_uv(mut self, corner_uv: Option<CornerUv>) -> Self {
        self.corner_uv = corner_uv;
        self
    }

    /// The file place of vertex `v` (this mesh's numbering).
    pub(crate) fn vertex_place(&self, v: usize) -> Option<Origin> {
        let at = MeshError::UnreferencedVertex {
            vertex: v,
            count: 1,
        };
        self.origin_of(&at)
    }

    /// After welding: welded vertex `c` is the former vertex `first[c]`.
    pub(crate) fn reset_origins(&mut self, first: &[usize]) {
        if !self.origins.first_file.is_empty() {
            let old = std::mem::take(&mut self.origins.first_file);
            self.origins.first_file = first.iter().map(|&i| old[i]).collect();
        }
        if let Some(e) = &mut self.elements {
            let old = std::mem::take(&mut e.vertex_of);
            e.vertex_of = first
                .iter()
                .map(|&i| if old.is_empty() { i } else { old[i] })
                .collect();
        }
    }

    /// The file place of the vertex or face `error` names (its numbering must be this
    /// mesh's): an OBJ line, a glTF primitive vertex or triangle; `None` for whole-mesh
    /// errors or an index past the mesh.
    pub fn origin_of(&self, error: &MeshError) -> Option<Origin> {
        origin_in(&self.source, &self.origins, self.elements.as_ref(), error)
    }

    /// The [`IoError::InvalidMesh`] for a validation error about this mesh (this mesh's
    /// numbering), with the file place of the element it names.
    pub fn invalid_mesh(&self, error: MeshError) -> IoError {
        IoError::InvalidMesh {
            path: self.source.path.clone(),
            origin: self.origin_of(&error),
            source: error,
        }
    }

    /// Validates the mesh ([`TriMesh::try_new`]), as [`read_mesh`](crate::read_mesh) does.
    ///
    /// # Errors
    /// [`IoError::InvalidMesh`] naming the file place of the offending element.
    ///
    /// # Examples
    /// ```
    /// use conformap_io::{read_raw_mesh_from_bytes, Format, IoError, Origin};
    /// // the second face repeats the first: the raw read succeeds, validation does not
    /// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 2 3 1\n";
    /// let raw = read_raw_mesh_from_bytes(obj, Format::Obj)?;
    /// assert_eq!(raw.faces.len(), 2);
    /// let err = raw.validate().unwrap_err();
    /// assert!(matches!(err, IoError::InvalidMesh { origin: Some(Origin::Line(5)), .. }));
    /// # Ok::<(), IoError>(())
    /// ```
    pub fn validate(self) -> Result<LoadedMesh, IoError> {
        let Self {
            positions,
            faces,
            uv,
            uv_problem,
            corner_uv,
            source,
            origins,
            elements,
        } = self;
        let mesh = TriMesh::try_new(positions, faces).map_err(|e| IoError::InvalidMesh {
            path: source.path.clone(),
            origin: origin_in(&source, &origins, elements.as_ref(), &e),
            source: e,
        })?;
        // a valid mesh references every vertex, so a per-vertex uv has every slot filled
        let uv = uv.map(|uv| uv.into_iter().collect::<Option<Vec<_>>>());
        let (uv, uv_problem) = match (uv, uv_problem) {
            (Some(Some(uv)), _) => (Some(uv), None),
            (Some(None), _) => (None, Some(UvProblem::Absent)),
            (None, problem) => (None, problem),
        };
        Ok(LoadedMesh {
            mesh,
            uv,
            uv_problem,
            corner_uv,
            source,
        })
    }
}
