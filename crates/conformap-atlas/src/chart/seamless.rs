//! Seamless charts (`--seamless`): every cone angle a multiple of π/2 and every seam a
//! rotation by a multiple of π/2 plus a translation, so that a texture periodic under
//! quarter turns (or a quad grid) continues across every cut.
//!
//! - **Genus 0** (closed, or with boundary and cones): the placed cones' defects rounded
//!   to multiples of π/2 ([`quantize_cones`]), the cone metric of the rounded cones laid
//!   out as every chart is (the cut disk flattened with the metric's boundary scale).
//!   Both sides of a seam then have equal lengths and complementary turning angles, so
//!   they differ by the holonomy of the cones the seam separates: a sum of multiples of
//!   π/2.
//! - **Genus ≥ 1**: the cone metric cannot close the handle loops with quarter-turn
//!   holonomy, so the chart is the layout of a holomorphic 1-form (`conformap-global`'s
//!   most uniform one): every seam a pure translation (a period), the form's zeros cones of
//!   angle `2π(1 + m)` (multiples of π/2, here of 2π), the cut run through them. The
//!   discrete form folds a face beside each zero (its cone angle spread over the fold);
//!   each zero's disk is laid out again as a true branch point first (`branch_zero`),
//!   an exact change of the form that keeps its periods; slits of one edge at each zero
//!   (`slit_zeros`) keep every copy of it below a full turn.
//!
//! What the atlas does afterwards keeps this: [`super::unfold`] moves interior vertices
//! only, splits and neck cuts keep both pieces' coordinates (the new seam is the
//! identity), and the packer turns charts by quarter turns only
//! ([`crate::PackOptions::quarter_turns_only`]). The one step that breaks it is
//! [`super::detach_folded`], which mirrors a face the boundary folds: [`seam_rigidity`],
//! run on the final texture coordinates, reports what is left.

use std::collections::VecDeque;
use std::f64::consts::{FRAC_PI_2, TAU};

use conformap_global::{global_map, GlobalMapOptions};
use conformap_mesh::{cut_mesh_along, CutMesh, EdgeIndex, TriMesh};
use num_complex::Complex64;
use serde::Serialize;

use super::{chart_closed_by, cut, unfold, Chart, PlanSlot};
use crate::component::ComponentChart;
use crate::cones::{place_cones, Cone, ConeMetric, ConeOptions, ConeSet};
use crate::error::AtlasError;
use crate::polish_mode::Polish;

/// Rounds of pair moves of [`quantize_cones`] after the rounding: at most 8 (each round
/// tries every ordered pair of cones, one quarter of defect moved from one to the other
/// keeping their sum; on spot's 8 cones the second round already finds nothing).
pub const QUANTIZE_ROUNDS: usize = 8;

/// The fewest cones a seamless atlas places on a closed genus-0 component: 3 (its 4π of
/// curvature in cones of at most 3π/2 each; `--cones 0`, 1 or 2 give 3).
pub const MIN_CLOSED_CONES: usize = 3;

/// The cone defects allowed with `--seamless`: multiples of π/2 whose cone angle
/// `2π − k` lies in the placement's bounds [π/2, 4π], i.e. `k = j π/2`, `j ∈ [-4, 3]`.
const STEPS: std::ops::RangeInclusive<i64> = -2..=3;

