//! A whole atlas: every connected component charted, the charts packed into `[0,1]²` with
//! one texel density, one texture coordinate per face corner of the input.

use conformap_mesh::{triangle_area, TriMesh};
use conformap_metrics::{raster_overlap, RasterFrame, RasterOverlap, OVERLAP_RESOLUTION};
use conformap_operators::planar;
use num_complex::Complex64;
use serde::Serialize;

use crate::chart::given::{chart_auto, chart_given, AutoCones};
use crate::chart::seamless::{chart_seamless, seam_rigidity};
use crate::chart::{
    chart_component_for, chart_quality, detach_folded, flipped_corner_faces, merge_pieces, polish,
    polish_with, split_overlapping, Piece,
};
use crate::component::ComponentChart;
use crate::cones::{Cone, ConeOptions};
use crate::error::AtlasError;
use crate::layout::{keep_in_rows, per_chart_factors, ChartScale, Layout};
use crate::pack::{pack_charts, PackOptions, Packing};
use crate::polish_mode::Polish;

/// The largest seam rotation error (radians, from a quarter turn) and residual after the
/// rigid map (relative to the edge length) a `--seamless` atlas may have: 1e-6 (rounding
/// leaves 1e-11 at most on the shared meshes; a seam through a hidden cone is off by
/// tenths).
pub const SEAMLESS_TOLERANCE: f64 = 1e-6;

/// How an atlas is built. `Default` is [`AtlasOptions::DEFAULT`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct AtlasOptions {
    /// Cones per closed component (and per component with handles); `None`: 8 there, 0 on
    /// a genus-0 component with boundary (boundary first flattening's defaults).
    pub cones: Option<usize>,
    /// Cone placement.
    pub cone_options: ConeOptions,
    /// Packing.
    pub pack: PackOptions,
    /// `--cones auto`: as many cones per component as bring the area spread of its cone
    /// metric to at most this ([`chart_auto`]); overrides [`Self::cones`]. Default: `None`.
    pub max_area_spread: Option<f64>,
    /// Where the charts go: packed into `[0,1]²` (default) or kept where they are.
    pub layout: Layout,
    /// One texel density for the whole atlas (default) or one per chart.
    pub scale: ChartScale,
    /// `--seamless`: cone angles multiples of π/2 and every seam a rotation by a multiple
    /// of π/2 plus a translation ([`crate::chart::seamless`]; charts packed with quarter
    /// turns only). Default: false.
    pub seamless: bool,
    /// `--polish`: which charts' layouts are polished after they are flattened
    /// ([`polish()`]): one Gauss–Newton step on the squared log area ratios and corner-angle
    /// errors with the seams held rigid, before the repairs and the packing. Lowers the
    /// area spread and the angle distortion on every closed mesh of the atlas table (spot
    /// 0.835 → 0.790 and 2.44° → 2.31°, armadillo 1.86 → 1.72 and 1.60° → 1.45°; eightsim's
    /// 173 vertices spread 0.164 → 0.173 for 3.67° → 3.43°), for one factorization of twice
    /// the chart's vertices (whole run: spot +15–25 %, kitten_53k +65 %); the charts, and
    /// so the packing, change with it (spot 0.66 → 0.67, a neck cut the plain layout does
    /// not take). With [`Self::seamless`] the seams keep their quarter turns (spot: spread
    /// 0.948 → 0.902, seams within 4.3e-13 rad of a quarter turn). A component with
    /// boundary and no cones keeps its free-boundary layout, already the least distortion
    /// of its kind: polished, its angles paid for the area (human_face 1.11° → 1.28°,
    /// spothead 2.14° → 2.58°, hand 1.16° → 1.26°). Default: [`Polish::Auto`] (where it
    /// pays and costs little).
    pub polish: Polish,
}

