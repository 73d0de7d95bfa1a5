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
pub(crate) mod given;
mod merge;
pub(crate) mod piece;
pub mod polish;
mod quality;
mod regions;
mod repair;
pub mod seamless;
pub(crate) mod split;

use conformap_disk::{flatten, FlattenBoundary, FlattenOptions};
use conformap_mesh::{
    cut_graph, cut_mesh_along, fill_holes, homology_basis, CutMesh, EdgeIndex, TriMesh,
};
use num_complex::Complex64;

use crate::cones::{place_cones, ConeMetric, ConeOptions, ConeSet};
use crate::error::AtlasError;
use crate::polish_mode::Polish;

pub(crate) use merge::merge_pieces;
pub use piece::Piece;
pub use polish::{polish, polish_with, PolishPlan, PolishReport};
pub(crate) use quality::flipped_corner_faces;
pub use quality::{chart_quality, ChartQuality};
pub use repair::{detach_folded, unfold, REPAIR_RINGS, REPAIR_TOLERANCE};
pub use split::{split_overlapping, MAX_SPLIT_DEPTH};

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
    /// Faces the flattening folded, before they were unfolded ([`unfold`]).
    pub folded_before_repair: usize,
    /// Wall time of the cone metric and the cone placement, milliseconds (0 where no
    /// cones were placed).
    pub cones_ms: f64,
    /// The polish's plan, made beside the flattening when the atlas polishes this chart.
    pub(crate) polish_plan: PlanSlot,
}

/// A [`PolishPlan`] kept with its chart until the polish takes it. A cache, not part of the
/// chart's value: a clone of the chart has none (the polish then makes its own).
#[derive(Debug, Default)]
pub(crate) struct PlanSlot(pub(crate) Option<PolishPlan>);

impl Clone for PlanSlot {
    fn clone(&self) -> Self {
        Self(None)
    }
}

/// Charts one connected component of any topology:
/// - closed: [`chart_closed`] with `cones` cones (8 when `None`);
/// - with boundary, genus 0: no cones by default (the free boundary of boundary first
///   flattening, lengths kept, the least area distortion); with cones, the cone metric with
///   `u = 0` on the boundary, the cones joined to it by shortest paths;
/// - with boundary and handles: every boundary loop filled with a centroid fan, the closed
///   surface charted, the fans dropped again (the holes become free openings of the chart).
///
/// # Errors
/// As [`chart_closed`].
pub fn chart_component(
    mesh: &TriMesh,
    cones: Option<usize>,
    options: &ConeOptions,
) -> Result<Chart, AtlasError> {
    chart_component_for(mesh, cones, options, Polish::Never)
}

/// [`chart_component`] for an atlas that polishes as `polish` says: a chart it will polish
/// gets its [`PolishPlan`] made on one core while the other flattens it.
pub(crate) fn chart_component_for(
    mesh: &TriMesh,
    cones: Option<usize>,
    options: &ConeOptions,
    polish: Polish,
) -> Result<Chart, AtlasError> {
    let closed = |cones: usize| {
        let place = |metric: &ConeMetric| place_cones(metric, cones, options);
        let metric_needed = cones > 0 || mesh.boundary_loops().is_empty();
        chart_closed_by(mesh, metric_needed.then_some(&place), polish)
    };
    if mesh.boundary_loops().is_empty() {
        return closed(cones.unwrap_or(8));
    }
    if mesh.genus() == Some(0) {
        return closed(cones.unwrap_or(0));
    }
    let all: Vec<usize> = (0..mesh.boundary_loops().len()).collect();
    let filled = fill_holes(mesh, &all).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let chart = chart_closed(&filled.mesh, cones.unwrap_or(8), options)?;
    Ok(drop_fans(chart, filled.original_faces))
}

/// The chart of a filled surface restricted to its first `faces` faces (the input's),
/// the fan vertices left out and the rest renumbered in order.
fn drop_fans(chart: Chart, faces: usize) -> Chart {
    let cut_faces = &chart.cut.mesh.faces()[..faces];
    let mut new_id = vec![u32::MAX; chart.cut.mesh.num_vertices()];
    let mut original = Vec::new();
    let mut positions = Vec::new();
    let mut uv = Vec::new();
    let mut kept_faces = Vec::with_capacity(faces);
    for t in cut_faces {
        kept_faces.push(t.map(|v| {
            if new_id[v as usize] == u32::MAX {
                new_id[v as usize] = original.len() as u32;
                original.push(chart.cut.original[v as usize]);
                positions.push(chart.cut.mesh.positions()[v as usize]);
                uv.push(chart.uv[v as usize]);
            }
            new_id[v as usize]
        }));
    }
    let mesh = match TriMesh::try_new(positions, kept_faces) {
        Ok(m) => m,
        // a sub-mesh of a valid mesh is valid; should it not be, keep the filled chart
        Err(_) => return chart,
    };
    Chart {
        cut: CutMesh {
            mesh,
            original,
            on_cut: chart.cut.on_cut,
        },
        uv,
        // the plan was made for the filled surface's cut
        polish_plan: PlanSlot(None),
        ..chart
    }
}

/// Charts closed surface `mesh` (one component, any genus) with `cones` cones; a surface
/// with boundary and genus 0 is charted the same way with `u = 0` on its boundary.
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
    let place = |metric: &ConeMetric| place_cones(metric, cones, options);
    let metric_needed = cones > 0 || mesh.boundary_loops().is_empty();
    chart_closed_by(mesh, metric_needed.then_some(&place), Polish::Never)
}

