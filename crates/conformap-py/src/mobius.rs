//! `mobius`: the `mobius` job on arrays. The map and the region are given in memory
//! ([`MobiusJob::param_map`], [`MobiusJob::region_faces`]) instead of `PARAM` and
//! `--region` files; everything else (usage check, memory check, the report) is
//! [`conformap::run_in_memory`]'s, as for `disk_map`.

use std::path::PathBuf;

use conformap::failure::Failure;
use conformap::jobs::mobius::{Domain, MobiusJob, Objective};
use conformap::jobs::param::{on_unit_sphere, MapFile, UNIT_SPHERE_TOL};
use conformap::pipeline::{InputOptions, OutputOptions};
use numpy::PyArray2;
use pyo3::prelude::*;

use crate::arrays::{mesh_input, points, to_array, MEMORY_PATH};
use crate::errors::{bad_input, to_py, usage};
use crate::maps::{report_dict, run};
use crate::values::{choice, region_faces};

/// The path reports and errors give for a map passed as an array (as `metrics` does).
pub const PARAM_PATH: &str = "<array>";

/// The map `param` as the CLI's [`MapFile`]: disk, `(n, 2)` values `u + i v` as a flat
/// mesh's positions; sphere, `(n, 3)` unit vectors.
fn param_map(param: &Bound<'_, PyAny>, domain: Domain, n: usize) -> PyResult<MapFile> {
    let cols = match domain {
        Domain::Disk => 2,
        Domain::Sphere => 3,
    };
    let flat = points(param, "param", cols)?;
    if flat.len() != cols * n {
        return Err(bad_input(format!(
            "param has {} rows, the mesh {n} vertices: one map point per vertex is needed",
            flat.len() / cols
        )));
    }
    let positions: Vec<[f64; 3]> = match domain {
        Domain::Disk => flat.chunks_exact(2).map(|p| [p[0], p[1], 0.0]).collect(),
        Domain::Sphere => flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
    };
    if domain == Domain::Sphere {
        let off = positions.iter().position(|p| !on_unit_sphere(p));
        if let Some(k) = off {
            let p = positions[k];
            return Err(to_py(Failure::BadInput(
                format!(
                    "param row {k} ({}, {}, {}) is not on the unit sphere (radius tolerance \
                     {UNIT_SPHERE_TOL:e})",
                    p[0], p[1], p[2]
                ),
                Some("pass the S of sphere_map (unit vectors, one per vertex)".to_string()),
            )));
        }
    }
    Ok(MapFile {
        path: PathBuf::from(PARAM_PATH),
        positions,
        uv: None,
        corner_uv: None,
    })
}

/// The optimal Möbius transformation of a disk or sphere map, as `conformap mobius`:
/// `param` (n, 2) in the unit disk or (n, 3) on the unit sphere, `region` face indices
/// for the emphasizing objectives; returns `(param, report)` (the full documentation is in
/// `conformap.pyi`).
///
/// Example: `moved, report = conformap.mobius(V, F, uv, objective="emphasize",
/// region=range(100))`
#[pyfunction]
// the default is written out (not DEFAULT_MAX_AREA_SCALE) so that `help()` shows it; a
// test holds the two equal
#[pyo3(signature = (V, F, param, domain = "disk", objective = "uniform", region = None, *,
    max_area_scale = 10.0, strict = false, max_memory = None))]
#[allow(clippy::too_many_arguments, non_snake_case)] // `V`, `F` as the stubs spell them
pub fn mobius<'py>(
    py: Python<'py>,
    V: &Bound<'py, PyAny>,
    F: &Bound<'py, PyAny>,
    param: &Bound<'py, PyAny>,
    domain: &str,
    objective: &str,
    region: Option<&Bound<'py, PyAny>>,
    max_area_scale: f64,
    strict: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyAny>)> {
    let domain = choice::<Domain>("domain", domain)?;
    let objective_value = choice::<Objective>("objective", objective)?;
    match (objective_value, region.is_some()) {
        (Objective::Uniform, true) => {
            return Err(usage(
                "region is only used with objective=\"emphasize\" or \"emphasize-density\"",
            ))
        }
        (Objective::Emphasize | Objective::EmphasizeDensity, false) => {
            return Err(usage(format!(
                "objective={objective:?} needs region=[face, ...] (0-based face indices)"
            )))
        }
        _ => {}
    }
    if !(max_area_scale > 1.0 && max_area_scale.is_finite()) {
        return Err(usage(format!(
            "max_area_scale must be a finite number > 1, got {max_area_scale}"
        )));
    }
    let max_memory = crate::options::max_memory(max_memory)?;
    let input = mesh_input(V, F)?;
    let n = input.mesh.num_vertices();
    let param = param_map(param, domain, n)?;
    let region = region
        .map(|r| region_faces(r, input.mesh.num_faces()))
        .transpose()?;
    let mut job = MobiusJob::new(
        InputOptions::new(MEMORY_PATH),
        PARAM_PATH,
        OutputOptions::new(MEMORY_PATH).with_strict(strict),
        domain,
        objective_value,
    );
    job.max_area_scale = max_area_scale;
    job.param_map = Some(param);
    job.region_faces = region;
    let (solved, report) = run(py, &job, &input, max_memory, strict)?;
    let moved = &solved.flat.0[..n.min(solved.flat.0.len())];
    let out = match domain {
        Domain::Disk => {
            let uv: Vec<[f64; 2]> = moved.iter().map(|p| [p[0], p[1]]).collect();
            to_array(py, &uv)?
        }
        Domain::Sphere => to_array(py, moved)?,
    };
    Ok((out, report_dict(py, &report)?))
}

#[cfg(test)]
mod tests {
    /// The default written in `mobius`'s signature is the CLI's.
    #[test]
    fn max_area_scale_default_is_the_cli_s() {
        let written = 10.0_f64;
        let cli = conformap::jobs::mobius::DEFAULT_MAX_AREA_SCALE;
        assert!(
            (written - cli).abs() <= f64::EPSILON * cli,
            "{written} vs {cli}"
        );
    }
}