impl AtlasOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        cones: None,
        cone_options: ConeOptions::DEFAULT,
        pack: PackOptions::DEFAULT,
        max_area_spread: None,
        layout: Layout::Pack,
        scale: ChartScale::Uniform,
        seamless: false,
        polish: Polish::Auto,
    };

    /// With a fixed number of cones on every component.
    pub fn with_cones(mut self, cones: usize) -> Self {
        self.cones = Some(cones);
        self
    }

    /// Every chart with cones polished (`true`: [`Polish::Always`]) or none (`false`:
    /// [`Polish::Never`]) ([`Self::polish`]).
    pub fn with_polish(mut self, polish: bool) -> Self {
        self.polish = if polish {
            Polish::Always
        } else {
            Polish::Never
        };
        self
    }

    /// With polish mode `polish` ([`Self::polish`]).
    pub fn with_polish_mode(mut self, polish: Polish) -> Self {
        self.polish = polish;
        self
    }

    /// Seamless or not ([`Self::seamless`]).
    pub fn with_seamless(mut self, seamless: bool) -> Self {
        self.seamless = seamless;
        self
    }
}

impl Default for AtlasOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The numbers of an atlas, for reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct AtlasReport {
    /// Connected components.
    pub components: usize,
    /// Charts packed (a component whose layout overlapped itself is split in several).
    pub charts: usize,
    /// Cones over all charts.
    pub cones: usize,
    /// Faces turned over in the atlas.
    pub flipped: usize,
    /// sd over all faces of `log(uv area share / 3D area share)`.
    pub area_spread: f64,
    /// Mean over corners of the angle distortion, degrees.
    pub angle_mean_deg: f64,
    /// The mean seam length mismatch `|log(l₁/l₂)|` over the seam edges of the atlas
    /// (edges whose two faces give them different texture coordinates).
    pub seam_log_ratio_mean: f64,
    /// The largest one.
    pub seam_log_ratio_max: f64,
    /// Texels covered twice at [`OVERLAP_RESOLUTION`]².
    pub overlap: RasterOverlap,
    /// Share of `[0,1]²` covered by the charts.
    pub packing_efficiency: f64,
    /// Texture units per 3D unit (one texel density for the whole atlas).
    pub scale: f64,
    /// Every cone: its input vertex and cone angle, component by component, in the order
    /// placed (a file of these lines is what `--cones FILE` reads).
    pub cone_list: Vec<ConeEntry>,
    /// What `--cones auto` chose (`None` without it).
    pub auto_cones: Option<AutoConesReport>,
    /// `"unit-square"`: charts packed into `[0,1]²`; `"none"`: kept in their own
    /// coordinates (texture units = layout units), side by side.
    pub packing: &'static str,
    /// `"uniform"`: one texel density; `"per-chart"`: every component's charts scaled to
    /// the same texture area.
    pub scale_mode: &'static str,
    /// Where a non-manifold input was split before charting (`None`: it was manifold; set
    /// by the caller that split it, [`crate::split_non_manifold`]).
    pub non_manifold: Option<crate::SplitReport>,
    /// Whether the atlas was built seamless ([`AtlasOptions::seamless`]).
    pub seamless: bool,
    /// Over the seam edges of the final texture coordinates, the largest distance (radians)
    /// of the rotation from one side to the other from a multiple of π/2 (about 0 in a
    /// seamless atlas; measured on every atlas).
    pub seam_rotation_error_max: f64,
    /// The largest residual of a seam edge after the nearest quarter-turn rigid map,
    /// relative to its length ([`crate::chart::seamless::SeamRigidity`]).
    pub seam_rigid_residual_max: f64,
    /// The polish mode ([`AtlasOptions::polish`]).
    pub polish: Polish,
    /// Components whose chart was polished ([`Polish::applies`]).
    pub polished_components: usize,
    /// The polish's energy summed over the polished charts, before and after
    /// (`Σ (log area ratio − mean)² + (μ/3) Σ angle error²`, [`crate::chart::polish()`]);
    /// `None` when no chart was polished.
    pub polish_energy: Option<[f64; 2]>,
    /// Wall time of each stage, milliseconds.
    pub timings_ms: AtlasTimings,
}

