//! `morph`: the CLI's `morph` command on arrays, through the CLI's own pieces
//! ([`MorphJob::check_counts`], [`conformap::jobs::morph::solve`] over
//! conformap-morph's public API, [`command_report`]), so errors and the report are the
//! CLI's. Surfaces are named `<surfaces[k]>` and landmark lists `<landmarks[k]>` where the
//! CLI names files.

use std::path::PathBuf;
use std::time::Instant;

use conformap::failure::Failure;
use conformap::jobs::morph::{command_report, morph_peak_bytes, solve, MorphJob};
use conformap::report::{MemoryReport, StageTimings};
use conformap_morph::{Landmarks, Surface};
use numpy::{PyArray2, PyArray3, PyArrayMethods};
use pyo3::prelude::*;

use crate::arrays::{faces_array, mesh_input_at, to_py_json};
use crate::errors::{bad_input, to_py, usage};

/// The name of surface `k` in reports and errors.
fn surface_name(k: usize) -> PathBuf {
    PathBuf::from(format!("<surfaces[{k}]>"))
}

/// The name of landmark list `k` in reports and errors.
fn landmarks_name(k: usize) -> PathBuf {
    PathBuf::from(format!("<landmarks[{k}]>"))
}

/// Landmarks from a sequence of vertex indices, named by position (`"0"`, `"1"`, …), or
/// from a mapping `name -> vertex`: in the order of `order` (the first surface's names)
/// when it holds the same names, else in the mapping's own order.
fn landmarks(obj: &Bound<'_, PyAny>, k: usize, order: Option<&[String]>) -> PyResult<Landmarks> {
    let place = landmarks_name(k);
    let pairs: Vec<(i64, String)> = if let Ok(map) = obj.cast::<pyo3::types::PyDict>() {
        map.iter()
            .map(|(name, v)| Ok((v.extract::<i64>()?, name.str()?.to_string())))
            .collect::<PyResult<_>>()
            .map_err(|_| {
                bad_input(format!(
                    "{}: a landmark dict maps names to integer vertex indices",
                    place.display()
                ))
            })?
    } else {
        let vertices: Vec<i64> = obj.extract().map_err(|_| {
            bad_input(format!(
                "{}: landmarks must be a sequence of integer vertex indices (0-based) or a \
                 dict name -> vertex",
                place.display()
            ))
        })?;
        vertices
            .into_iter()
            .enumerate()
            .map(|(j, v)| (v, j.to_string()))
            .collect()
    };
    let pairs = by_name(pairs, order);
    let pairs = pairs
        .into_iter()
        .enumerate()
        .map(|(j, (v, name))| {
            u32::try_from(v).map(|v| (v, name)).map_err(|_| {
                bad_input(format!(
                    "{}[{j}]: {v} is not a vertex index (0-based)",
                    place.display()
                ))
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    Landmarks::new(pairs).map_err(|e| to_py(Failure::input(e).in_file(&place)))
}

/// `(frames, F, report)`: frames `(N, n, 3)` float64, `F` `(m, 3)` int64.
pub type MorphArrays<'py> = (
    Bound<'py, PyArray3<f64>>,
    Bound<'py, PyArray2<i64>>,
    Bound<'py, PyAny>,
);

/// A morph through two or more disk-like surfaces with landmarks, as `conformap morph`:
/// `surfaces` `[(V1, F1), (V2, F2), …]`, `landmarks` one list of vertex indices (or dict
/// name → vertex) per surface; returns `(frames (N, n, 3), F, report)` (the full
/// documentation is in `conformap.pyi`).
///
/// Example: `P, F, report = conformap.morph([(V1, F1), (V2, F2)], [L1, L2], frames=24)`
#[pyfunction]
#[pyo3(signature = (surfaces, landmarks, frames, *, lambda_ = None, hard = false))]
pub fn morph<'py>(
    py: Python<'py>,
    surfaces: &Bound<'py, PyAny>,
    landmarks: &Bound<'py, PyAny>,
    frames: &Bound<'py, PyAny>,
    lambda_: Option<f64>,
    hard: bool,
) -> PyResult<MorphArrays<'py>> {
    let frames = crate::options::count(frames, "frames")?;
    if hard && lambda_.is_some() {
        return Err(usage("lambda_ and hard=True exclude each other"));
    }
    let surfaces: Vec<Bound<'py, PyAny>> = surfaces
        .try_iter()?
        .collect::<PyResult<_>>()
        .map_err(|_| bad_input("surfaces must be a sequence of (V, F) pairs"))?;
    let lists: Vec<Bound<'py, PyAny>> = landmarks
        .try_iter()?
        .collect::<PyResult<_>>()
        .map_err(|_| bad_input("landmarks must be a sequence of landmark lists"))?;
    let mut args = MorphJob::new(
        (0..surfaces.len()).map(surface_name).collect(),
        (0..lists.len()).map(landmarks_name).collect(),
        frames,
        PathBuf::new(),
    );
    args.lambda = lambda_;
    args.hard = hard;
    args.check_counts().map_err(to_py)?;
    let mut keys = Vec::with_capacity(surfaces.len());
    let order = dict_names(&lists[0]);
    for (k, (pair, lms)) in surfaces.iter().zip(&lists).enumerate() {
        let (v, f): (Bound<'py, PyAny>, Bound<'py, PyAny>) = pair
            .extract()
            .map_err(|_| bad_input(format!("<surfaces[{k}]>: must be a (V, F) pair")))?;
        let place = surface_name(k).display().to_string();
        let input = mesh_input_at(&v, &f, &place)?;
        if k == 0 {
            check_frames_memory(frames, input.mesh.num_vertices())?;
        }
        let lms = self::landmarks(lms, k, order.as_deref())?;
        keys.push(Surface::new(input.mesh, lms));
    }
    let memory = check_morph_memory(&keys, &args, frames)?;
    let (solution, mut report, positions) = py
        .detach(|| {
            let t = Instant::now();
            let solution = solve(&args, &keys)?;
            let m = &solution.morph;
            let positions: Vec<f64> = solution
                .times
                .iter()
                .flat_map(|&t| m.frame(t))
                .flatten()
                .collect();
            let timings = StageTimings {
                total: t.elapsed().as_secs_f64() * 1e3,
                ..StageTimings::default()
            };
            let report = command_report(&args, &keys, &solution, timings);
            Ok::<_, Failure>((solution, report, positions))
        })
        .map_err(to_py)?;
    report.memory = Some(MemoryReport {
        peak_rss_bytes: conformap_operators::peak_rss_bytes(),
        ..memory
    });
    let m = &solution.morph;
    let n = positions.len() / (3 * frames.max(1));
    let frames_array = numpy::PyArray1::from_vec(py, positions).reshape([frames, n, 3])?;
    let value = serde_json::to_value(&report).map_err(|e| bad_input(e.to_string()))?;
    Ok((
        frames_array,
        faces_array(py, m.faces())?,
        to_py_json(py, &value)?,
    ))
}

/// The names of a landmark dict, in its order (`None` for a sequence).
fn dict_names(obj: &Bound<'_, PyAny>) -> Option<Vec<String>> {
    let map = obj.cast::<pyo3::types::PyDict>().ok()?;
    map.keys()
        .iter()
        .map(|k| k.str().map(|s| s.to_string()))
        .collect::<PyResult<_>>()
        .ok()
}

/// `pairs` (vertex, name) reordered to the names of `order`, when they are the same set;
/// else as given (the morph then names the first mismatch).
fn by_name(pairs: Vec<(i64, String)>, order: Option<&[String]>) -> Vec<(i64, String)> {
    let Some(order) = order else { return pairs };
    let mut sorted: Vec<(i64, String)> = Vec::with_capacity(pairs.len());
    for name in order {
        match pairs.iter().find(|(_, n)| n == name) {
            Some(p) => sorted.push(p.clone()),
            None => return pairs,
        }
    }
    if sorted.len() == pairs.len() {
        sorted
    } else {
        pairs
    }
}

/// Bytes per frame vertex kept at once: the frame's positions in the result array (3 f64)
/// and the frame being evaluated.
const FRAME_BYTES_PER_VERTEX: u64 = 2 * 3 * 8;

/// Refuses, before the morph is solved, a morph of `keys` whose estimate (the CLI's
/// [`morph_peak_bytes`], plus the frames returned) is above the memory available, as
/// `conformap morph` does; returns the report's `memory` object (without the peak).
fn check_morph_memory(keys: &[Surface], args: &MorphJob, frames: usize) -> PyResult<MemoryReport> {
    let n = keys.first().map_or(0, |s| s.mesh.num_vertices()) as u64;
    let estimate = morph_peak_bytes(keys, &args.options()).saturating_add(
        (frames as u64)
            .saturating_mul(n)
            .saturating_mul(FRAME_BYTES_PER_VERTEX),
    );
    let limit = conformap_operators::available_memory();
    if let Some((bytes, from)) = limit.filter(|&(bytes, _)| estimate > bytes) {
        let human = conformap::pipeline::memory::human_bytes;
        return Err(to_py(Failure::BadInput(
            format!(
                "the morph through these {} surfaces needs an estimated {} at peak, more \
                 than the {} available ({from}); nothing was computed",
                keys.len(),
                human(estimate),
                human(bytes)
            ),
            Some("free memory or use a larger machine, or decimate the meshes".to_string()),
        )));
    }
    Ok(MemoryReport {
        estimated_peak_bytes: estimate,
        limit_bytes: limit.map(|l| l.0),
        limit_source: limit.map(|l| l.1),
        peak_rss_bytes: None,
    })
}

/// Refuses, before any work, `frames` frames of `n` vertices that would not fit in the
/// memory available (the result alone is `frames × n × 24` bytes): a failed allocation
/// would abort the interpreter.
fn check_frames_memory(frames: usize, n: usize) -> PyResult<()> {
    let need = (frames as u64)
        .saturating_mul(n as u64)
        .saturating_mul(FRAME_BYTES_PER_VERTEX);
    let Some((limit, from)) = conformap_operators::available_memory() else {
        return Ok(());
    };
    if need <= limit {
        return Ok(());
    }
    let human = conformap::pipeline::memory::human_bytes;
    Err(to_py(Failure::BadInput(
        format!(
            "frames={frames} of {n} vertices need an estimated {} at peak, more than the {} \
             available ({from}); nothing was computed",
            human(need),
            human(limit)
        ),
        Some(format!(
            "ask for fewer frames (at most about {}), or evaluate the morph in parts",
            limit / (n.max(1) as u64 * FRAME_BYTES_PER_VERTEX)
        )),
    )))
}
