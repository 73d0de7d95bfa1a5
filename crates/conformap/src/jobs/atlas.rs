//! `conformap atlas MESH -o OUT ...`: a texture atlas of any mesh — every component charted
//! (closed ones through cones and their handles), charts that overlap themselves split,
//! everything packed into `[0,1]²` with one texel density.

use rustc_hash::FxHashMap as HashMap;
use std::path::{Path, PathBuf};

/// Which charts are polished ([`AtlasJob::polish`]).
pub use conformap_atlas::Polish;
use conformap_atlas::{
    atlas_peak_bytes_with, build_atlas_of_mesh, AtlasOptions, ChartScale, Layout, PackOptions,
};
use conformap_io::CornerUv;
use conformap_mesh::TriMesh;
use conformap_metrics::{corner_map_metrics, MetricsOptions};
use num_complex::Complex64;

use crate::failure::Failure;
use crate::pipeline::{Input, InputOptions, MapJob, OutputOptions, Solved, TexCoords};
use crate::report::{MetricsSection, SolverDetail, SolverSection, StageTimings};

mod cones;

pub use cones::{parse_cone_file, GivenCone, GivenCones, GAUSS_BONNET_TOLERANCE_DEG};

/// The area spread `--cones auto` aims at unless `--max-area-spread` says otherwise: 1.0,
/// the spread boundary first flattening reaches on spot with its default 8 cones (1.01):
/// an automatic atlas at least as even as that, with as few cones (seams) as it takes.
pub const DEFAULT_MAX_AREA_SPREAD: f64 = 1.0;

/// How close to a multiple of 90° a given cone angle must be with `--seamless`, in quarter
/// turns: 1e-9 (a cone file written with 9 or more decimals of degrees passes; a real
/// 89.9° cone does not).
pub const SEAMLESS_ANGLE_TOLERANCE: f64 = 1e-9;

/// Where the cones of an atlas come from.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ConeChoice {
    /// Placed automatically, as many as [`AtlasJob::cones`] says (`--cones N`, default).
    Count,
    /// As many per component as bring its area spread to [`AtlasJob::max_area_spread`]
    /// (`--cones auto`).
    Auto,
    /// Given: a file of `<vertex> <cone angle in degrees>` lines (`--cones FILE`).
    File(PathBuf),
    /// Given: a list (the Python package's array of `(vertex, angle)`).
    List(GivenCones),
}

/// Arguments of `conformap atlas`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct AtlasJob {
    /// The mesh: any number of components, each a valid surface of any topology; a
    /// non-manifold vertex or edge is split there ([`crate::pipeline::read_input_splitting`]).
    pub input: InputOptions,
    /// The outputs: `-o` holds one texture coordinate per face corner (`f v/vt`, the `v`
    /// lines in the input's order), every coordinate in `[0,1]²`; `--flat` the atlas as a
    /// flat mesh (one vertex per texture coordinate).
    pub output: OutputOptions,
    /// Cones per closed component (and per component with handles); `None`: 8 there, 0 on
    /// a genus-0 component with boundary.
    pub cones: Option<usize>,
    /// Texels a side of the texture the margin is measured in. Default: 1024.
    pub resolution: usize,
    /// Empty texels between charts. Default: 2.
    pub margin: f64,
    /// Where the cones come from. Default: [`ConeChoice::Count`].
    pub cone_choice: ConeChoice,
    /// The area spread per component `--cones auto` stops at. Default:
    /// [`DEFAULT_MAX_AREA_SPREAD`].
    pub max_area_spread: f64,
    /// `--pack none`: the charts kept in their own coordinates (texture units = 3D units
    /// about), moved apart side by side, not packed into `[0,1]²`. Default: false.
    pub pack_none: bool,
    /// `--scale per-chart`: every chart scaled to the same texture area instead of one
    /// texel density for the whole atlas. Default: false.
    pub per_chart_scale: bool,
    /// `--seamless`: cone angles multiples of 90° and every seam a rotation by a multiple
    /// of 90° plus a translation (genus ≥ 1: a holomorphic 1-form's layout, seams pure
    /// translations); charts packed with quarter turns only. Default: false.
    pub seamless: bool,
    /// `--polish[=WHEN]`: which charts' layouts are polished after they are flattened
    /// ([`AtlasOptions::polish`]). Default: [`Polish::Auto`].
    pub polish: Polish,
}

impl AtlasJob {
    /// The atlas of `input` written to `output`, with the defaults.
    pub fn new(input: InputOptions, output: OutputOptions) -> Self {
        Self {
            input,
            output,
            cones: None,
            resolution: PackOptions::DEFAULT.resolution,
            margin: PackOptions::DEFAULT.margin_texels,
            cone_choice: ConeChoice::Count,
            max_area_spread: DEFAULT_MAX_AREA_SPREAD,
            pack_none: false,
            per_chart_scale: false,
            seamless: false,
            polish: Polish::Auto,
        }
    }