/// Wall time of each stage of an atlas, milliseconds (summed over the components).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
#[non_exhaustive]
pub struct AtlasTimings {
    /// The cone metrics' factorizations and the cone placements (on genus ≥ 1 with the
    /// handle cut, found beside the metric's weights).
    pub cones: f64,
    /// The rest of the charting: cut graphs, cuts, flattenings, fold repairs.
    pub charts: f64,
    /// Charts that folded or overlapped themselves, detached and split (each chart's
    /// distortion is measured beside it, on the other core).
    pub splits: f64,
    /// The charts' distortion polish (0 where no chart was polished).
    pub polish: f64,
    /// Neck cuts and the packing into `[0,1]²` (or the rows of `--pack none`).
    pub packing: f64,
    /// The report's measurements (the overlap raster, distortion, seams).
    pub report: f64,
}

/// A cone of the atlas, for reports.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[non_exhaustive]
pub struct ConeEntry {
    /// The input vertex (0-based).
    pub vertex: u32,
    /// The cone angle, degrees (360 minus the angle defect).
    pub angle_deg: f64,
}

/// What `--cones auto` chose, for reports.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[non_exhaustive]
pub struct AutoConesReport {
    /// The area spread asked for (per component, of its cone metric).
    pub max_area_spread: f64,
    /// The most cones tried per component ([`crate::chart::given::MAX_AUTO_CONES`]).
    pub cap: usize,
    /// Cones chosen on each component.
    pub counts: Vec<usize>,
    /// Components where the cap stopped the search before the spread was reached.
    pub capped: Vec<usize>,
}

/// A texture atlas of a mesh.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct Atlas {
    /// One texture coordinate per corner of every input face, `uv[3 f + k]`, in `[0,1]²`.
    pub uv: Vec<[f64; 2]>,
    /// The charts.
    pub charts: Vec<ComponentChart>,
    /// Where each chart went.
    pub packing: Packing,
    /// The numbers.
    pub report: AtlasReport,
}

/// Builds the atlas of the triangle soup `positions`, `faces` (any number of components,
/// each one a valid manifold surface).
///
/// # Errors
/// [`AtlasError::Component`] naming the component whose mesh is not valid, and every error
/// of [`crate::chart_component`] and [`crate::pack_charts`].
pub fn build_atlas(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &AtlasOptions,
) -> Result<Atlas, AtlasError> {
    build_atlas_with_cones(positions, faces, options, None)
}

/// [`build_atlas`] with the cones `given` (input vertex, defect `2π − angle`) on every
/// component instead of placed ones, when `Some` (a component none of them is on gets
/// none). The caller checks them: distinct interior vertices, and on a closed genus-0
/// component defects summing to `4π`.
///
/// # Errors
/// As [`build_atlas`].
pub fn build_atlas_with_cones(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &AtlasOptions,
    given: Option<&[(u32, f64)]>,
) -> Result<Atlas, AtlasError> {
    build(positions, faces, options, given, None)
}

/// [`build_atlas_with_cones`] of a mesh validated already: each component taken from it
/// with [`TriMesh::sub_mesh`] (the mesh validating the component's faces again would give,
/// for a fraction of the time: 1 ms of spot's 65).
///
/// # Errors
/// As [`build_atlas`].
pub fn build_atlas_of_mesh(
    mesh: &TriMesh,
    options: &AtlasOptions,
    given: Option<&[(u32, f64)]>,
) -> Result<Atlas, AtlasError> {
    build(mesh.positions(), mesh.faces(), options, given, Some(mesh))
}

