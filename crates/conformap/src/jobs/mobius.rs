//! `conformap mobius MESH PARAM --domain disk|sphere --objective uniform|emphasize ...`: the
//! optimal Möbius transformation of a disk or sphere map.

use std::path::{Path, PathBuf};
use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_metrics::{cross_ratio_distortion, planar_map_metrics, MetricsOptions};
use conformap_sphere::{
    from_equirectangular_uv, mobius_peak_bytes, optimize_disk_mobius, optimize_sphere_mobius,
    sphere_metrics, sphere_points_from_corner_uv, MobiusObjective, MobiusOptions, MobiusReport,
    EMPHASIZE_MAX_AREA_SCALE,
};

use crate::failure::Failure;
use crate::jobs::param::{on_unit_sphere, read_map_file, read_region, MapFile};
use crate::jobs::sphere::sphere_tex_coords;
use crate::pipeline::{
    disk_uv, planar_points, Input, InputOptions, MapJob, OutputOptions, Solved, TexCoords,
};
use crate::report::{
    ms_since, MetricsExtra, MetricsSection, MobiusDetail, ParamInfo, SolverDetail, SolverSection,
    StageTimings,
};

/// The default of [`MobiusJob::max_area_scale`]: the library's
/// [`EMPHASIZE_MAX_AREA_SCALE`].
pub const DEFAULT_MAX_AREA_SCALE: f64 = EMPHASIZE_MAX_AREA_SCALE;

crate::choice! {
    /// The domain of the map.
    pub enum Domain {
        /// A planar map in the unit disk; Möbius maps `(az + b)/(b̄z + ā)`.
        Disk = "disk",
        /// A map onto the unit sphere; Möbius maps `(az + b)/(cz + d)` through stereographic
        /// projection.
        Sphere = "sphere",
    }
}

crate::choice! {
    /// The energy to optimize.
    pub enum Objective {
        /// Minimize the uniformity energy Σ (image area share − surface area share)².
        Uniform = "uniform",
        /// Maximize the image-area share of the faces in --region (with --max-area-scale).
        Emphasize = "emphasize",
        /// Maximize the mean log area magnification of the faces in --region (no cap needed).
        EmphasizeDensity = "emphasize-density",
    }
}

/// Arguments of `conformap mobius`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct MobiusJob {
    /// The 3D mesh and how to read it.
    pub input: InputOptions,
    /// The map. Disk: texture coordinates (u = 2·vt_x − 1, v = 2·vt_y − 1, as `disk` writes)
    /// or a flat mesh whose (x, y) are the map. Sphere: a mesh whose positions are the
    /// unit-sphere points (`sphere --flat`), or else equirectangular texture coordinates
    /// (as `sphere -o` writes).
    pub param: PathBuf,
    /// The outputs: `-o` holds the moved map as texture coordinates (disk:
    /// ((u+1)/2, (v+1)/2); sphere: equirectangular, as `sphere` writes).
    pub output: OutputOptions,
    /// Domain of the map.
    pub domain: Domain,
    /// Energy to optimize.
    pub objective: Objective,
    /// Faces to emphasize: a text file with one 0-based face index per line (blank lines and
    /// lines starting with # are skipped). Required with --objective emphasize.
    pub region: Option<PathBuf>,
    /// Largest area magnification the emphasizing Möbius map may apply (> 1; only for
    /// --objective emphasize): the share of an emphasized region has no maximum, it tends to
    /// 100 % as the map degenerates.
    pub max_area_scale: f64,
    /// The map given in memory instead of read from [`MobiusJob::param`] (the Python
    /// package's arrays; `param` then only names it in the report). Default: none.
    pub param_map: Option<MapFile>,
    /// The region's faces given in memory instead of read from [`MobiusJob::region`] (each
    /// checked with [`crate::jobs::param::region_face`]). Default: none.
    pub region_faces: Option<Vec<usize>>,
}

