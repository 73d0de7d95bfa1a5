//! `conformap flatten MESH -o OUT ...`: boundary first flattening (Sawhney & Crane 2017) —
//! a free boundary with the least area distortion, given boundary scale factors or angles,
//! BFF's circle, rectangles and polygons with exact corners.

use conformap_disk::{flatten, flatten_peak_bytes, BoundarySpec, FlattenInterior, FlattenOptions};
use conformap_mesh::TriMesh;

use crate::failure::Failure;
use crate::pipeline::{planar_points, Input, InputOptions, MapJob, OutputOptions, Solved};
use crate::report::{MetricsSection, SolverDetail, SolverSection, StageTimings};

crate::choice! {
    /// How the interior follows the boundary curve.
    pub enum Interior {
        /// `x` and `y` harmonic, the boundary curve met exactly (default: never folded on
        /// the shared meshes, angle distortion at most the conjugate's).
        Harmonic = "harmonic",
        /// `y` the harmonic conjugate of `x` (the paper's variant; one more factorization).
        Conjugate = "conjugate",
    }
}

/// Arguments of `conformap flatten`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct FlattenJob {
    /// The mesh (connected, genus 0, with a boundary; holes are filled and left free).
    pub input: InputOptions,
    /// The outputs: `-o` holds the map as one texture coordinate per vertex, the layout's
    /// bounding box scaled uniformly into `[0,1]²` (aspect kept: `vt = (p − min) / side`
    /// with `side` the box's longer side); `--flat` the raw layout `(u, v, 0)`.
    pub output: OutputOptions,
    /// The boundary target: `free` (default), `circle`, `rectangle`, `scale:FILE`,
    /// `angles:FILE` or `polygon:FILE` (files: `<0-based vertex> <value>` per line; angles
    /// are exterior angles in degrees).
    pub boundary: BoundarySpec,
    /// The rectangle's corners, in boundary order (the first to the second is the width);
    /// `None`: chosen automatically.
    pub corners: Option<[u32; 4]>,
    /// The rectangle's width over height; `None`: the conformal modulus.
    pub aspect: Option<f64>,
    /// The interior variant.
    pub interior: Interior,
    /// The text of the boundary file given in memory (the Python package's `values`):
    /// used instead of reading [`BoundarySpec::file`].
    pub boundary_text: Option<String>,
}

impl FlattenJob {
    /// The free-boundary flattening of `input` written to `output`.
    pub fn new(input: InputOptions, output: OutputOptions) -> Self {
        Self {
            input,
            output,
            boundary: BoundarySpec::Free,
            corners: None,
            aspect: None,
            interior: Interior::Harmonic,
            boundary_text: None,
        }
    }

    /// With another boundary target.
    pub fn with_boundary(mut self, boundary: BoundarySpec) -> Self {
        self.boundary = boundary;
        self
    }

    /// With the rectangle's corners.
    pub fn with_corners(mut self, corners: [u32; 4]) -> Self {
        self.corners = Some(corners);
        self
    }

    /// With the rectangle's aspect (width over height).
    pub fn with_aspect(mut self, aspect: f64) -> Self {
        self.aspect = Some(aspect);
        self
    }

    /// With another interior variant.
    pub fn with_interior(mut self, interior: Interior) -> Self {
        self.interior = interior;
        self
    }

    fn library_interior(&self) -> FlattenInterior {
        match self.interior {
            Interior::Harmonic => FlattenInterior::Harmonic,
            Interior::Conjugate => FlattenInterior::Conjugate,
        }
    }

    /// The library's options, the boundary file's text read (a boundary of a file-taking
    /// mode without its text falls back to the free boundary, for the memory estimate).
    fn options(&self, text: Option<&str>) -> Result<FlattenOptions, conformap_disk::DiskError> {
        let boundary = if self.boundary.file().is_some() && text.is_none() {
            conformap_disk::FlattenBoundary::Free
        } else {
            self.boundary
                .clone()
                .into_boundary(text, self.corners, self.aspect)?
        };
        Ok(FlattenOptions::DEFAULT
            .with_boundary(boundary)
            .with_interior(self.library_interior()))
    }
}

