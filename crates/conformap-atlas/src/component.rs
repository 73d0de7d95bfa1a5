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

/// The seam edges of the atlas `uv` (`uv[3 f + k]`, input faces) of `charts`: input edges
/// whose two faces give them different texture coordinates, as `[a, b, p, q]` with `a → b`
/// on one side and `p → q` the same edge, same direction, on the other.
pub(crate) fn seam_edges<'a>(
    uv: &'a [[f64; 2]],
    charts: &'a [ComponentChart],
) -> impl Iterator<Item = [[f64; 2]; 4]> + 'a {
    charts.iter().flat_map(move |c| {
        let opp = c.mesh.opposite_halfedges();
        let corner = move |h: usize, step: usize| {
            let (f, k) = (h / 3, (h % 3 + step) % 3);
            uv[3 * c.faces[f] as usize + k]
        };
        (0..opp.len()).filter_map(move |h| {
            let o = opp[h];
            if o == conformap_mesh::NO_HALFEDGE || (o as usize) < h {
                return None;
            }
            // h runs a → b, o runs b → a: p, q are a, b on the other side
            let (a, b) = (corner(h, 0), corner(h, 1));
            let (p, q) = (corner(o as usize, 1), corner(o as usize, 0));
            (a != p || b != q).then_some([a, b, p, q])
        })
    })
}