impl MobiusJob {
    /// The optimal Möbius transformation of the map `param` of `input` on `domain` for
    /// `objective`, written to `output`; no region, the default area cap.
    pub fn new(
        input: InputOptions,
        param: impl Into<PathBuf>,
        output: OutputOptions,
        domain: Domain,
        objective: Objective,
    ) -> Self {
        Self {
            input,
            param: param.into(),
            output,
            domain,
            objective,
            region: None,
            max_area_scale: EMPHASIZE_MAX_AREA_SCALE,
            param_map: None,
            region_faces: None,
        }
    }

    /// With the faces of `region` (a file of 0-based face indices) emphasized.
    pub fn with_region(mut self, region: impl Into<PathBuf>) -> Self {
        self.region = Some(region.into());
        self
    }
}

/// The moved map of one domain, before it becomes a [`Solved`].
struct Moved {
    uv: TexCoords,
    flat: Vec<[f64; 3]>,
    report: MobiusReport,
    metrics: MetricsSection,
    from: &'static str,
}

impl MapJob for MobiusJob {
    fn name(&self) -> &'static str {
        "mobius"
    }

    fn work(&self) -> &'static str {
        "an optimal Möbius map"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn picture_domain(&self) -> crate::pipeline::PictureDomain {
        match self.domain {
            Domain::Disk => crate::pipeline::PictureDomain::Plane,
            Domain::Sphere => crate::pipeline::PictureDomain::Sphere,
        }
    }

    fn other_inputs(&self) -> Vec<&Path> {
        std::iter::once(self.param.as_path())
            .chain(self.region.as_deref())
            .collect()
    }

    fn check_usage(&self) -> Result<(), Failure> {
        let has_region = self.region.is_some() || self.region_faces.is_some();
        match (self.objective, has_region) {
            (Objective::Emphasize | Objective::EmphasizeDensity, false) => {
                return Err(Failure::Usage(
                    "--objective emphasize needs --region FACES.txt".to_string(),
                ))
            }
            (Objective::Uniform, true) => {
                return Err(Failure::Usage(
                    "--region is only used with --objective emphasize or emphasize-density"
                        .to_string(),
                ))
            }
            _ => {}
        }
        if !(self.max_area_scale > 1.0 && self.max_area_scale.is_finite()) {
            return Err(Failure::Usage(format!(
                "--max-area-scale must be a finite number > 1, got {}",
                self.max_area_scale
            )));
        }
        Ok(())
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        mobius_peak_bytes(mesh)
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let t = Instant::now();
        // connectivity checked, geometry not; non-finite values are refused by the
        // optimization, which names the vertex
        let read;
        let param = match &self.param_map {
            Some(map) => map,
            None => {
                read = read_map_file(&self.param, &self.input.mesh, mesh)?;
                &read
            }
        };
        let region = match (&self.region_faces, &self.region) {
            (Some(faces), _) => Some(faces.clone()),
            (None, Some(path)) => Some(read_region(path, mesh.num_faces())?),
            (None, None) => None,
        };
        let read_ms = if self.param_map.is_some() {
            0.0
        } else {
            ms_since(t)
        };
        self.solve_with(input, param, region, read_ms)
    }
}