impl MapJob for FlattenJob {
    fn name(&self) -> &'static str {
        "flatten"
    }

    fn work(&self) -> &'static str {
        "a boundary first flattening"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn other_inputs(&self) -> Vec<&std::path::Path> {
        match self.boundary_text {
            Some(_) => Vec::new(),
            None => self.boundary.file().into_iter().collect(),
        }
    }

    fn check_usage(&self) -> Result<(), Failure> {
        let rectangle = matches!(self.boundary, BoundarySpec::Rectangle);
        if !rectangle && (self.corners.is_some() || self.aspect.is_some()) {
            return Err(Failure::Usage(
                "--corners and --aspect shape a rectangle: add --boundary rectangle".into(),
            ));
        }
        if let Some(a) = self.aspect {
            if !(a > 0.0 && a.is_finite()) {
                return Err(Failure::Usage(format!(
                    "--aspect must be a positive width/height, got {a}"
                )));
            }
        }
        Ok(())
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        let options = self.options(None).unwrap_or_default();
        flatten_peak_bytes(mesh, &options)
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        check_topology(mesh).map_err(|f| input.fail(f))?;
        let t = std::time::Instant::now();
        let text = match (self.boundary.file(), &self.boundary_text) {
            (_, Some(text)) => Some(text.clone()),
            (Some(path), None) => Some(std::fs::read_to_string(path).map_err(|e| {
                Failure::BadInput(
                    format!("cannot read {}: {e}", path.display()),
                    Some("give a readable text file of `<vertex> <value>` lines".into()),
                )
            })?),
            (None, None) => None,
        };
        let read_ms = t.elapsed().as_secs_f64() * 1e3;
        let options = self
            .options(text.as_deref())
            .map_err(|e| input.fail(e.into()))?;
        let flat = flatten(mesh, &options).map_err(|e| input.fail(e.into()))?;
        let r = &flat.report;
        let solver = SolverSection::new(r.summary(), SolverDetail::None);
        let converged = solver.summary.converged;
        let sections = crate::report::Sections {
            flatten: Some(r.clone()),
            ..Default::default()
        };
        let flipped = r.metrics.flipped_faces;
        let strict_violation = if !r.overlap_free {
            Some(format!(
                "the flattening overlaps itself ({flipped} folded faces, {} boundary touches)",
                r.boundary_touches
            ))
        } else if !converged {
            Some(format!(
                "the boundary curve did not close (residual {:.1e})",
                r.closure_residual
            ))
        } else {
            None
        };
        let summary = format!(
            "{} vertices, {} faces; {} boundary{}; area spread {:.3}, mean angle distortion \
             {:.3}°, flipped faces {}{}",
            mesh.num_vertices(),
            mesh.num_faces(),
            r.boundary,
            r.aspect
                .map_or(String::new(), |a| format!(" (aspect {a:.6})")),
            r.metrics.area_distortion_log.sd,
            r.metrics.angle_distortion_deg.mean,
            flipped,
            if r.overlap_free {
                ""
            } else {
                "; the image overlaps itself"
            },
        );
        Ok(Solved {
            picture_domain: None,
            method: format!("bff-{}", r.boundary),
            uv: unit_square_uv(&flat.map).into(),
            flat: (planar_points(&flat.map), None),
            solver,
            param: None,
            sections,
            metrics: MetricsSection::planar(r.metrics.clone()),
            timings: StageTimings {
                read: read_ms,
                assemble: flat.timings.setup,
                solve: flat.timings.boundary + flat.timings.curve + flat.timings.interior,
                metrics: flat.timings.metrics,
                ..StageTimings::default()
            },
            strict_violation,
            summary,
        })
    }
}

/// A flattening needs a connected genus-0 surface with a boundary; every other topology
/// is refused with the command that maps it.
fn check_topology(mesh: &TriMesh) -> Result<(), Failure> {
    use conformap_mesh::Topology as T;
    let found = mesh.topology();
    if matches!(found, T::Disk | T::MultiplyConnected { .. }) {
        return Ok(());
    }
    Err(Failure::BadInput(
        format!(
            "boundary first flattening needs a connected genus-0 surface with a boundary, but \
             the mesh is {}",
            topology_name(mesh)
        ),
        Some(crate::failure::topology_hint(&found)),
    ))
}

fn topology_name(mesh: &TriMesh) -> String {
    match (mesh.genus(), mesh.boundary_loops().len()) {
        (Some(0), 0) => "a closed genus-0 surface".into(),
        (Some(g), 0) => format!("a closed surface of genus {g}"),
        (Some(g), b) => format!("a surface of genus {g} with {b} boundary loop(s)"),
        (None, _) => format!("{} components", mesh.num_components()),
    }
}

/// Texture coordinates of a planar layout: its bounding box scaled uniformly into
/// `[0,1]²` (aspect kept), `vt = (p − min) / side`.
pub fn unit_square_uv(map: &[num_complex::Complex64]) -> Vec<[f64; 2]> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for z in map {
        lo = [lo[0].min(z.re), lo[1].min(z.im)];
        hi = [hi[0].max(z.re), hi[1].max(z.im)];
    }
    let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    let side = if side > 0.0 { side } else { 1.0 };
    map.iter()
        .map(|z| [(z.re - lo[0]) / side, (z.im - lo[1]) / side])
        .collect()
}