/// The cones `cones` with their defects rounded to multiples of π/2 (cone angles in
/// [π/2, 4π]), on a closed surface their sum brought to the surface's `2πχ` (a multiple
/// of π/2) by the quarter steps that raise the metric's area spread least; then pairs of
/// cones trade a quarter while that lowers the spread ([`QUANTIZE_ROUNDS`]). Cones whose
/// defect ends at 0 are dropped. The scale factor and spread are the metric's.
pub fn quantize_cones(metric: &ConeMetric, cones: &[Cone]) -> ConeSet {
    let vertices: Vec<u32> = cones.iter().map(|c| c.vertex).collect();
    let greens = metric.greens(&vertices);
    let base = metric.curvature_potential();
    let spread = |steps: &[i64]| {
        let mut u: Vec<f64> = base.iter().map(|x| -x).collect();
        for (g, &j) in greens.iter().zip(steps) {
            if j != 0 {
                let k = j as f64 * FRAC_PI_2;
                u.iter_mut().zip(g).for_each(|(x, y)| *x += k * y);
            }
        }
        metric.area_spread(&u)
    };
    let mut steps: Vec<i64> = cones
        .iter()
        .map(|c| ((c.defect / FRAC_PI_2).round() as i64).clamp(*STEPS.start(), *STEPS.end()))
        .collect();
    if metric.closed() {
        let target = (metric.total_defect() / FRAC_PI_2).round() as i64;
        // one quarter at a time towards the target, where it costs least
        while !steps.is_empty() {
            let sum: i64 = steps.iter().sum();
            if sum == target {
                break;
            }
            let dir = (target - sum).signum();
            let best = (0..steps.len())
                .filter(|&i| STEPS.contains(&(steps[i] + dir)))
                .map(|i| {
                    let mut s = steps.clone();
                    s[i] += dir;
                    (spread(&s), i)
                })
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let Some((_, i)) = best else { break };
            steps[i] += dir;
        }
    }
    let mut current = spread(&steps);
    for _ in 0..QUANTIZE_ROUNDS {
        let mut improved = false;
        for i in 0..steps.len() {
            for l in 0..steps.len() {
                // on a surface with boundary a single cone may move alone (l == i: +1)
                let alone = l == i && !metric.closed();
                if l == i && !alone {
                    continue;
                }
                let mut s = steps.clone();
                s[i] += 1;
                if !alone {
                    s[l] -= 1;
                }
                if !STEPS.contains(&s[i]) || !STEPS.contains(&s[l]) {
                    continue;
                }
                let x = spread(&s);
                if x < current {
                    (steps, current, improved) = (s, x, true);
                }
                if alone {
                    let mut s = steps.clone();
                    s[i] -= 1;
                    if STEPS.contains(&s[i]) {
                        let x = spread(&s);
                        if x < current {
                            (steps, current, improved) = (s, x, true);
                        }
                    }
                }
            }
        }
        if !improved {
            break;
        }
    }
    let kept: Vec<Cone> = cones
        .iter()
        .zip(&steps)
        .filter(|(_, &j)| j != 0)
        .map(|(c, &j)| Cone {
            vertex: c.vertex,
            defect: j as f64 * FRAC_PI_2,
        })
        .collect();
    let pairs: Vec<(u32, f64)> = kept.iter().map(|c| (c.vertex, c.defect)).collect();
    let u = metric.scale_factor(&pairs);
    let area_spread = metric.area_spread(&u);
    ConeSet {
        cones: kept,
        u,
        area_spread,
        greedy_spread: area_spread,
        moves: 0,
    }
}

/// Charts one component for a seamless atlas: genus 0 by the cone metric of `cones`
/// placed cones (8 on a closed surface when `None`, at least [`MIN_CLOSED_CONES`] there;
/// none on one with boundary) rounded by
/// [`quantize_cones`], or the `given` cones as they are (the caller checks they are
/// multiples of π/2); genus ≥ 1 by [`chart_one_form`] (holes filled first and dropped
/// again on a surface with boundary), whatever the cone count.
///
/// # Errors
/// As [`super::chart_closed`]; [`AtlasError::Flatten`] when the holomorphic 1-form of a
/// genus ≥ 1 component cannot be computed.
pub fn chart_seamless(
    mesh: &TriMesh,
    cones: Option<usize>,
    given: Option<&[Cone]>,
    options: &ConeOptions,
) -> Result<Chart, AtlasError> {
    let mut chart = if mesh.genus() != Some(0) {
        super::given::with_holes_filled(mesh, chart_one_form)?
    } else if let Some(given) = given {
        super::given::chart_given(mesh, given)?
    } else {
        let closed = mesh.boundary_loops().is_empty();
        let count = cones.unwrap_or(if closed { 8 } else { 0 });
        // a closed genus-0 surface needs 4π of curvature in cones of at most 3π/2
        // (`STEPS`): at least 3 of them, else the pinned vertex would take the rest as a
        // hidden cone and the seams through it would not be rigid
        let count = if closed {
            count.max(MIN_CLOSED_CONES)
        } else {
            count
        };
        if !closed && count == 0 {
            // a disk without cones has no seam: the free boundary
            chart_closed_by(mesh, None, Polish::Never)?
        } else {
            let place = |metric: &ConeMetric| {
                let placed = place_cones(metric, count, options);
                quantize_cones(metric, &placed.cones)
            };
            chart_closed_by(mesh, Some(&place), Polish::Never)?
        }
    };
    unfold_across_seams(&mut chart);
    Ok(chart)
}