    /// With `cones` cones on every closed component.
    pub fn with_cones(mut self, cones: usize) -> Self {
        self.cones = Some(cones);
        self
    }

    fn options(&self) -> AtlasOptions {
        let mut o = AtlasOptions::DEFAULT;
        o.cones = self.cones;
        o.pack = PackOptions::DEFAULT
            .with_resolution(self.resolution)
            .with_margin_texels(self.margin);
        if self.cone_choice == ConeChoice::Auto {
            o.max_area_spread = Some(self.max_area_spread);
        }
        if self.pack_none {
            o.layout = Layout::Keep;
        }
        if self.per_chart_scale {
            o.scale = ChartScale::PerChart;
        }
        o.seamless = self.seamless;
        o.polish = self.polish;
        o
    }

    /// The given cones, read and checked against `mesh`; `None` when they are placed.
    fn given_cones(&self, input: &Input) -> Result<Option<Vec<(u32, f64)>>, Failure> {
        let given = match &self.cone_choice {
            ConeChoice::File(path) => parse_cone_file(path)?,
            ConeChoice::List(list) => list.clone(),
            _ => return Ok(None),
        };
        let n = input.mesh.num_vertices();
        let copies = match &input.split {
            Some(s) => &s.vertex_to_input[n - s.report.vertices_added..],
            None => &[][..],
        };
        let checked = given.check(&input.mesh, copies)?;
        if self.seamless {
            // a seamless atlas needs every cone angle a multiple of 90°
            for &(v, defect) in &checked {
                let quarters = defect / std::f64::consts::FRAC_PI_2;
                if (quarters - quarters.round()).abs() > SEAMLESS_ANGLE_TOLERANCE {
                    let source = match &self.cone_choice {
                        ConeChoice::File(path) => path.display().to_string(),
                        _ => "cones".into(),
                    };
                    return Err(Failure::BadInput(
                        format!(
                            "{source}: cone at vertex {v}: angle {:.6}° is not a multiple of 90°, which \
                             --seamless needs",
                            (std::f64::consts::TAU - defect).to_degrees()
                        ),
                        Some(
                            "give cone angles of 90, 180, 270, 450, 540, ... degrees, or drop \
                             --seamless"
                                .into(),
                        ),
                    ));
                }
            }
        }
        Ok(Some(checked))
    }
}