/// The atlas of `positions`, `faces`, whose mesh is `whole` when it was validated already.
fn build(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &AtlasOptions,
    given: Option<&[(u32, f64)]>,
    whole: Option<&TriMesh>,
) -> Result<Atlas, AtlasError> {
    if options.seamless && options.max_area_spread.is_some() && given.is_none() {
        return Err(AtlasError::InvalidOption {
            name: "seamless",
            value: "with an automatic cone count".into(),
            why: "a seamless atlas takes a cone count or given cones (multiples of 90°)",
        });
    }
    let ms = |t: std::time::Instant| t.elapsed().as_secs_f64() * 1e3;
    let mut timings = AtlasTimings::default();
    let components = split_components(positions.len(), faces);
    let mut charts = Vec::with_capacity(components.len());
    let mut autos: Vec<AutoCones> = Vec::new();
    let mut polish_energy = [0.0; 2];
    let mut polished_components = 0;
    for (index, face_ids) in components.into_iter().enumerate() {
        let (mesh, vertices) = match whole {
            Some(whole) => whole.sub_mesh(&face_ids).map_err(|e| e.to_string()),
            None => component_mesh(positions, faces, &face_ids),
        }
        .map_err(|why| AtlasError::Component { index, why })?;
        let start = std::time::Instant::now();
        let mut chart = match (given, options.max_area_spread) {
            _ if options.seamless => {
                let local = given.map(|g| local_cones(g, &vertices));
                chart_seamless(
                    &mesh,
                    options.cones,
                    local.as_deref(),
                    &options.cone_options,
                )?
            }
            (Some(given), _) => chart_given(&mesh, &local_cones(given, &vertices))?,
            (None, Some(spread)) => {
                let (chart, auto) = chart_auto(&mesh, spread, &options.cone_options)?;
                autos.push(auto);
                chart
            }
            (None, None) => {
                chart_component_for(&mesh, options.cones, &options.cone_options, options.polish)?
            }
        };
        timings.cones += chart.cones_ms;
        timings.charts += ms(start) - chart.cones_ms;
        if options.polish.polishes(&mesh, &chart.cones) {
            let start = std::time::Instant::now();
            let polished = match chart.polish_plan.0.take() {
                Some(plan) => polish_with(plan, &chart.cut.mesh, &mut chart.uv),
                None => polish(&mesh, &chart.cut.mesh, &mut chart.uv),
            };
            if polished.energy.iter().all(|e| e.is_finite()) {
                polish_energy[0] += polished.energy[0];
                polish_energy[1] += polished.energy[1];
            }
            polished_components += 1;
            timings.polish += ms(start);
        }
        scale_to_surface_area(&mesh, &mut chart);
        let start = std::time::Instant::now();
        let whole = Piece {
            faces: (0..mesh.num_faces() as u32).collect(),
            mesh: chart.cut.mesh.clone(),
            original: chart.cut.original.clone(),
            uv: chart.uv.clone(),
        };
        // the chart's distortion (one core) beside its repairs (the other)
        let (quality, pieces) = rayon::join(
            || chart_quality(&mesh, &chart.cut, &chart.uv),
            || -> Result<Vec<Piece>, AtlasError> {
                let mut pieces = Vec::new();
                for piece in detach_folded(whole.clone())? {
                    pieces.extend(split_overlapping(piece, 0)?);
                }
                // slivers the splits left merged back where that overlaps nothing
                merge_pieces(&whole, pieces)
            },
        );
        let pieces = pieces?;
        if options.seamless {
            // the repairs keep every piece's coordinates (rigid seams), so a fold they
            // cannot detach stays: refused rather than written
            let flipped: usize = pieces
                .iter()
                .map(|p| {
                    let corner: Vec<Complex64> = p
                        .mesh
                        .faces()
                        .iter()
                        .flat_map(|t| t.map(|v| p.uv[v as usize]))
                        .collect();
                    flipped_corner_faces(&corner)
                })
                .sum();
            if flipped > 0 {
                return Err(AtlasError::SeamlessFolds {
                    component: index,
                    genus: mesh.genus().unwrap_or(0),
                    flipped,
                });
            }
        }
        timings.splits += ms(start);
        charts.push(ComponentChart {
            faces: face_ids,
            vertices,
            mesh,
            chart,
            quality,
            pieces,
        });
    }
    // one texel density, packed: by outlines, charts cut at necks where that packs denser;
    // otherwise (per-chart scale, or the charts kept in place) the rectangle packer or rows
    // seamless: the charts turned by quarter turns only, so every seam stays one
    let pack = options
        .pack
        .with_quarter_turns_only(options.pack.quarter_turns_only || options.seamless);
    let start = std::time::Instant::now();
    let packing = if options.layout == Layout::Pack && options.scale == ChartScale::Uniform {
        crate::neck::cut_necks(&mut charts, &pack)?
    } else {
        let outlines: Vec<Vec<[f64; 2]>> = charts
            .iter()
            .flat_map(|c| &c.pieces)
            .map(|p| p.uv.iter().map(|z| [z.re, z.im]).collect())
            .collect();
        // --scale per-chart: every chart brought to the same layout area first
        let factors = match options.scale {
            ChartScale::Uniform => vec![1.0; outlines.len()],
            ChartScale::PerChart => per_chart_factors(&charts),
        };
        let outlines: Vec<Vec<[f64; 2]>> = outlines
            .into_iter()
            .zip(&factors)
            .map(|(o, &f)| o.into_iter().map(|p| [f * p[0], f * p[1]]).collect())
            .collect();
        let mut packing = match options.layout {
            Layout::Pack => pack_charts(&outlines, &pack)?,
            Layout::Keep => keep_in_rows(&outlines, &pack)?,
        };
        for (place, f) in packing.charts.iter_mut().zip(&factors) {
            place.scale *= f;
        }
        packing
    };
    let mut uv = vec![[0.0; 2]; 3 * faces.len()];
    let mut places = packing.charts.iter();
    for c in &charts {
        for piece in &c.pieces {
            let Some(place) = places.next() else { break };
            for (local, &cf) in piece.faces.iter().enumerate() {
                let f = c.faces[cf as usize] as usize;
                let t = piece.mesh.faces()[local];
                for k in 0..3 {
                    let z = piece.uv[t[k] as usize];
                    uv[3 * f + k] = place.apply([z.re, z.im]);
                }
            }
        }
    }
    timings.packing = ms(start);
    let start = std::time::Instant::now();
    let mut report = report(positions, faces, &uv, &charts, &packing, options);
    timings.report = ms(start);
    report.timings_ms = timings;
    report.polish = options.polish;
    report.polished_components = polished_components;
    report.polish_energy = (polished_components > 0).then_some(polish_energy);
    if options.seamless
        && !(report.seam_rotation_error_max <= SEAMLESS_TOLERANCE
            && report.seam_rigid_residual_max <= SEAMLESS_TOLERANCE)
    {
        return Err(AtlasError::SeamlessNotRigid {
            rotation: report.seam_rotation_error_max,
            residual: report.seam_rigid_residual_max,
        });
    }
    if let Some(spread) = options.max_area_spread.filter(|_| given.is_none()) {
        report.auto_cones = Some(AutoConesReport {
            max_area_spread: spread,
            cap: crate::chart::given::MAX_AUTO_CONES,
            counts: autos.iter().map(|a| a.count).collect(),
            capped: (0..autos.len()).filter(|&i| autos[i].capped).collect(),
        });
    }
    Ok(Atlas {
        uv,
        charts,
        packing,
        report,
    })
}