/// The chart of closed surface `mesh` of genus ≥ 1 laid out by its most uniform
/// holomorphic 1-form (`conformap-global`, default options; the layout's area is the
/// surface's): every zero made a branch point (`branch_zero`), the surface cut along its
/// homology loops and from every zero to them, the form integrated over the cut disk,
/// folds inside unfolded. Every seam is a pure
/// translation; the zeros are the cones (defect `−2π m` for a zero of multiplicity `m`).
///
/// # Errors
/// [`AtlasError::Flatten`] when the form cannot be computed, [`AtlasError::Mesh`] when the
/// cut does not open the surface.
pub fn chart_one_form(mesh: &TriMesh) -> Result<Chart, AtlasError> {
    let map = global_map(mesh, &GlobalMapOptions::DEFAULT)
        .map_err(|e| AtlasError::Flatten(format!("holomorphic 1-form: {e}")))?;
    if map.double_covered || map.surface.num_faces() != mesh.num_faces() {
        return Err(AtlasError::Mesh(
            "the holomorphic 1-form of a closed surface came on another surface".into(),
        ));
    }
    let edges = &map.edges;
    let mut form = map.form.clone();
    // each zero made a branch point, at its vertex or one beside it
    let zeros: Vec<Cone> = map
        .input_zeros()
        .filter(|z| z.multiplicity > 0)
        .map(|z| {
            let (v, m) = (z.vertex as u32, z.multiplicity as u32);
            Cone {
                vertex: branch_zero(mesh, edges, &mut form, v, m).unwrap_or(v),
                defect: -TAU * f64::from(m),
            }
        })
        .collect();
    let mut on_cut = map.cut.on_cut.clone();
    let handle_length = super::cut_length(mesh, edges, &on_cut);
    let graph = cut::Graph::new(mesh, edges);
    let targets: Vec<u32> = zeros.iter().map(|c| c.vertex).collect();
    let added = cut::join_to_cut(mesh, edges, &graph, &mut on_cut, &targets, &[]);
    let added = added + slit_zeros(mesh, edges, &form, &mut on_cut, &zeros);
    let cut = cut_mesh_along(mesh, edges, on_cut).map_err(|e| AtlasError::Mesh(e.to_string()))?;
    let mut uv = integrate(&cut, edges, &form);
    let folded_before_repair = super::repair::folded_faces(&cut.mesh, &uv).len();
    unfold(&cut.mesh, &mut uv);
    let n = mesh.num_vertices();
    Ok(Chart {
        cut,
        uv,
        cones: ConeSet {
            cones: zeros,
            u: vec![0.0; n],
            area_spread: f64::NAN,
            greedy_spread: f64::NAN,
            moves: 0,
        },
        cut_length: handle_length + added,
        closure_residual: 0.0,
        polish_plan: PlanSlot::default(),
        folded_before_repair,
        cones_ms: 0.0,
    })
}

