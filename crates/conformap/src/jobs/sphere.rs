//! `conformap sphere MESH -o OUT ...`: conformal map of a closed genus-0 mesh onto the unit
//! sphere.

use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_sphere::{
    equirectangular_corner_uv, optimize_sphere_mobius, sphere_map, sphere_metrics,
    sphere_peak_bytes, MobiusObjective, MobiusOptions, SphereError, SphereMetrics, SphereOptions,
};

use crate::failure::Failure;
use crate::pipeline::{
    Input, InputOptions, MapJob, OutputOptions, PictureDomain, Solved, TexCoords,
};
use crate::report::{
    ms_since, MetricsExtra, MetricsSection, SolverDetail, SolverSection, SphereDetail, StageTimings,
};

crate::choice! {
    /// The Möbius normalization applied to the sphere map.
    pub enum SphereMobius {
        /// None: the map as computed (source of Angenent's dipole near the north pole).
        None = "none",
        /// The Möbius map minimizing the uniformity energy (Jin et al. 2004, §3.4).
        Uniform = "uniform",
    }
}

/// Arguments of `conformap sphere`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct SphereJob {
    /// The mesh (closed, connected, genus 0) and how to read it.
    pub input: InputOptions,
    /// The outputs: `-o` holds the equirectangular projection of the sphere point,
    /// u = (atan2(y, x) + π)/2π, v = (asin z + π/2)/π, one `vt` per face corner, split
    /// along the seam meridian (a face crossing it keeps its corners together, some `u` in
    /// (1, 1.25): `REPEAT` wrapping) and with the poles treated (see
    /// [`conformap_sphere::equirectangular_corner_uv`]); `--flat` the unit-sphere points.
    pub output: OutputOptions,
    /// Möbius normalization of the map.
    pub mobius: SphereMobius,
}

impl SphereJob {
    /// The sphere map of `input` written to `output`, no Möbius normalization.
    pub fn new(input: InputOptions, output: OutputOptions) -> Self {
        Self {
            input,
            output,
            mobius: SphereMobius::None,
        }
    }

    /// With the Möbius normalization `mobius`.
    pub fn with_mobius(mut self, mobius: SphereMobius) -> Self {
        self.mobius = mobius;
        self
    }
}

impl MapJob for SphereJob {
    fn name(&self) -> &'static str {
        "sphere"
    }

    fn work(&self) -> &'static str {
        "a sphere map"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn picture_domain(&self) -> PictureDomain {
        PictureDomain::Sphere
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        sphere_peak_bytes(mesh)
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let fail = |e: conformap_sphere::SphereError| input.fail(e.into());
        let map = sphere_map(mesh, &SphereOptions::DEFAULT).map_err(fail)?;
        let t = Instant::now();
        let before = sphere_metrics(mesh, &map.points).map_err(fail)?;
        let mut metrics_ms = ms_since(t);
        let (points, mobius, after, mobius_ms) = match self.mobius {
            SphereMobius::None => (map.points.clone(), None, before.clone(), 0.0),
            SphereMobius::Uniform => {
                let t = Instant::now();
                let best = optimize_sphere_mobius(
                    mesh,
                    &map.points,
                    &MobiusObjective::Uniform,
                    &MobiusOptions::DEFAULT,
                )
                .map_err(fail)?;
                let mobius_ms = ms_since(t);
                let t = Instant::now();
                let after = sphere_metrics(mesh, &best.points).map_err(fail)?;
                metrics_ms += ms_since(t);
                (best.points, Some(best.report), after, mobius_ms)
            }
        };
        let s = &map.report;
        let method = match self.mobius {
            SphereMobius::None => s.method.clone(),
            SphereMobius::Uniform => format!("{}+mobius-uniform", s.method),
        };
        let extra = match &mobius {
            Some(m) => MetricsExtra::SphereMobius {
                angle_distortion_deg_before_mobius: before.angle_distortion_deg,
                uniformity_energy_before_mobius: m.uniformity_before,
            },
            None => MetricsExtra::None,
        };
        let metrics = MetricsSection::sphere(after.clone()).and(extra);
        // converged as the sphere map (and its Möbius normalization, if any) decided it
        let summary_of_solver = s.summary_with_mobius(mobius.as_ref());
        let converged = summary_of_solver.converged;
        let solver = SolverSection::new(
            summary_of_solver,
            SolverDetail::Sphere(SphereDetail {
                energy_history_is: "mean chord-angle distortion (degrees) after each stage",
                mobius,
                sphere: s.clone(),
            }),
        );
        let summary = summary(
            mesh,
            s.corrections,
            matches!(self.mobius, SphereMobius::Uniform),
            &after,
        );
        let strict_violation = strict_violation(&after, converged, s.residual);
        Ok(Solved {
            picture_domain: None,
            method,
            uv: sphere_tex_coords(mesh, &points).map_err(fail)?,
            flat: (points, None),
            solver,
            param: None,
            sections: crate::report::Sections::default(),
            metrics,
            timings: StageTimings {
                assemble: s.timings_ms.assemble,
                factor: s.timings_ms.factor,
                solve: s.timings_ms.solve + mobius_ms,
                metrics: metrics_ms,
                ..StageTimings::default()
            },
            strict_violation,
            summary,
        })
    }
}

/// The texture coordinates `-o` gets for a sphere map (of `sphere`, `mobius --domain
/// sphere` and `global --topology-opt`): the equirectangular texture, one `vt` per face
/// corner ([`equirectangular_corner_uv`]).
///
/// # Errors
/// A map of the wrong length or with a non-finite point.
pub(crate) fn sphere_tex_coords(
    mesh: &TriMesh,
    points: &[[f64; 3]],
) -> Result<TexCoords, SphereError> {
    let t = equirectangular_corner_uv(mesh, points)?;
    Ok(TexCoords::PerCorner(conformap_io::CornerUv {
        texcoords: t.texcoords,
        faces: t.faces,
    }))
}

/// The summary line of a sphere map.
fn summary(mesh: &TriMesh, corrections: usize, mobius: bool, after: &SphereMetrics) -> String {
    format!(
        "{} vertices, {} faces; sphere map with {} correction(s){}; mean angle \
         distortion {:.3}°, inverted faces {}, uniformity energy {:.3e}",
        mesh.num_vertices(),
        mesh.num_faces(),
        corrections,
        if mobius {
            " and uniform Möbius normalization"
        } else {
            ""
        },
        after.angle_distortion_deg.mean,
        after.flipped_faces,
        after.uniformity_energy,
    )
}

/// Why `--strict` refuses the map: inverted faces, or a solve that did not converge.
fn strict_violation(after: &SphereMetrics, converged: bool, residual: f64) -> Option<String> {
    if after.flipped_faces > 0 {
        Some(format!(
            "{} triangles are inverted on the sphere",
            after.flipped_faces
        ))
    } else if !converged {
        Some(format!(
            "the sphere map did not converge (solve residual {residual:.1e})"
        ))
    } else {
        None
    }
}