/// Scales the layout of `chart` (a chart of `mesh`) to the area of the surface. A closed
/// component's cone metric is fixed at one pinned vertex (`u = 0` there), which leaves its
/// layout as a whole `e^{2u}` times larger or smaller than the surface (spot's 8-cone
/// layout: 14× the area per 3D area of a disk's free-boundary layout); brought to the
/// surface's area, every component's layout is in 3D units on the whole, so one common
/// packing scale is one texel density for all components (and `--pack none` keeps 3D
/// units). A uniform scale: angles, seams and rigidity are unchanged.
fn scale_to_surface_area(mesh: &TriMesh, chart: &mut crate::chart::Chart) {
    let surface = conformap_operators::surface_area(mesh);
    let layout: f64 = chart
        .cut
        .mesh
        .faces()
        .iter()
        .map(|t| {
            let z = t.map(|v| chart.uv[v as usize]);
            planar::triangle_signed_area(z[0], z[1], z[2]).abs()
        })
        .sum();
    let factor = (surface / layout).sqrt();
    if factor.is_finite() && factor > 0.0 {
        chart.uv.iter_mut().for_each(|z| *z *= factor);
    }
}

/// The cones of `given` (input vertices) on a component whose vertices are `vertices`
/// (local → input), in the component's numbering.
fn local_cones(given: &[(u32, f64)], vertices: &[u32]) -> Vec<Cone> {
    let local: rustc_hash::FxHashMap<u32, u32> = vertices
        .iter()
        .enumerate()
        .map(|(l, &v)| (v, l as u32))
        .collect();
    given
        .iter()
        .filter_map(|&(v, defect)| {
            let vertex = *local.get(&v)?;
            Some(Cone { vertex, defect })
        })
        .collect()
}