/// Gives every zero of multiplicity `m` (a cone of `2π(m + 1)`, a branch point of `form`)
/// at least `m + 2` cut edges, and more while one of its copies in the cut disk spans a
/// full turn or more, so that each copy's neighbourhood lies flat without covering itself
/// (a zero at the end of a single cut path had all its `2π(m + 1)` in one copy, two sheets
/// the overlap splits then cut into slivers): dangling slits of one edge from the zero to a
/// neighbour not touching the cut (a slit never closes a cycle: the cut still opens the
/// surface to one disk), each in the direction farthest, by layout angle around the zero,
/// from the cut edges already there. The two sides of a slit integrate to the same
/// positions (the form is closed around its tip): its seam is the identity. A copy whose
/// neighbours all touch the cut keeps its span (eightsim: one copy of 474°). Returns the
/// 3D length added.
fn slit_zeros(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    form: &[Complex64],
    on_cut: &mut [bool],
    zeros: &[Cone],
) -> f64 {
    let faces = mesh.faces();
    let p = mesh.positions();
    let n = mesh.num_vertices();
    let mut touches = vec![false; n];
    for (e, &c) in on_cut.iter().enumerate() {
        if c {
            let (a, b) = mesh.halfedge_vertices(edges.halfedge[e] as usize);
            touches[a as usize] = true;
            touches[b as usize] = true;
        }
    }
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut added = 0.0;
    for c in zeros {
        let z = c.vertex;
        let m = (-c.defect / TAU).round() as usize;
        // the fan around z: (neighbour, half-edge z → neighbour, 3D angle of the corner
        // that follows it)
        let mut next = std::collections::HashMap::new();
        for (f, t) in faces.iter().enumerate() {
            if let Some(k) = t.iter().position(|&x| x == z) {
                let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
                // the corner's angle in the layout: between the form's values on z → a
                // and z → b (the half-edge b → z is the face's third)
                let h = 3 * f + k;
                let back = 3 * f + (k + 2) % 3;
                let to_a = edges.sign(h) * form[edges.edge_of[h] as usize];
                let to_b = -edges.sign(back) * form[edges.edge_of[back] as usize];
                let angle = (to_b / to_a).arg();
                next.insert(a, (b, h, angle));
            }
        }
        let Some(&first) = next.keys().min() else {
            continue;
        };
        let mut ring = Vec::new(); // (neighbour, half-edge, angle position)
        let (mut at, mut theta) = (first, 0.0);
        while let Some(&(b, h, angle)) = next.get(&at) {
            ring.push((at, h, theta));
            theta += angle;
            at = b;
            if at == first || ring.len() > next.len() {
                break;
            }
        }
        let total = theta;
        let on = |h: usize, on_cut: &[bool]| on_cut[edges.edge_of[h] as usize];
        let mut dirs: Vec<f64> = ring
            .iter()
            .filter(|r| on(r.1, on_cut))
            .map(|r| r.2)
            .collect();
        loop {
            // the widest copy of the zero: the largest gap between consecutive cut edges
            let mut sorted = dirs.clone();
            sorted.sort_by(f64::total_cmp);
            let widest = (0..sorted.len())
                .map(|i| match sorted.get(i + 1) {
                    Some(&next) => next - sorted[i],
                    None => sorted[0] + total - sorted[i],
                })
                .fold(0.0f64, f64::max);
            if dirs.len() >= m + 2 && widest < TAU * (1.0 - 1e-9) {
                break;
            }
            let gap = |x: f64| {
                dirs.iter()
                    .map(|&d| {
                        let g = (x - d).rem_euclid(total);
                        g.min(total - g)
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            let best = ring
                .iter()
                .filter(|r| !on(r.1, on_cut) && !touches[r.0 as usize])
                .max_by(|a, b| gap(a.2).total_cmp(&gap(b.2)));
            let Some(&(x, h, d)) = best else { break };
            on_cut[edges.edge_of[h] as usize] = true;
            touches[x as usize] = true;
            dirs.push(d);
            added += dot(
                sub(p[x as usize], p[z as usize]),
                sub(p[x as usize], p[z as usize]),
            )
            .sqrt();
        }
    }
    added
}

/// Ring counts of the disk re-laid around a zero of the 1-form ([`branch_zero`]),
/// smallest first: the first whose boundary winds `m + 1` times around the zero and whose
/// re-layout turns no face over is kept. Up to 8 rings (the discrete zeros found on eight,
/// fertility and eightsim are clusters of one or two vertices with a folded face beside
/// them; 2 rings already enclose them); a zero no ring count fixes keeps its folds and is
/// refused by the atlas (`AtlasError::SeamlessFolds`).
const BRANCH_RINGS: [usize; 5] = [2, 3, 4, 6, 8];

/// Gauss–Seidel sweeps of the mean value layout of a zero's disk, at most; it stops once no
/// vertex moves by more than 1e-14 of the disk's size (the disk has a few hundred vertices
/// at most: convergence, not speed, decides).
const BRANCH_SWEEPS: usize = 20_000;

/// Makes the zero of multiplicity `m` of the discrete holomorphic 1-form `form` at vertex
/// `zero` a true branch point: the layout of a discrete form folds faces beside its zeros
/// (the cone angle `2π(m + 1)` is spread over a folded face and the vertices around it, each
/// of which turns once), which no later step can unfold without moving seams. The disk of
/// the first of [`BRANCH_RINGS`] rings around the zero whose boundary, integrated from the
/// zero, winds `m + 1` times around it is laid out again: its boundary lifted by `ζ =
/// w^{1/(m+1)}` (one turn), the inside by mean value weights with the zero pinned at `ζ =
/// 0`, then mapped back by `w = ζ^{m+1}`: every face counter-clockwise, the zero's ring
/// turning `m + 1` times. The form's values on the edges inside the disk become the
/// differences of the new positions: the change is exact (the boundary is kept), so the
/// form stays closed with the same periods and every seam stays a translation.
///
/// The branch point is the zero's vertex when more than `2(m + 1)` faces surround it (each
/// angle at it must stay below `π/(m+1)` before the power), else the first neighbour, most
/// faces first, where the re-layout succeeds. Returns the vertex made the branch point, or
/// `None` (form unchanged) when no vertex and ring count give a fold-free disk.
fn branch_zero(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    form: &mut [Complex64],
    zero: u32,
    m: u32,
) -> Option<u32> {
    let n = mesh.num_vertices();
    let faces = mesh.faces();
    let mut vertex_faces: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (f, t) in faces.iter().enumerate() {
        t.iter()
            .for_each(|&v| vertex_faces[v as usize].push(f as u32));
    }
    // a branch point of m + 1 turns needs more than 2(m + 1) faces around it (each angle
    // below π/(m+1) before the power): the zero's vertex if it has them, else its
    // neighbours with the most faces (the discrete zero is a cluster: any vertex beside it
    // serves)
    let enough = |v: u32| vertex_faces[v as usize].len() > 2 * (m as usize + 1);
    let mut candidates: Vec<u32> = vertex_faces[zero as usize]
        .iter()
        .flat_map(|&f| faces[f as usize])
        .filter(|&v| v != zero && enough(v))
        .collect();
    candidates.sort_unstable_by_key(|&v| (std::cmp::Reverse(vertex_faces[v as usize].len()), v));
    candidates.dedup();
    if enough(zero) {
        candidates.insert(0, zero);
    }
    candidates
        .into_iter()
        .find(|&v| branch_at(mesh, edges, form, &vertex_faces, v, m).is_some())
}

/// [`branch_zero`] at vertex `zero` (`vertex_faces`: the faces around each vertex):
/// the ring count used, or `None` (form unchanged).
fn branch_at(
    mesh: &TriMesh,
    edges: &EdgeIndex,
    form: &mut [Complex64],
    vertex_faces: &[Vec<u32>],
    zero: u32,
    m: u32,
) -> Option<usize> {
    let n = mesh.num_vertices();
    let faces = mesh.faces();
    // ring distance from the zero, up to the largest ring count
    let far = *BRANCH_RINGS.last()?;
    let mut dist = vec![usize::MAX; n];
    dist[zero as usize] = 0;
    let mut queue = VecDeque::from([zero]);
    while let Some(v) = queue.pop_front() {
        let d = dist[v as usize];
        if d >= far {
            continue;
        }
        for &f in &vertex_faces[v as usize] {
            for &w in &faces[f as usize] {
                if dist[w as usize] == usize::MAX {
                    dist[w as usize] = d + 1;
                    queue.push_back(w);
                }
            }
        }
    }
    let power = f64::from(m + 1);
    for rings in BRANCH_RINGS {
        // the disk: faces with a vertex closer than `rings`
        let patch: Vec<usize> = (0..faces.len())
            .filter(|&f| faces[f].iter().any(|&v| dist[v as usize] < rings))
            .collect();
        let mut local = vec![u32::MAX; n];
        let mut global = Vec::new();
        let tris: Vec<[u32; 3]> = patch
            .iter()
            .map(|&f| {
                faces[f].map(|v| {
                    if local[v as usize] == u32::MAX {
                        local[v as usize] = global.len() as u32;
                        global.push(v);
                    }
                    local[v as usize]
                })
            })
            .collect();
        let positions = global
            .iter()
            .map(|&v| mesh.positions()[v as usize])
            .collect();
        let Ok(disk) = TriMesh::try_new(positions, tris) else {
            continue;
        };
        let loops = disk.boundary_loops();
        let boundary_edges: usize = loops.iter().map(Vec::len).sum();
        let edge_count = (3 * disk.num_faces() + boundary_edges) / 2;
        if loops.len() != 1 || disk.num_vertices() + disk.num_faces() != edge_count + 1 {
            continue; // not a disk
        }
        // the form integrated over the disk from the zero, breadth-first
        let nl = global.len();
        let mut w = vec![Complex64::new(0.0, 0.0); nl];
        let mut seen = vec![false; nl];
        let z = local[zero as usize] as usize;
        seen[z] = true;
        let mut queue = VecDeque::from([z]);
        let mut out: Vec<Vec<(usize, usize)>> = vec![Vec::new(); nl];
        for &f in &patch {
            for k in 0..3 {
                let a = local[faces[f][k] as usize] as usize;
                let b = local[faces[f][(k + 1) % 3] as usize] as usize;
                out[a].push((b, 3 * f + k));
                out[b].push((a, 3 * f + k));
            }
        }
        while let Some(a) = queue.pop_front() {
            for &(b, h) in &out[a] {
                if !seen[b] {
                    seen[b] = true;
                    let value = edges.sign(h) * form[edges.edge_of[h] as usize];
                    // h runs from its face's k-th vertex to the next
                    let from = local[mesh.halfedge_vertices(h).0 as usize] as usize;
                    w[b] = w[a] + if from == a { value } else { -value };
                    queue.push_back(b);
                }
            }
        }
        let boundary = &loops[0];
        if boundary.iter().any(|&v| w[v as usize].norm() == 0.0) {
            continue;
        }
        // the boundary's winding around the zero
        let turns: f64 = (0..boundary.len())
            .map(|i| {
                let (a, b) = (boundary[i], boundary[(i + 1) % boundary.len()]);
                (w[b as usize] / w[a as usize]).arg()
            })
            .sum::<f64>()
            / TAU;
        if (turns.abs() - power).abs() > 1e-6 {
            continue;
        }
        // the boundary lifted by the (m+1)-th root, continuously
        let mut zeta = vec![Complex64::new(0.0, 0.0); nl];
        let first = boundary[0] as usize;
        zeta[first] = w[first].powf(1.0 / power);
        for i in 1..boundary.len() {
            let (a, b) = (boundary[i - 1] as usize, boundary[i] as usize);
            zeta[b] = zeta[a] * (w[b] / w[a]).powf(1.0 / power);
        }
        let mut fixed = vec![false; nl];
        boundary.iter().for_each(|&v| fixed[v as usize] = true);
        fixed[z] = true;
        let free: Vec<u32> = (0..nl as u32).filter(|&v| !fixed[v as usize]).collect();
        let weights = super::repair::mean_value_weights(&disk);
        relax_disk(&weights, &free, &mut zeta);
        // the zero's fan: an angle of π/(m+1) or more at it turns its face over under the
        // power; then the fan's neighbours are spread evenly around it (their distances
        // kept) and the rest laid out again
        let ring = fan(&disk, z as u32)?;
        let d = ring.len();
        let widest = (0..d)
            .map(|j| (zeta[ring[(j + 1) % d] as usize] / zeta[ring[j] as usize]).arg())
            .fold(f64::NEG_INFINITY, f64::max);
        if widest >= FAN_ANGLE_LIMIT * std::f64::consts::PI / power {
            let start = zeta[ring[0] as usize].arg();
            let step = TAU / d as f64;
            let shift = (0..d)
                .map(|j| {
                    let x = zeta[ring[j] as usize].arg() - start - step * j as f64;
                    x - TAU * (x / TAU).round()
                })
                .sum::<f64>()
                / d as f64;
            for (j, &v) in ring.iter().enumerate() {
                let r = zeta[v as usize].norm();
                zeta[v as usize] = Complex64::from_polar(r, start + shift + step * j as f64);
                fixed[v as usize] = true;
            }
            let free: Vec<u32> = free.into_iter().filter(|&v| !fixed[v as usize]).collect();
            relax_disk(&weights, &free, &mut zeta);
        }
        let moved: Vec<u32> = (0..nl as u32)
            .filter(|&v| v as usize != z && !boundary.contains(&v))
            .collect();
        let mut new_w = w.clone();
        for &v in &moved {
            new_w[v as usize] = zeta[v as usize].powf(power);
        }
        let mut inside = vec![false; nl];
        moved.iter().for_each(|&v| inside[v as usize] = true);
        let ccw = disk.faces().iter().all(|t| {
            let p = t.map(|v| new_w[v as usize]);
            let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
            e1.re * e2.im - e1.im * e2.re > 0.0
        });
        if !ccw {
            continue;
        }
        // the form on every edge with an end inside the disk: the new differences
        for &f in &patch {
            for k in 0..3 {
                let h = 3 * f + k;
                let (a, b) = mesh.halfedge_vertices(h);
                let (a, b) = (local[a as usize] as usize, local[b as usize] as usize);
                if !inside[a] && !inside[b] && a != z && b != z {
                    continue;
                }
                form[edges.edge_of[h] as usize] = edges.sign(h) * (new_w[b] - new_w[a]);
            }
        }
        return Some(rings);
    }
    None
}

/// The widest angle allowed at a zero in the root plane of [`branch_zero`], as a fraction
/// of `π/(m+1)` (where the power `ζ^{m+1}` would turn the face over): 0.9, a margin so
/// that the faces beside it do not come out needle-thin; wider fans are spread evenly.
const FAN_ANGLE_LIMIT: f64 = 0.9;

/// The neighbours of interior vertex `v` of `disk` in counter-clockwise order, or `None`
/// when its faces do not close a fan.
fn fan(disk: &TriMesh, v: u32) -> Option<Vec<u32>> {
    let mut next = std::collections::HashMap::new();
    for t in disk.faces() {
        if let Some(k) = t.iter().position(|&x| x == v) {
            next.insert(t[(k + 1) % 3], t[(k + 2) % 3]);
        }
    }
    let &first = next.keys().min()?;
    let mut ring = vec![first];
    let mut at = first;
    loop {
        at = *next.get(&at)?;
        if at == first {
            break;
        }
        if ring.len() > next.len() {
            return None;
        }
        ring.push(at);
    }
    (ring.len() == next.len()).then_some(ring)
}

/// Gauss–Seidel on the mean value average over the `free` vertices of a zero's disk
/// ([`BRANCH_SWEEPS`], to 1e-14 of the disk's size).
fn relax_disk(weights: &[Vec<(u32, f64)>], free: &[u32], zeta: &mut [Complex64]) {
    let size = zeta.iter().map(|z| z.norm_sqr()).fold(0.0f64, f64::max);
    for _ in 0..BRANCH_SWEEPS {
        let mut moved = 0.0f64;
        for &v in free {
            let (mut sum, mut total) = (Complex64::new(0.0, 0.0), 0.0);
            for &(j, wt) in &weights[v as usize] {
                sum += zeta[j as usize] * wt;
                total += wt;
            }
            let x = sum / total;
            moved = moved.max((x - zeta[v as usize]).norm_sqr());
            zeta[v as usize] = x;
        }
        if moved <= 1e-28 * size {
            break;
        }
    }
}

/// `form` (one value per edge of `edges`, which number the input's edges) integrated over
/// the cut disk from its vertex 0 along a breadth-first tree: one point per cut vertex.
fn integrate(cut: &CutMesh, edges: &EdgeIndex, form: &[Complex64]) -> Vec<Complex64> {
    let cm = &cut.mesh;
    let nv = cm.num_vertices();
    let mut out: Vec<Vec<u32>> = vec![Vec::new(); nv];
    for (f, t) in cm.faces().iter().enumerate() {
        for (k, &v) in t.iter().enumerate() {
            out[v as usize].push((3 * f + k) as u32);
        }
    }
    let mut uv = vec![Complex64::new(0.0, 0.0); nv];
    let mut seen = vec![false; nv];
    for root in 0..nv {
        if seen[root] {
            continue;
        }
        seen[root] = true;
        let mut queue = VecDeque::from([root]);
        while let Some(v) = queue.pop_front() {
            for &h in &out[v] {
                let h = h as usize;
                let w = cm.faces()[h / 3][(h % 3 + 1) % 3] as usize;
                if !seen[w] {
                    seen[w] = true;
                    uv[w] = uv[v] + edges.sign(h) * form[edges.edge_of[h] as usize];
                    queue.push_back(w);
                }
            }
        }
    }
    uv
}

/// Gauss–Seidel sweeps of [`unfold_across_seams`] per ring count, at most (as the
/// atlas's own unfolding, `repair`); it stops earlier once no vertex moves by more than
/// [`super::REPAIR_TOLERANCE`] of the region's size.
const SWEEPS: usize = 2000;

/// Unfolds the faces of `chart` still folded after [`unfold`] — those the boundary curve
/// folds, which [`super::detach_folded`] would mirror, breaking the seams — by the same
/// mean value relaxation with the seam vertices free too: a vertex with two copies (a
/// seam vertex that is no cone) moves as one point, its copies kept related by the
/// seam's quarter-turn rigid map, its neighbours on both sides averaged in one frame.
/// Seams stay rigid (both sides move alike) and keep equal lengths; cones and branch
/// points of the cut stay fixed, but for a cone of a whole number of turns at the end of a
/// cut (a 1-form's zero), whose two sides leave it alike. Rings of [`super::REPAIR_RINGS`], kept while each
/// leaves fewer folded faces. Returns the faces still folded.
pub fn unfold_across_seams(chart: &mut Chart) -> usize {
    let cm = &chart.cut.mesh;
    let uv = &mut chart.uv;
    let mut folded = super::repair::folded_faces(cm, uv).len();
    if folded == 0 {
        return 0;
    }
    let n = cm.num_vertices();
    let mut copies: Vec<Vec<u32>> = Vec::new();
    for (v, &o) in chart.cut.original.iter().enumerate() {
        if copies.len() <= o as usize {
            copies.resize(o as usize + 1, Vec::new());
        }
        copies[o as usize].push(v as u32);
    }
    // twin[v]: the other copy of a two-copy vertex, with the quarter turn r taking the
    // twin's side to v's (z ↦ r z + t), from a seam edge at v
    let mut twin: Vec<Option<(u32, Complex64)>> = vec![None; n];
    // a cone of a fraction of a turn with two copies (the cut runs through it) turns its
    // two seams differently: it stays fixed
    let mut fractional = vec![false; copies.len()];
    for c in &chart.cones.cones {
        let turns = c.defect / TAU;
        if (turns - turns.round()).abs() > 1e-12 {
            if let Some(x) = fractional.get_mut(c.vertex as usize) {
                *x = true;
            }
        }
    }
    let faces = cm.faces();
    let orig = chart.cut.original.clone();
    let mut by_edge: std::collections::HashMap<(u32, u32), usize> = Default::default();
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            by_edge.insert(
                (orig[t[k] as usize], orig[t[(k + 1) % 3] as usize]),
                3 * f + k,
            );
        }
    }
    for t in faces {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let Some(&o) = by_edge.get(&(orig[b as usize], orig[a as usize])) else {
                continue;
            };
            let (q, p) = (faces[o / 3][o % 3], faces[o / 3][(o % 3 + 1) % 3]);
            if p == a && q == b {
                continue; // not a seam
            }
            let (d1, d2) = (
                uv[b as usize] - uv[a as usize],
                uv[q as usize] - uv[p as usize],
            );
            let turns = ((d1 / d2).arg() / FRAC_PI_2).round();
            let r = Complex64::from_polar(1.0, turns * FRAC_PI_2);
            let r = Complex64::new(r.re.round(), r.im.round());
            for (v, w) in [(a, p), (b, q)] {
                let o = orig[v as usize] as usize;
                if copies[o].len() == 2 && !fractional[o] && twin[v as usize].is_none() {
                    twin[v as usize] = Some((w, r));
                    twin[w as usize] = Some((v, r.conj()));
                }
            }
        }
    }
    let weights = super::repair::mean_value_weights(cm);
    let mut on_boundary = vec![false; n];
    for &v in cm.boundary_loops().iter().flatten() {
        on_boundary[v as usize] = true;
    }
    // a cone of a whole number of turns (a zero of a 1-form) at the end of a cut: its two
    // sides leave it alike (rotation 1), so it may move too
    let mut whole_turn = vec![false; n];
    for c in &chart.cones.cones {
        let turns = c.defect / TAU;
        let at = copies.get(c.vertex as usize).map_or(&[][..], |v| &v[..]);
        if (turns - turns.round()).abs() < 1e-12 && at.len() == 1 {
            whole_turn[at[0] as usize] = true;
        }
    }
    // fixed: boundary vertices without a twin (cones, branch points, open boundary)
    let fixed: Vec<bool> = (0..n)
        .map(|v| on_boundary[v] && twin[v].is_none() && !whole_turn[v])
        .collect();
    for rings in super::REPAIR_RINGS {
        let bad = super::repair::folded_faces(cm, uv);
        // breadth-first over the one-rings, through to a seam vertex's twin
        let dist = super::repair::ring_distances(cm, &bad, rings, |v, next| {
            next.extend(weights[v as usize].iter().map(|e| e.0));
            if let Some((w, _)) = twin[v as usize] {
                next.push(w);
            }
        });
        // one of each twin pair moves (the lower index), its twin follows
        let free: Vec<u32> = (0..n as u32)
            .filter(|&v| dist[v as usize] < rings && !fixed[v as usize])
            .filter(|&v| twin[v as usize].is_none_or(|(w, _)| v < w || dist[w as usize] >= rings))
            .collect();
        let mut trial = uv.clone();
        relax_across(&weights, &twin, &free, &mut trial);
        let left = super::repair::folded_faces(cm, &trial).len();
        if left >= folded {
            break;
        }
        folded = left;
        uv.copy_from_slice(&trial);
        if folded == 0 {
            break;
        }
    }
    folded
}

