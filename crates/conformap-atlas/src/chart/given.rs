//! Charts whose cones are not placed by count: cones given by the caller (`--cones FILE`)
//! and as many cones as it takes to reach an area spread (`--cones auto`). Both go through
//! [`chart_closed_by`] with their own choice of cones from the one factored cone metric.

use conformap_mesh::{fill_holes, TriMesh};
use serde::Serialize;

use super::piece::Piece;
use super::repair::detach_folded;
use super::split::split_overlapping;
use super::{chart_closed_by, chart_quality, drop_fans, Chart};
use crate::cones::{greedy_count, place_cones, Cone, ConeMetric, ConeOptions, ConeSet};
use crate::error::AtlasError;
use crate::polish_mode::Polish;

/// The most cones `--cones auto` places on one component: 32. Each count is a placement
/// of its own (greedy pass and moves, a few Green's function solves per cone), so the
/// search costs about the sum of the counts tried; spot reaches an area spread of 0.5 with
/// fewer than 20, and past 32 cones a chart is more seams than surface.
pub const MAX_AUTO_CONES: usize = 32;

/// What `--cones auto` chose on one component.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct AutoCones {
    /// Cones placed.
    pub count: usize,
    /// The area spread of the cone metric with them (the layout's, up to the
    /// discretization of the flattening; NaN for the cone-free free boundary, which is
    /// measured on its layout).
    pub metric_spread: f64,
    /// Whether [`MAX_AUTO_CONES`] stopped the search before the spread was reached (the
    /// set with the least spread seen is kept).
    pub capped: bool,
}

/// Charts `mesh` (one component, any topology, as [`super::chart_component`]) with the
/// cones `cones` exactly as given (vertex in `mesh`'s numbering, defect `2π − angle`): no
/// placement. The caller checks them (distinct interior vertices; on a closed genus-0
/// surface defects summing to `2πχ = 4π`, else the pinned vertex takes the rest as a
/// hidden cone).
///
/// # Errors
/// As [`super::chart_closed`].
pub fn chart_given(mesh: &TriMesh, cones: &[Cone]) -> Result<Chart, AtlasError> {
    let place = |metric: &ConeMetric| given_set(metric, cones);
    with_holes_filled(mesh, |m| {
        let needed = !cones.is_empty() || m.boundary_loops().is_empty();
        chart_closed_by(m, needed.then_some(&place), Polish::Never)
    })
}

/// The cone set of `cones` in `metric`: their scale factor and its area spread.
fn given_set(metric: &ConeMetric, cones: &[Cone]) -> ConeSet {
    let pairs: Vec<(u32, f64)> = cones.iter().map(|c| (c.vertex, c.defect)).collect();
    let u = metric.scale_factor(&pairs);
    let area_spread = metric.area_spread(&u);
    ConeSet {
        cones: cones.to_vec(),
        u,
        area_spread,
        greedy_spread: area_spread,
        moves: 0,
    }
}

/// Charts `mesh` (as [`super::chart_component`]) with as few cones as give a cone metric
/// of area spread at most `max_spread` (counts from 0 on a surface with boundary or
/// handles, which then take up the curvature; from 3 on a closed genus-0 surface, whose
/// cones must carry `4π` at angles of at least π/2; up to [`MAX_AUTO_CONES`]), all from
/// one factorization: the greedy pass alone finds a count that reaches the bound (its
/// prefixes give every count at once), then full placements ([`place_cones`]) bisect the
/// counts below it for the fewest within the bound (the spread of placed cones falls with
/// their number on every mesh measured; should it rise somewhere, the bisection may keep
/// a count above the fewest). Should no greedy prefix reach the bound, every count is
/// placed in full, upwards.
/// On a genus-0 surface with boundary, the cone-free free boundary comes first and is
/// kept when its layout is within `max_spread`. The chosen count's layout is measured
/// too: where its spread is still above `max_spread`, or a face stays flipped after the
/// atlas's repairs, the search goes on from one cone more.
///
/// # Errors
/// As [`super::chart_closed`].
pub fn chart_auto(
    mesh: &TriMesh,
    max_spread: f64,
    options: &ConeOptions,
) -> Result<(Chart, AutoCones), AtlasError> {
    let free_boundary = !mesh.boundary_loops().is_empty() && mesh.genus() == Some(0);
    if free_boundary {
        let chart = chart_closed_by(mesh, None, Polish::Never)?;
        let spread = chart_quality(mesh, &chart.cut, &chart.uv).area_spread;
        if spread <= max_spread {
            let auto = AutoCones {
                count: 0,
                metric_spread: f64::NAN,
                capped: false,
            };
            return Ok((chart, auto));
        }
    }
    let mut first = if free_boundary {
        1
    } else if mesh.genus() == Some(0) {
        3
    } else {
        0
    };
    loop {
        let (chart, auto) = chart_auto_from(mesh, first, max_spread, options)?;
        // the layout reproduces the metric's spread up to the flattening's discretization
        // (eightsim at 0.2: 0.203): short of it, the search goes on from one cone more
        // (a factorization more)
        // and a layout the atlas's repairs leave a flipped face in (armadillo at 1.0: 18
        // cones, 1 face) is no answer either while more cones may give one
        let spread = chart_quality(mesh, &chart.cut, &chart.uv).area_spread;
        let good = spread <= max_spread && flipped_after_repair(&chart)? == 0;
        if good || auto.capped || auto.count >= MAX_AUTO_CONES {
            return Ok((chart, auto));
        }
        first = auto.count + 1;
    }
}