/// Faces grouped by connected component (through shared vertices), each group in input
/// order, groups ordered by their first face.
pub fn split_components(vertices: usize, faces: &[[u32; 3]]) -> Vec<Vec<u32>> {
    let mut parent: Vec<u32> = (0..vertices as u32).collect();
    fn find(p: &mut [u32], mut x: u32) -> u32 {
        while p[x as usize] != x {
            p[x as usize] = p[p[x as usize] as usize];
            x = p[x as usize];
        }
        x
    }
    for t in faces {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, t[0]), find(&mut parent, t[k]));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    let mut group_of = rustc_hash::FxHashMap::default();
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for (f, t) in faces.iter().enumerate() {
        let root = find(&mut parent, t[0]);
        let g = *group_of.entry(root).or_insert_with(|| {
            groups.push(Vec::new());
            groups.len() - 1
        });
        groups[g].push(f as u32);
    }
    groups
}

/// The mesh of one component (vertices renumbered in order of first use) and the input
/// vertex of each of its vertices.
fn component_mesh(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    ids: &[u32],
) -> Result<(TriMesh, Vec<u32>), String> {
    let mut local = rustc_hash::FxHashMap::default();
    let mut vertices = Vec::new();
    let mut tris = Vec::with_capacity(ids.len());
    for &f in ids {
        tris.push(faces[f as usize].map(|v| {
            *local.entry(v).or_insert_with(|| {
                vertices.push(v);
                (vertices.len() - 1) as u32
            })
        }));
    }
    let pts = vertices.iter().map(|&v| positions[v as usize]).collect();
    let mesh = TriMesh::try_new(pts, tris).map_err(|e| e.to_string())?;
    Ok((mesh, vertices))
}

/// The largest `|log(l₁/l₂)|` over the seams of the atlas: input edges whose two faces
/// give them different texture coordinates.
fn seam_log_ratios(uv: &[[f64; 2]], charts: &[ComponentChart]) -> (f64, f64) {
    let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0usize);
    for [a, b, p, q] in crate::component::seam_edges(uv, charts) {
        let l1 = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
        let l2 = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).sqrt();
        let r = (l1 / l2).ln().abs();
        worst = worst.max(r);
        sum += r;
        count += 1;
    }
    (sum / count.max(1) as f64, worst)
}

fn report(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    uv: &[[f64; 2]],
    charts: &[ComponentChart],
    packing: &Packing,
    options: &AtlasOptions,
) -> AtlasReport {
    let tris = (0..faces.len()).map(|f| [uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]]);
    // charts kept in their own coordinates: the raster over their bounding box
    let frame = match options.layout {
        Layout::Pack => RasterFrame::UnitSquare,
        Layout::Keep => RasterFrame::BoundingBox,
    };
    // the raster (on all cores) beside the rest of the measurements (one core)
    let (overlap, report) = rayon::join(
        || raster_overlap(tris, OVERLAP_RESOLUTION, frame),
        || measure(positions, faces, uv, charts, packing, options),
    );
    AtlasReport { overlap, ..report }
}