/// Gauss–Seidel on the mean value average over the `free` vertices, a seam vertex's
/// average taken over both its copies' neighbours in its own frame and its twin moved
/// along by the seam's rigid map.
fn relax_across(
    weights: &[Vec<(u32, f64)>],
    twin: &[Option<(u32, Complex64)>],
    free: &[u32],
    uv: &mut [Complex64],
) {
    if free.is_empty() {
        return;
    }
    let (mut lo, mut hi) = (uv[free[0] as usize], uv[free[0] as usize]);
    for &v in free {
        let z = uv[v as usize];
        lo = Complex64::new(lo.re.min(z.re), lo.im.min(z.im));
        hi = Complex64::new(hi.re.max(z.re), hi.im.max(z.im));
    }
    let size = (hi - lo).norm_sqr().max(f64::MIN_POSITIVE);
    let tolerance = super::REPAIR_TOLERANCE * super::REPAIR_TOLERANCE * size;
    for _ in 0..SWEEPS {
        let mut moved = 0.0f64;
        for &v in free {
            let (mut sum, mut total) = (Complex64::new(0.0, 0.0), 0.0);
            for &(j, w) in &weights[v as usize] {
                sum += uv[j as usize] * w;
                total += w;
            }
            // the twin's side mapped into v's frame: z ↦ r z + t, t = x_v − r x_twin
            let map = twin[v as usize].map(|(w, r)| (w, r, uv[v as usize] - r * uv[w as usize]));
            if let Some((w, r, t)) = map {
                for &(j, wt) in &weights[w as usize] {
                    sum += (r * uv[j as usize] + t) * wt;
                    total += wt;
                }
            }
            if total > 0.0 {
                let z = sum / total;
                moved = moved.max((z - uv[v as usize]).norm_sqr());
                uv[v as usize] = z;
                if let Some((w, r, t)) = map {
                    uv[w as usize] = (z - t) / r;
                }
            }
        }
        if moved < tolerance {
            break;
        }
    }
}

