//! One connected component of the input as charted: its faces and vertices in the input,
//! its mesh, chart, quality and the flat pieces it was laid out as (what the build, the
//! layout and the neck cuts share).

use conformap_mesh::TriMesh;

use crate::chart::{Chart, ChartQuality, Piece};

/// One component's chart and where its faces and vertices came from.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ComponentChart {
    /// Input face of each of the component's faces.
    pub faces: Vec<u32>,
    /// Input vertex of each of the component's vertices.
    pub vertices: Vec<u32>,
    /// The component's mesh.
    pub mesh: TriMesh,
    /// Its chart.
    pub chart: Chart,
    /// Its quality in its own layout (before any split).
    pub quality: ChartQuality,
    /// The flat pieces it was laid out as: one, or more where the chart overlapped itself
    /// and was split.
    pub pieces: Vec<Piece>,
}