/// Every number of the report but the overlap (left at its default).
fn measure(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    uv: &[[f64; 2]],
    charts: &[ComponentChart],
    packing: &Packing,
    options: &AtlasOptions,
) -> AtlasReport {
    // per face: 3D area and signed texture area (the metrics crate needs one validated
    // mesh; an atlas's input may be several)
    let corner: Vec<Complex64> = uv.iter().map(|p| Complex64::new(p[0], p[1])).collect();
    let a3: Vec<f64> = faces
        .iter()
        .map(|t| {
            let p = t.map(|v| positions[v as usize]);
            triangle_area(p[0], p[1], p[2])
        })
        .collect();
    let a2: Vec<f64> = corner
        .chunks_exact(3)
        .map(|q| planar::triangle_signed_area(q[0], q[1], q[2]))
        .collect();
    let (s3, s2) = (
        a3.iter().sum::<f64>(),
        a2.iter().map(|a| a.abs()).sum::<f64>(),
    );
    let logs: Vec<f64> = a3
        .iter()
        .zip(&a2)
        .map(|(&x, &y)| ((y.abs() / s2).max(f64::MIN_POSITIVE) / (x / s3)).ln())
        .collect();
    let n = logs.len().max(1) as f64;
    let mean = logs.iter().sum::<f64>() / n;
    let area_spread = (logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / n).sqrt();
    let seams = seam_log_ratios(uv, charts);
    let rigidity = seam_rigidity(uv, charts);
    let corners: f64 = charts.iter().map(|c| 3.0 * c.mesh.num_faces() as f64).sum();
    let angle_mean_deg = charts
        .iter()
        .map(|c| c.quality.angle_mean_deg * 3.0 * c.mesh.num_faces() as f64)
        .sum::<f64>()
        / corners.max(1.0);
    AtlasReport {
        components: charts.len(),
        charts: charts.iter().map(|c| c.pieces.len()).sum(),
        cones: charts.iter().map(|c| c.chart.cones.cones.len()).sum(),
        flipped: flipped_corner_faces(&corner),
        area_spread,
        angle_mean_deg,
        seam_log_ratio_mean: seams.0,
        seam_log_ratio_max: seams.1,
        overlap: RasterOverlap::default(),
        packing_efficiency: s2 / bounding_square(uv),
        scale: packing.scale,
        cone_list: charts
            .iter()
            .flat_map(|c| {
                c.chart.cones.cones.iter().map(|k| ConeEntry {
                    vertex: c.vertices[k.vertex as usize],
                    angle_deg: k.angle_deg(),
                })
            })
            .collect(),
        auto_cones: None,
        packing: match options.layout {
            Layout::Pack => "unit-square",
            Layout::Keep => "none",
        },
        scale_mode: match options.scale {
            ChartScale::Uniform => "uniform",
            ChartScale::PerChart => "per-chart",
        },
        non_manifold: None,
        seamless: options.seamless,
        seam_rotation_error_max: rigidity.rotation_error_max,
        seam_rigid_residual_max: rigidity.rigid_residual_max,
        polish: options.polish,
        polished_components: 0,
        polish_energy: None,
        timings_ms: AtlasTimings::default(),
    }
}

/// The area the packing efficiency is measured against: 1 (the texture square) when every
/// point lies in `[0,1]²` (a packed atlas), else the square on the longer side of the
/// layout's bounding box (charts kept in their own coordinates).
fn bounding_square(uv: &[[f64; 2]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in uv {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if uv.is_empty() || (lo[0] >= 0.0 && lo[1] >= 0.0 && hi[0] <= 1.0 && hi[1] <= 1.0) {
        return 1.0;
    }
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    side * side
}