/// How far the seams of an atlas are from quarter-turn rigid maps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct SeamRigidity {
    /// Seam edges checked (input edges whose two faces give them different texture
    /// coordinates).
    pub seam_edges: usize,
    /// The largest distance, radians, of the rotation taking one side of a seam edge to
    /// the other from the nearest multiple of π/2.
    pub rotation_error_max: f64,
    /// The largest `|(b − a) − R (q − p)| / |b − a|` over seam edges `ab` (one side) and
    /// `pq` (the other), `R` the nearest quarter turn: what is left after the rigid map of
    /// quarter-turn rotation and translation, relative to the edge length (adjacent seam
    /// edges share a vertex, so their translations agree when this is 0).
    pub rigid_residual_max: f64,
}

/// [`SeamRigidity`] of the texture coordinates `uv` (`uv[3 f + k]`, input faces) of the
/// atlas of `charts`.
pub fn seam_rigidity(uv: &[[f64; 2]], charts: &[ComponentChart]) -> SeamRigidity {
    let mut out = SeamRigidity {
        seam_edges: 0,
        rotation_error_max: 0.0,
        rigid_residual_max: 0.0,
    };
    for [a, b, p, q] in crate::component::seam_edges(uv, charts) {
        let [a, b, p, q] = [a, b, p, q].map(|z| Complex64::new(z[0], z[1]));
        out.seam_edges += 1;
        let (d1, d2) = (b - a, q - p);
        let longer = d1.norm().max(d2.norm());
        if longer == 0.0 {
            continue; // both sides a point: rigid whatever the turn
        }
        if d1.norm() == 0.0 || d2.norm() == 0.0 {
            // one side collapsed: no rotation takes one to the other
            out.rotation_error_max = out.rotation_error_max.max(FRAC_PI_2 / 2.0);
            out.rigid_residual_max = out.rigid_residual_max.max(1.0);
            continue;
        }
        let angle = (d1 / d2).arg();
        let turns = (angle / FRAC_PI_2).round();
        let error = (angle - turns * FRAC_PI_2).abs();
        let r = Complex64::from_polar(1.0, turns * FRAC_PI_2);
        // the quarter turn exactly: no rounding of sin and cos
        let r = Complex64::new(r.re.round(), r.im.round());
        let residual = (d1 - r * d2).norm() / longer;
        out.rotation_error_max = out.rotation_error_max.max(error);
        out.rigid_residual_max = out.rigid_residual_max.max(residual);
    }
    out
}
