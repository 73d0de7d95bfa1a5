//! What a map job's solve returns to the pipeline ([`Solved`]): the texture coordinates
//! ([`TexCoords`]), the flat mesh, the report sections, the summary line, and where the map
//! lands for its pictures ([`PictureDomain`]).

use conformap_mesh::TriMesh;

use crate::report::{MetricsSection, ParamInfo, Sections, SolverSection, StageTimings};

/// Where a command's map lands, for its pictures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PictureDomain {
    /// A planar map: the texture coordinates of [`Solved::uv`] (an affine image of the map,
    /// which the pictures fit to their frame anyway).
    Plane,
    /// A sphere map: the unit-sphere points of [`Solved::flat`].
    Sphere,
}

/// What a command's solve returns to the pipeline.
#[derive(Debug)]
pub struct Solved {
    /// The report's `method`.
    pub method: String,
    /// The texture coordinates written with the mesh to `-o`.
    pub uv: TexCoords,
    /// The `--flat` mesh: points, and faces when they are not the mesh's.
    pub flat: (Vec<[f64; 3]>, Option<Vec<[u32; 3]>>),
    /// The report's `solver` object.
    pub solver: SolverSection,
    /// The report's `param` object, for commands that read a map.
    pub param: Option<ParamInfo>,
    /// Top-level report sections of the command (`factorization`, `circle_domain`).
    pub sections: Sections,
    /// The report's `metrics` object.
    pub metrics: MetricsSection,
    /// Timings of the solve: `read` holds the reading of other inputs (a map file), which
    /// the pipeline adds to its own; `write` and `total` are the pipeline's.
    pub timings: StageTimings,
    /// Why `--strict` refuses this result (did not converge, inverted faces), if it does.
    pub strict_violation: Option<String>,
    /// The summary line (without the mesh path and the total time, which the pipeline
    /// adds).
    pub summary: String,
    /// Where this result lands for the `--png` pictures when it differs from the
    /// command's [`MapJob::picture_domain`](crate::pipeline::MapJob::picture_domain)
    /// (`global --topology-opt` returning the starting sphere map: drawn as `sphere` draws
    /// it); `None`: the command's.
    pub picture_domain: Option<PictureDomain>,
}

/// The texture coordinates a command writes to `-o`.
#[derive(Debug)]
pub enum TexCoords {
    /// One per vertex of the input mesh (disk, holes, sphere, mobius).
    PerVertex(Vec<[f64; 2]>),
    /// Per face corner of the input mesh: a seamed map (`global`), written as `f v/vt`.
    PerCorner(conformap_io::CornerUv),
    /// Per face corner of a refinement of the input mesh the command had to make (a
    /// double covering that split boundary chords): the refined mesh is written instead of
    /// the input, and the report says so.
    Refined {
        /// The mesh written (its first vertices are the input's, in the input's order).
        mesh: TriMesh,
        /// Its seamed map.
        uv: conformap_io::CornerUv,
    },
}

impl From<Vec<[f64; 2]>> for TexCoords {
    fn from(uv: Vec<[f64; 2]>) -> Self {
        Self::PerVertex(uv)
    }
}
