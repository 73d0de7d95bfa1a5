//! `conformap atlas MESH -o OUT ...`: a texture atlas of any mesh — every component charted
//! (closed ones through cones and their handles), charts that overlap themselves split,
//! everything packed into `[0,1]²` with one texel density.

use std::collections::HashMap;

use conformap_atlas::{atlas_peak_bytes, build_atlas, AtlasOptions, PackOptions};
use conformap_io::CornerUv;
use conformap_mesh::TriMesh;
use conformap_metrics::{corner_map_metrics, MetricsOptions};
use num_complex::Complex64;

use crate::failure::Failure;
use crate::pipeline::{Input, InputOptions, MapJob, OutputOptions, Solved, TexCoords};
use crate::report::{MetricsSection, SolverDetail, SolverSection, StageTimings};

/// Arguments of `conformap atlas`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct AtlasJob {
    /// The mesh: any number of components, each a valid manifold surface of any topology.
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
        o
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

    fn check_usage(&self) -> Result<(), Failure> {
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

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        atlas_peak_bytes(mesh)
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let t = std::time::Instant::now();
        let atlas = build_atlas(mesh.positions(), mesh.faces(), &self.options())
            .map_err(|e| input.fail(Failure::Numerical(e.to_string())))?;
        let solve_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = std::time::Instant::now();
        let corner: Vec<Complex64> = atlas
            .uv
            .iter()
            .map(|p| Complex64::new(p[0], p[1]))
            .collect();
        let metrics = corner_map_metrics(mesh, &corner, &MetricsOptions::DEFAULT)?;
        let metrics_ms = t.elapsed().as_secs_f64() * 1e3;
        let r = &atlas.report;
        let solver = SolverSection::new(r.summary(), SolverDetail::None);
        let clean = solver.summary.converged;
        let uv = shared_corner_uv(mesh, &atlas.uv);
        let flat_points = uv.texcoords.iter().map(|p| [p[0], p[1], 0.0]).collect();
        let flat_faces = uv.faces.clone();
        let summary = format!(
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
    let mut index: HashMap<(u32, u64, u64), u32> = HashMap::new();
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
