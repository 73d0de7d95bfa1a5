//! One chart of a closed surface: cones placed, the surface cut through them (and through
//! its handles) into a disk, the disk flattened with the cone metric's boundary scale.
//!
//! On genus 0 the cut is a tree of shortest paths through the cones, and the chart is the
//! cone metric itself: the two sides of every seam have equal lengths and differ by the
//! cone rotation and a translation. On genus ≥ 1 the handle loops of a tree–cotree
//! decomposition are cut too and kept at `u = 0` (their lengths kept, as a free boundary:
//! they take up the curvature the cones leave, bending differently on their two sides);
//! the cones are placed in the metric pinned there and joined to the loops.

mod cut;
mod quality;

use conformap_disk::{flatten, FlattenBoundary, FlattenOptions};
use conformap_mesh::{cut_graph, cut_mesh, homology_basis, CutMesh, TriMesh};
use num_complex::Complex64;

use crate::cones::{place_cones, ConeMetric, ConeOptions, ConeSet};
use crate::error::AtlasError;

pub use quality::{chart_quality, ChartQuality};

/// A closed surface cut into one disk and flattened.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Chart {
    /// The surface opened along the cut (its faces are the input's, in order).
    pub cut: CutMesh,
    /// The flat layout, one point per vertex of [`Chart::cut`]'s mesh.
    pub uv: Vec<Complex64>,
    /// The cones, their metric's scale factor and area spread.
    pub cones: ConeSet,
    /// 3D length of the cut (handle loops and cone paths).
    pub cut_length: f64,
    /// The closing residual of the boundary curve (boundary first flattening).
    pub closure_residual: f64,
}

/// Charts closed surface `mesh` (one component, any genus) with `cones` cones.
///
/// # Errors
/// [`AtlasError::Mesh`] if the cut does not leave a disk, [`AtlasError::Flatten`] if the
/// cut disk cannot be flattened, [`AtlasError::Factorization`] for a Laplacian that does
/// not factor.
pub fn chart_closed(
    mesh: &TriMesh,
    cones: usize,
    options: &ConeOptions,
) -> Result<Chart, AtlasError> {
    let basis = homology_basis(mesh, None).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let edges = &basis.edges;
    let mut on_cut = if basis.generators.is_empty() {
        vec![false; edges.len()]
    } else {
        cut_graph(mesh, &basis)
    };
    let metric = if basis.generators.is_empty() {
        ConeMetric::new(mesh)?
    } else {
        let mut pinned = Vec::new();
        for (e, &c) in on_cut.iter().enumerate() {
            if c {
                let (a, b) = mesh.halfedge_vertices(edges.halfedge[e] as usize);
                pinned.extend([a, b]);
            }
        }
        ConeMetric::with_pinned(mesh, &pinned)?
    };
    let set = place_cones(&metric, cones, options);
    let graph = cut::Graph::new(mesh, edges);
    let handle_length = cut_length(mesh, edges, &on_cut);
    let targets: Vec<u32> = set.cones.iter().map(|c| c.vertex).collect();
    let added = cut::join_to_cut(mesh, edges, &graph, &mut on_cut, &targets);
    let cut = cut_mesh(mesh, &basis, on_cut).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let scale: Vec<(u32, f64)> = cut
        .mesh
        .boundary_loops()
        .iter()
        .flatten()
        .map(|&w| (w, set.u[cut.original[w as usize] as usize]))
        .collect();
    let options = FlattenOptions::DEFAULT
        .with_boundary(FlattenBoundary::Scale(scale))
        .with_equal_lengths(seam_pairs(mesh, &cut));
    let flat = flatten(&cut.mesh, &options).map_err(|e| AtlasError::Flatten(e.to_string()))?;
    Ok(Chart {
        cut,
        uv: flat.map,
        cones: set,
        cut_length: handle_length + added,
        closure_residual: flat.closure_residual,
    })
}

/// The two sides of every seam, as boundary edges of the cut mesh named by their first
/// vertex along the boundary (a boundary half-edge of a face runs with the loop).
fn seam_pairs(mesh: &TriMesh, cut: &CutMesh) -> Vec<(u32, u32)> {
    let start = |h: usize| cut.mesh.faces()[h / 3][h % 3];
    let end = |h: usize| cut.mesh.faces()[h / 3][(h + 1) % 3];
    mesh.opposite_halfedges()
        .iter()
        .enumerate()
        .filter(|&(h, &o)| o != conformap_mesh::NO_HALFEDGE && h < o as usize)
        .filter(|&(h, &o)| start(h) != end(o as usize) || end(h) != start(o as usize))
        .map(|(h, &o)| (start(h), start(o as usize)))
        .collect()
}

fn cut_length(mesh: &TriMesh, edges: &conformap_mesh::EdgeIndex, on_cut: &[bool]) -> f64 {
    let p = mesh.positions();
    on_cut
        .iter()
        .enumerate()
        .filter(|(_, &c)| c)
        .map(|(e, _)| {
            let (a, b) = mesh.halfedge_vertices(edges.halfedge[e] as usize);
            let (pa, pb) = (p[a as usize], p[b as usize]);
            ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2)).sqrt()
        })
        .sum()
}