/// The faces of `chart` still flipped after the atlas's repairs of it (folded faces
/// detached, overlapping pieces split), as `build_atlas` applies them.
///
/// # Errors
/// Those of the repairs (none in practice on a valid chart).
fn flipped_after_repair(chart: &Chart) -> Result<usize, AtlasError> {
    let whole = Piece {
        faces: (0..chart.cut.mesh.num_faces() as u32).collect(),
        mesh: chart.cut.mesh.clone(),
        original: chart.cut.original.clone(),
        uv: chart.uv.clone(),
    };
    let mut flipped = 0;
    for piece in detach_folded(whole)? {
        for p in split_overlapping(piece, 0)? {
            flipped += p
                .mesh
                .faces()
                .iter()
                .filter(|t| {
                    let [a, b, c] = t.map(|v| p.uv[v as usize]);
                    let (e1, e2) = (b - a, c - a);
                    e1.re * e2.im - e1.im * e2.re <= 0.0
                })
                .count();
        }
    }
    Ok(flipped)
}

/// One search of [`chart_auto`]: counts from `first` up, the first whose cone metric is
/// within `max_spread` charted.
fn chart_auto_from(
    mesh: &TriMesh,
    first: usize,
    max_spread: f64,
    options: &ConeOptions,
) -> Result<(Chart, AutoCones), AtlasError> {
    let chosen = std::cell::Cell::new(None);
    let place = |metric: &ConeMetric| {
        // the greedy pass's count bounds the answer from above; full placements bisect
        // the counts below it (the spread falls with the count)
        if let Some(top) = greedy_count(metric, first.max(1), MAX_AUTO_CONES, max_spread) {
            let set = place_cones(metric, top, options);
            if set.area_spread <= max_spread {
                // `best` within the bound at `hi` cones; every count up to `lo` missed it
                // (or lies below `first`)
                let (mut lo, mut hi, mut best) = (first as isize - 1, top as isize, set);
                while hi - lo > 1 {
                    let mid = (lo + hi) / 2;
                    let trial = place_cones(metric, mid as usize, options);
                    if trial.area_spread <= max_spread {
                        (hi, best) = (mid, trial);
                    } else {
                        lo = mid;
                    }
                }
                chosen.set(Some((best.cones.len(), best.area_spread, false)));
                return best;
            }
        }
        let mut best: Option<ConeSet> = None;
        for count in first..=MAX_AUTO_CONES {
            let set = place_cones(metric, count, options);
            let spread = set.area_spread;
            if best.as_ref().is_none_or(|b| !(b.area_spread <= spread)) {
                best = Some(set);
            }
            if let Some(b) = best.take() {
                if spread <= max_spread {
                    chosen.set(Some((b.cones.len(), b.area_spread, false)));
                    return b;
                }
                best = Some(b);
            }
        }
        let best = best.unwrap_or_else(|| place_cones(metric, first, options));
        chosen.set(Some((best.cones.len(), best.area_spread, true)));
        best
    };
    let chart = with_holes_filled(mesh, |m| chart_closed_by(m, Some(&place), Polish::Never))?;
    let (count, metric_spread, capped) = chosen.get().unwrap_or((0, f64::NAN, false));
    let auto = AutoCones {
        count,
        metric_spread,
        capped,
    };
    Ok((chart, auto))
}

/// Runs `chart` on `mesh`, or, when `mesh` has boundary and handles, on `mesh` with every
/// hole filled by a centroid fan (original vertices keep their indices), the fans dropped
/// again from the chart (as [`super::chart_component`] does).
pub(crate) fn with_holes_filled(
    mesh: &TriMesh,
    chart: impl Fn(&TriMesh) -> Result<Chart, AtlasError>,
) -> Result<Chart, AtlasError> {
    if mesh.boundary_loops().is_empty() || mesh.genus() == Some(0) {
        return chart(mesh);
    }
    let all: Vec<usize> = (0..mesh.boundary_loops().len()).collect();
    let filled = fill_holes(mesh, &all).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let c = chart(&filled.mesh)?;
    Ok(drop_fans(c, filled.original_faces))
}