/// [`chart_closed`] with the cones chosen by `place` from the surface's cone metric (one
/// factorization, however many sets `place` tries); `None` on a surface with boundary:
/// no cones, the free boundary. The hook of given cones and of `--cones auto`
/// (module `given`). A chart `polish` applies to gets its [`PolishPlan`].
///
/// # Errors
/// As [`chart_closed`].
pub(crate) fn chart_closed_by(
    mesh: &TriMesh,
    place: Option<&dyn Fn(&ConeMetric) -> ConeSet>,
    polish: Polish,
) -> Result<Chart, AtlasError> {
    // a surface with boundary comes here with genus 0: a planar domain needs no cut
    let handles = mesh.boundary_loops().is_empty() && mesh.genus() != Some(0);
    let no_cones = |metric: &ConeMetric| place_cones(metric, 0, &ConeOptions::DEFAULT);
    let place = match place {
        Some(place) => place,
        None if mesh.boundary_loops().is_empty() => &no_cones,
        None => {
            // boundary first flattening's free boundary: no cone metric to factor
            let edges = EdgeIndex::new(mesh);
            let none = vec![false; edges.len()];
            let set = ConeSet::none(mesh.num_vertices());
            return flatten_cut(mesh, &edges, none, set, 0.0, false);
        }
    };
    let start = std::time::Instant::now();
    let (metric, (edges, on_cut)) = if handles {
        // the handle cut (tree–cotree) on one core beside the metric's weights, curvature
        // and rings on the other; the cut's vertices are then pinned
        ConeMetric::with_pinned_from(mesh, || {
            let basis = homology_basis(mesh, None).map_err(|e| AtlasError::Mesh(e.to_string()))?;
            let on_cut = cut_graph(mesh, &basis);
            let mut pinned = Vec::new();
            for (e, &c) in on_cut.iter().enumerate() {
                if c {
                    let (a, b) = mesh.halfedge_vertices(basis.edges.halfedge[e] as usize);
                    pinned.extend([a, b]);
                }
            }
            Ok((pinned, (basis.edges, on_cut)))
        })?
    } else {
        let edges = EdgeIndex::new(mesh);
        let none = vec![false; edges.len()];
        (ConeMetric::new(mesh)?, (edges, none))
    };
    let edges = &edges;
    let set = place(&metric);
    let cones_ms = start.elapsed().as_secs_f64() * 1e3;
    let handle_length = cut_length(mesh, edges, &on_cut);
    // as the atlas decides
    let plan = polish.polishes(mesh, &set);
    let chart = flatten_cut(mesh, edges, on_cut, set, handle_length, plan)?;
    Ok(Chart { cones_ms, ..chart })
}

/// Joins the cones of `set` to the cut `on_cut` (handle loops of length `handle_length`,
/// or a boundary), opens the surface along it and flattens the disk with the cone metric's
/// scale on its boundary (the free boundary when there are no cones on a surface with
/// boundary), then unfolds any folded face. With `plan`, the polish's plan is made on
/// one core while the other flattens.
fn flatten_cut(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    mut on_cut: Vec<bool>,
    set: ConeSet,
    handle_length: f64,
    plan: bool,
) -> Result<Chart, AtlasError> {
    let graph = cut::Graph::new(mesh, edges);
    let targets: Vec<u32> = set.cones.iter().map(|c| c.vertex).collect();
    let seeds: Vec<u32> = mesh.boundary_loops().iter().flatten().copied().collect();
    let added = cut::join_to_cut(mesh, edges, &graph, &mut on_cut, &targets, &seeds);
    let cut = cut_mesh_along(mesh, edges, on_cut).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    // the scale on the boundary the flattening keeps: its longest loop (other loops of a
    // planar domain are filled and left free by the flattening)
    let longest = cut
        .mesh
        .boundary_loops()
        .iter()
        .max_by_key(|l| l.len())
        .cloned()
        .unwrap_or_default();
    let boundary = if set.cones.is_empty() && !mesh.boundary_loops().is_empty() {
        FlattenBoundary::Free
    } else {
        FlattenBoundary::Scale(
            longest
                .iter()
                .map(|&w| (w, set.u[cut.original[w as usize] as usize]))
                .collect(),
        )
    };
    let options = FlattenOptions::DEFAULT
        .with_boundary(boundary)
        .with_equal_lengths(seam_pairs(mesh, &cut))
        // `unfold` below repairs a fold locally; the fallback operators cost a factorization
        .with_fold_fallback(false)
        // the chart's quality is measured once the folds are repaired (`chart_quality`)
        .with_measure(false);
    let (flat, plan) = rayon::join(
        || flatten(&cut.mesh, &options),
        || plan.then(|| PolishPlan::new(mesh, &cut.mesh)),
    );
    let flat = flat.map_err(|e| AtlasError::Flatten(e.to_string()))?;
    let mut uv = flat.map;
    let folded_before_repair = repair::folded_faces(&cut.mesh, &uv).len();
    unfold(&cut.mesh, &mut uv);
    Ok(Chart {
        cut,
        uv,
        folded_before_repair,
        cones: set,
        cut_length: handle_length + added,
        closure_residual: flat.closure_residual,
        cones_ms: 0.0,
        polish_plan: PlanSlot(plan),
    })
}

/// The two sides of every seam, as boundary edges of the cut mesh named by their first
/// vertex along the boundary (a boundary half-edge of a face runs with the loop).
fn seam_pairs(mesh: &TriMesh, cut: &CutMesh) -> Vec<(u32, u32)> {
    cut::seam_edges(mesh, &cut.mesh)
        .into_iter()
        .map(|[a, _, _, b2]| (a, b2))
        .collect()
}

fn cut_length(mesh: &TriMesh, edges: &EdgeIndex, on_cut: &[bool]) -> f64 {
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