impl MobiusJob {
    /// [`MapJob::solve`] on a map and a region already in memory (the Python package's
    /// arrays): `param` stands for the file `self.param` names (its connectivity already
    /// checked against the mesh), `region` for the faces of `--region` (each checked with
    /// [`crate::jobs::param::region_face`]); `read_ms` is the report's `read` time.
    ///
    /// # Errors
    /// A usage failure when the objective needs a region and there is none; every failure
    /// of the optimization and of the metrics.
    pub fn solve_with(
        &self,
        input: &Input,
        param: &MapFile,
        region: Option<Vec<usize>>,
        read_ms: f64,
    ) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let objective = match (self.objective, region) {
            (Objective::Uniform, _) => MobiusObjective::Uniform,
            (Objective::Emphasize, Some(region)) => MobiusObjective::Emphasize { region },
            (Objective::EmphasizeDensity, Some(region)) => {
                MobiusObjective::EmphasizeDensity { region }
            }
            (_, None) => {
                return Err(Failure::Usage(
                    "--objective emphasize needs --region FACES.txt".to_string(),
                ))
            }
        };
        self.check_domain(mesh)?;
        let options = MobiusOptions::DEFAULT.with_max_area_scale(self.max_area_scale);
        let t = Instant::now();
        let moved = match self.domain {
            Domain::Disk => self.disk(mesh, param, &objective, &options)?,
            Domain::Sphere => self.sphere(mesh, param, &objective, &options)?,
        };
        let metrics_ms = (ms_since(t) - moved.report.time_ms).max(0.0);
        let mobius = moved.report;
        let solver = SolverSection::new(
            mobius.summary(),
            SolverDetail::Mobius(MobiusDetail {
                energy_history_is: "the objective at the optimum of each start",
                mobius: mobius.clone(),
                residual_is: "the objective's gradient norm at the optimum",
            }),
        );
        let summary = summary(self, &mobius);
        Ok(Solved {
            picture_domain: None,
            method: format!("newton-{}", mobius.objective),
            uv: moved.uv,
            flat: (moved.flat, None),
            solver,
            param: Some(ParamInfo {
                path: self.param.display().to_string(),
                map_from: moved.from,
            }),
            sections: crate::report::Sections::default(),
            metrics: moved.metrics,
            timings: StageTimings {
                read: read_ms,
                solve: mobius.time_ms,
                metrics: metrics_ms,
                ..StageTimings::default()
            },
            strict_violation: (!mobius.converged)
                .then(|| "the Möbius optimization did not converge".to_string()),
            summary,
        })
    }

    /// Refuses a domain the mesh has no map onto: a sphere map needs a closed genus-0
    /// mesh, a disk map a mesh with boundary (bad input, exit 1, with the domain or the
    /// command that fits).
    fn check_domain(&self, mesh: &TriMesh) -> Result<(), Failure> {
        let loops = mesh.boundary_loops().len();
        let genus = mesh.genus();
        let what = self.input.mesh.display();
        let refuse = |msg: String, hint: &str| Err(Failure::BadInput(msg, Some(hint.into())));
        match self.domain {
            Domain::Sphere if loops > 0 => refuse(
                format!(
                    "{what} has {loops} boundary loop(s): --domain sphere moves the sphere map \
                     of a closed genus-0 mesh, and a mesh with boundary has none"
                ),
                "a map of a mesh with boundary is a disk map: rerun with --domain disk",
            ),
            Domain::Sphere if genus != Some(0) => refuse(
                format!(
                    "{what} is {}: --domain sphere needs a closed genus-0 mesh",
                    mesh.topology()
                ),
                "a closed surface with handles has no sphere map: `conformap global` maps it",
            ),
            Domain::Disk if loops == 0 && genus == Some(0) => refuse(
                format!(
                    "{what} is closed (no boundary loop): it has no disk map, so --domain disk \
                     does not fit; its map is a sphere map"
                ),
                "rerun with --domain sphere (on the -o or --flat output of `conformap sphere`)",
            ),
            Domain::Disk if loops == 0 => refuse(
                format!(
                    "{what} is {}: it has no disk map, so --domain disk does not fit",
                    mesh.topology()
                ),
                "`conformap global` maps closed surfaces with handles; the Möbius \
                 optimization moves disk and sphere maps only",
            ),
            _ => Ok(()),
        }
    }

    fn fail(&self, e: impl Into<Failure>) -> Failure {
        e.into().in_file(&self.param)
    }

    /// A disk map, moved by its optimal automorphism.
    fn disk(
        &self,
        mesh: &TriMesh,
        param: &MapFile,
        objective: &MobiusObjective,
        options: &MobiusOptions,
    ) -> Result<Moved, Failure> {
        let (map, from) = param.planar()?;
        let best =
            optimize_disk_mobius(mesh, &map, objective, options).map_err(|e| self.fail(e))?;
        let before = planar_map_metrics(mesh, &map, &MetricsOptions::default())
            .map_err(|e| Failure::input(format!("{}: {e}", self.param.display())))?;
        let after = planar_map_metrics(mesh, &best.map, &MetricsOptions::default())?;
        // the map was checked by planar_map_metrics above
        let cr_before = cross_ratio_distortion(mesh, &map)?;
        let cr_after = cross_ratio_distortion(mesh, &best.map)?;
        let metrics = MetricsSection::planar(after).and(MetricsExtra::MobiusDisk {
            angle_distortion_deg_before: before.angle_distortion_deg,
            cross_ratio_log: cr_after,
            cross_ratio_log_before: cr_before,
            uniformity_energy: best.report.uniformity_after,
            uniformity_energy_before: best.report.uniformity_before,
        });
        Ok(Moved {
            uv: disk_uv(&best.map).into(),
            flat: planar_points(&best.map),
            report: best.report,
            metrics,
            from,
        })
    }

    /// A sphere map, moved by its optimal Möbius transformation.
    fn sphere(
        &self,
        mesh: &TriMesh,
        param: &MapFile,
        objective: &MobiusObjective,
        options: &MobiusOptions,
    ) -> Result<Moved, Failure> {
        let on_sphere = param.positions.iter().all(on_unit_sphere);
        let corners = param
            .corner_uv
            .as_ref()
            .and_then(|c| sphere_points_from_corner_uv(mesh, &c.texcoords, &c.faces));
        let (points, from): (Vec<[f64; 3]>, &'static str) = match (&param.uv, on_sphere) {
            (_, true) => (param.positions.clone(), "sphere positions"),
            (Some(uv), false) => (
                uv.iter().map(|&t| from_equirectangular_uv(t)).collect(),
                "equirectangular texture coordinates",
            ),
            (None, false) if corners.is_some() => (
                corners.unwrap_or_default(),
                "equirectangular texture coordinates per corner",
            ),
            (None, false) => {
                return Err(Failure::BadInput(
                    format!(
                        "{}: neither are its positions on the unit sphere nor has it texture \
                         coordinates",
                        self.param.display()
                    ),
                    Some("pass the --flat or -o output of `conformap sphere`".to_string()),
                ))
            }
        };
        let best =
            optimize_sphere_mobius(mesh, &points, objective, options).map_err(|e| self.fail(e))?;
        let before = sphere_metrics(mesh, &points).map_err(|e| self.fail(e))?;
        let after = sphere_metrics(mesh, &best.points).map_err(|e| self.fail(e))?;
        let metrics = MetricsSection::sphere(after).and(MetricsExtra::MobiusSphere {
            angle_distortion_deg_before: before.angle_distortion_deg,
            cross_ratio_log_before: before.cross_ratio_log,
            uniformity_energy_before: before.uniformity_energy,
        });
        Ok(Moved {
            uv: sphere_tex_coords(mesh, &best.points).map_err(|e| self.fail(e))?,
            flat: best.points,
            report: best.report,
            metrics,
            from,
        })
    }
}

/// The summary line of a Möbius optimization.
fn summary(args: &MobiusJob, mobius: &MobiusReport) -> String {
    let cap = if args.objective == Objective::Emphasize {
        format!(
            ", area magnification cap {}{}",
            args.max_area_scale,
            if mobius.cap_active { ", reached" } else { "" }
        )
    } else {
        String::new()
    };
    let what = match (mobius.region_share_before, mobius.region_share_after) {
        (Some(b), Some(a)) => format!(
            "emphasized region's image share {:.2} % → {:.2} % (surface share {:.2} %{cap})",
            100.0 * b,
            100.0 * a,
            100.0 * mobius.region_surface_share.unwrap_or(0.0),
        ),
        _ => format!(
            "uniformity energy {:.4e} → {:.4e}",
            mobius.uniformity_before, mobius.uniformity_after
        ),
    };
    let limited = match mobius.flip_limited {
        Some(t) => format!(
            " (boost shortened to {t:.3} of the optimum: a longer one inverts crowded faces)"
        ),
        None => String::new(),
    };
    format!("optimal {} Möbius map: {what}{limited}", mobius.domain)
}