impl MapJob for AtlasJob {
    fn name(&self) -> &'static str {
        "atlas"
    }

    fn work(&self) -> &'static str {
        "a texture atlas"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn other_inputs(&self) -> Vec<&Path> {
        match &self.cone_choice {
            ConeChoice::File(path) => vec![path.as_path()],
            _ => Vec::new(),
        }
    }

    fn check_usage(&self) -> Result<(), Failure> {
        if self.seamless && self.cone_choice == ConeChoice::Auto {
            return Err(Failure::Usage(
                "--seamless takes --cones N or --cones FILE (angles multiples of 90°), not \
                 --cones auto: rounding the cones to quarter turns changes the area spread \
                 the automatic count aims at"
                    .into(),
            ));
        }
        if !(self.max_area_spread > 0.0 && self.max_area_spread.is_finite()) {
            return Err(Failure::Usage(format!(
                "--max-area-spread must be a finite number above 0, got {}",
                self.max_area_spread
            )));
        }
        if self.resolution == 0 {
            return Err(Failure::Usage(
                "--resolution must be at least 1 texel".into(),
            ));
        }
        if !(self.margin >= 0.0 && self.margin.is_finite()) {
            return Err(Failure::Usage(format!(
                "--margin must be a finite number of texels, 0 or more, got {}",
                self.margin
            )));
        }
        Ok(())
    }

    fn splits_non_manifold(&self) -> bool {
        true
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        atlas_peak_bytes_with(mesh, &self.options())
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let given = self.given_cones(input)?;
        let t = std::time::Instant::now();
        let atlas = build_atlas_of_mesh(mesh, &self.options(), given.as_deref())
            .map_err(|e| input.fail(atlas_failure(&e)))?;
        let solve_ms = t.elapsed().as_secs_f64() * 1e3;
        // the metrics (one core) beside the shared texture coordinates (the other)
        let (metrics, uv) = rayon::join(
            || {
                let t = std::time::Instant::now();
                let corner: Vec<Complex64> = atlas
                    .uv
                    .iter()
                    .map(|p| Complex64::new(p[0], p[1]))
                    .collect();
                let metrics = corner_map_metrics(mesh, &corner, &MetricsOptions::DEFAULT);
                (metrics, t.elapsed().as_secs_f64() * 1e3)
            },
            || shared_corner_uv(mesh, &atlas.uv),
        );
        let (metrics, metrics_ms) = (metrics.0?, metrics.1);
        let mut atlas = atlas;
        atlas.report.non_manifold = input.split.as_ref().map(|s| s.report.clone());
        let r = &atlas.report;
        let solver = SolverSection::new(r.summary(), SolverDetail::None);
        let clean = solver.summary.converged;
        let flat_points = uv.texcoords.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let flat_faces = uv.faces.clone();
        let mut summary = format!(
            "{} vertices, {} faces; {} component(s), {} chart(s), {} cone(s); area spread {:.3}, \
             mean angle distortion {:.3}°, flipped faces {}, texels covered twice {}, packing {:.2}",
            mesh.num_vertices(),
            mesh.num_faces(),
            r.components,
            r.charts,
            r.cones,
            r.area_spread,
            r.angle_mean_deg,
            r.flipped,
            r.overlap.covered_twice,
            r.packing_efficiency,
        );
        if let Some(auto) = &r.auto_cones {
            summary.push_str(&format!(
                "; --cones auto: {:?} cone(s) per component for an area spread of at most {}",
                auto.counts, auto.max_area_spread
            ));
            if !auto.capped.is_empty() {
                summary.push_str(&format!(
                    " (component(s) {:?} stopped at the cap of {} cones before reaching it)",
                    auto.capped, auto.cap
                ));
            }
        }
        if let Some(s) = &r.non_manifold {
            summary.push_str(&format!(
                "; non-manifold input split: {} vertex(es) (first: {:?}) into {} more, {} edge(s) \
                 of 3+ faces cut",
                s.vertices_split, s.split_vertices, s.vertices_added, s.edges_split
            ));
        }
        if self.pack_none {
            summary.push_str("; packing off (charts in their own coordinates)");
        }
        if self.per_chart_scale {
            summary.push_str("; one scale per chart");
        }
        if self.seamless {
            summary.push_str(&format!(
                "; seamless: seam rotation within {:.1e} rad of a quarter turn, residual after \
                 the rigid map {:.1e} of the edge length",
                r.seam_rotation_error_max, r.seam_rigid_residual_max
            ));
        }
        match (r.polish_energy, r.polish) {
            (Some([before, after]), _) if before > 0.0 => summary.push_str(&format!(
                "; polished {} of {} components: distortion energy {:.0} % lower",
                r.polished_components,
                r.components,
                100.0 * (1.0 - after / before)
            )),
            (None, Polish::Always) => {
                summary.push_str("; nothing polished (free boundaries kept as flattened)")
            }
            _ => {}
        }
        let strict_violation = (!clean).then(|| {
            format!(
                "the atlas has {} flipped faces and {} texels covered twice",
                r.flipped, r.overlap.covered_twice
            )
        });
        Ok(Solved {
            picture_domain: None,
            method: "atlas-cones".into(),
            uv: TexCoords::PerCorner(uv),
            flat: (flat_points, Some(flat_faces)),
            solver,
            param: None,
            sections: crate::report::Sections {
                atlas: Some(atlas.report.clone()),
                ..Default::default()
            },
            metrics: MetricsSection::planar(metrics),
            timings: StageTimings {
                solve: solve_ms,
                metrics: metrics_ms,
                ..StageTimings::default()
            },
            strict_violation,
            summary,
        })
    }
}

/// Per-corner texture coordinates with one entry per distinct (vertex, coordinate): the
/// corners of a vertex inside one chart share their `vt`.
fn shared_corner_uv(mesh: &TriMesh, corner: &[[f64; 2]]) -> CornerUv {
    let mut index: HashMap<(u32, u64, u64), u32> = HashMap::default();
    let mut texcoords = Vec::new();
    let faces = mesh
        .faces()
        .iter()
        .enumerate()
        .map(|(f, t)| {
            std::array::from_fn(|k| {
                let p = corner[3 * f + k];
                *index
                    .entry((t[k], p[0].to_bits(), p[1].to_bits()))
                    .or_insert_with(|| {
                        texcoords.push(p);
                        (texcoords.len() - 1) as u32
                    })
            })
        })
        .collect();
    CornerUv { texcoords, faces }
}

/// The failure of an atlas error: a layout the options or the input rule out is bad input
/// (exit 1) with the atlas's hint; a solve that broke is numerical (exit 3), the hint
/// in its message.
fn atlas_failure(e: &conformap_atlas::AtlasError) -> Failure {
    use conformap_atlas::AtlasError as E;
    match e {
        E::SeamlessFolds { .. }
        | E::SeamlessNotRigid { .. }
        | E::TooManyCharts { .. }
        | E::Component { .. } => Failure::BadInput(e.to_string(), Some(e.hint().to_string())),
        E::InvalidOption { .. } => Failure::Usage(e.to_string()),
        _ => Failure::Numerical(format!("{e}\nhint: {}", e.hint())),
    }
}
