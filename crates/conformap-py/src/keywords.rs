//! The keyword → job conversion of the map functions, shared with `batch_one`: `disk_map`,
//! `sphere_map`, `global_map`, `flatten` and `atlas` build their jobs with the functions
//! here, and `batch_one(path, command, out_dir, **options)` builds its
//! [`BatchTemplate`] with the same functions from `options` ([`template`]), so both accept
//! the same keywords with the same checks and defaults.
//!
//! The jobs read and write [`MEMORY_PATH`]; a batch replaces both paths by each input's.

use conformap::jobs::atlas::{AtlasJob, ConeChoice, GivenCones, Polish, DEFAULT_MAX_AREA_SPREAD};
use conformap::jobs::disk::{DiskJob, FactorOrder, Method};
use conformap::jobs::flatten::{FlattenJob, Interior};
use conformap::jobs::global::{Conjugate, FormObjective, GlobalJob};
use conformap::jobs::sphere::{SphereJob, SphereMobius};
use conformap::pipeline::{InputOptions, OutputOptions};
use conformap::{BatchCommand, BatchTemplate, Choice};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};

use crate::arrays::MEMORY_PATH;
use crate::errors::usage;
use crate::options::{nonneg, opt_count};
use crate::values::{boundary_spec, choice, pairs, region_faces, vertex_list};

/// The keywords of `disk_map` that shape its job (all but `V`, `F`, `max_memory`).
pub const DISK: &[&str] = &[
    "method",
    "outer",
    "max_iter",
    "tol",
    "keep_folds",
    "ordering",
    "strict",
];
/// The keywords of `sphere_map` that shape its job.
pub const SPHERE: &[&str] = &["mobius", "strict"];
/// The keywords of `global_map` that shape its job (`return_mesh` only shapes what
/// `global_map` returns, so a batch refuses it).
pub const GLOBAL: &[&str] = &[
    "objective",
    "form",
    "region",
    "zeros",
    "starts",
    "conjugate",
    "root",
    "topology_opt",
    "strict",
];
/// The keywords of `flatten` that shape its job.
pub const FLATTEN: &[&str] = &[
    "boundary", "values", "corners", "aspect", "interior", "strict",
];
/// The keywords of `atlas` that shape its job.
pub const ATLAS: &[&str] = &[
    "cones",
    "resolution",
    "margin",
    "max_area_spread",
    "pack",
    "scale",
    "seamless",
    "polish",
    "strict",
];

/// The input and output options of an in-memory job, `strict` as `--strict` sets it.
fn io(strict: bool) -> (InputOptions, OutputOptions) {
    (
        InputOptions::new(MEMORY_PATH),
        OutputOptions::new(MEMORY_PATH).with_strict(strict),
    )
}

/// The `disk` job of `disk_map`'s keywords.
///
/// # Errors
/// `ConformapError` (usage) for an unknown `method` or `ordering`, a negative `outer` or
/// `max_iter`.
#[allow(clippy::too_many_arguments)]
pub fn disk_job(
    method: &str,
    outer: Option<&Bound<'_, PyAny>>,
    max_iter: Option<&Bound<'_, PyAny>>,
    tol: Option<f64>,
    keep_folds: bool,
    ordering: &str,
    strict: bool,
) -> PyResult<DiskJob> {
    let (input, output) = io(strict);
    let mut job = DiskJob::new(input, output)
        .with_method(choice::<Method>("method", method)?)
        .with_max_iter(opt_count(max_iter, "max_iter")?)
        .with_tol(tol);
    job.ordering = choice::<FactorOrder>("ordering", ordering)?;
    job.outer = opt_count(outer, "outer")?;
    job.keep_folds = keep_folds;
    Ok(job)
}

/// The `sphere` job of `sphere_map`'s keywords.
///
/// # Errors
/// `ConformapError` (usage) for an unknown `mobius`.
pub fn sphere_job(mobius: &str, strict: bool) -> PyResult<SphereJob> {
    let (input, output) = io(strict);
    Ok(SphereJob::new(input, output).with_mobius(choice::<SphereMobius>("mobius", mobius)?))
}

/// The `global` job of `global_map`'s keywords but the `region` faces, which
/// [`global_region`] converts once the mesh is known (`region` is checked here against
/// the objective).
///
/// # Errors
/// `ConformapError` (usage) for an unknown `objective` or `conjugate`, a `region` without
/// an emphasizing objective or the other way round, `zeros` without `objective="zeros"` or
/// the other way round, negative counts; (bad input) for `zeros` or `region` that are not
/// indices.
#[allow(clippy::too_many_arguments)]
pub fn global_job(
    objective: &str,
    form: Option<&Bound<'_, PyAny>>,
    region: Option<&Bound<'_, PyAny>>,
    zeros: Option<&Bound<'_, PyAny>>,
    starts: Option<&Bound<'_, PyAny>>,
    conjugate: &str,
    root: Option<&Bound<'_, PyAny>>,
    topology_opt: bool,
    strict: bool,
) -> PyResult<GlobalJob> {
    let objective_value = choice::<FormObjective>("objective", objective)?;
    let regional = matches!(
        objective_value,
        FormObjective::Emphasize | FormObjective::DeEmphasize
    );
    match (regional, region.is_some()) {
        (true, false) => {
            return Err(usage(format!(
                "objective={objective:?} needs region=[face, ...] (0-based face indices)"
            )))
        }
        (false, true) => {
            return Err(usage(
                "region is only used with objective=\"emphasize\" or \"de-emphasize\"",
            ))
        }
        _ => {}
    }
    match (objective_value == FormObjective::Zeros, zeros.is_some()) {
        (true, false) => {
            return Err(usage(
                "objective=\"zeros\" needs zeros=[vertex, ...] (0-based vertices)",
            ))
        }
        (false, true) => return Err(usage("zeros is only used with objective=\"zeros\"")),
        _ => {}
    }
    let conjugate = choice::<Conjugate>("conjugate", conjugate)?;
    let zeros = zeros.map(|z| vertex_list(z, "zeros")).transpose()?;
    let (input, output) = io(strict);
    let mut job = GlobalJob::new(input, output)
        .with_objective(objective_value)
        .with_topology_opt(topology_opt);
    job.form = opt_count(form, "form")?;
    job.conjugate = conjugate;
    job.zeros = zeros;
    job.starts = opt_count(starts, "starts")?;
    job.root = opt_count(root, "root")?;
    Ok(job)
}

/// `job` with the faces of `region`, each checked against `faces`, the mesh's face count
/// (`usize::MAX` in a batch: each input's mesh checks them when it is mapped).
///
/// # Errors
/// `ConformapError` (bad input) for a `region` that is not a sequence of face indices
/// below `faces`.
pub fn global_region(
    mut job: GlobalJob,
    region: Option<&Bound<'_, PyAny>>,
    faces: usize,
) -> PyResult<GlobalJob> {
    job.region_faces = region.map(|r| region_faces(r, faces)).transpose()?;
    Ok(job)
}

/// The `flatten` job of `flatten`'s keywords.
///
/// # Errors
/// `ConformapError` (usage) for an unknown `boundary` or `interior`, `values` missing for
/// (or given to) a boundary target, `values` that are not `(vertex, value)` pairs.
pub fn flatten_job(
    boundary: &str,
    values: Option<&Bound<'_, PyAny>>,
    corners: Option<[u32; 4]>,
    aspect: Option<f64>,
    interior: &str,
    strict: bool,
) -> PyResult<FlattenJob> {
    let values = values.map(pairs).transpose()?;
    let (spec, text) = boundary_spec(boundary, values.as_deref())?;
    let (input, output) = io(strict);
    let mut job = FlattenJob::new(input, output)
        .with_boundary(spec)
        .with_interior(choice::<Interior>("interior", interior)?);
    job.corners = corners;
    job.aspect = aspect;
    job.boundary_text = text;
    Ok(job)
}

/// The polish mode of keyword `polish` (see [`atlas_job`]).
fn polish_mode(polish: Option<&Bound<'_, PyAny>>) -> PyResult<Polish> {
    match polish {
        None => Ok(Polish::Auto),
        Some(p) if p.is_none() => Ok(Polish::Auto),
        Some(p) if p.is_instance_of::<PyBool>() => Ok(if p.extract::<bool>()? {
            Polish::Always
        } else {
            Polish::Never
        }),
        Some(p) => match p.extract::<String>().ok().as_deref() {
            Some("auto") => Ok(Polish::Auto),
            Some("always") => Ok(Polish::Always),
            Some("never") => Ok(Polish::Never),
            _ => {
                let text = p.repr().map(|r| r.to_string()).unwrap_or_default();
                Err(usage(format!(
                    "polish must be \"auto\", \"always\", \"never\", True or False, got {text}"
                )))
            }
        },
    }
}

/// The `atlas` job of `atlas`'s keywords: `cones` an integer (placed), `"auto"` (as many
/// as reach `max_area_spread`) or `(vertex, angle in degrees)` pairs (given, checked
/// against the mesh as `--cones FILE`'s lines); `pack` `"square"` or `"none"`; `scale`
/// `"uniform"` or `"per-chart"`; `seamless` as `--seamless`; `polish` `None` or `"auto"`
/// (the default), `True` or `"always"`, `False` or `"never"`, as `--polish=WHEN`.
///
/// # Errors
/// `ConformapError` (usage) for a negative `cones` or `resolution`, another string than
/// `"auto"`, pairs that are not `(integer ≥ 0, float)`, an unknown `pack`, `scale` or
/// `polish`.
#[allow(clippy::too_many_arguments)] // one per keyword
pub fn atlas_job(
    cones: Option<&Bound<'_, PyAny>>,
    resolution: i64,
    margin: f64,
    max_area_spread: f64,
    pack: &str,
    scale: &str,
    seamless: bool,
    polish: Option<&Bound<'_, PyAny>>,
    strict: bool,
) -> PyResult<AtlasJob> {
    let (input, output) = io(strict);
    let mut job = AtlasJob::new(input, output);
    match cones {
        None => {}
        Some(c) if c.is_instance_of::<PyString>() => {
            let text: String = c.extract()?;
            if text != "auto" {
                return Err(usage(format!(
                    "cones must be an integer ≥ 0, \"auto\" or (vertex, angle) pairs, got {text:?}"
                )));
            }
            job.cone_choice = ConeChoice::Auto;
        }
        Some(c) if c.is_instance_of::<pyo3::types::PyInt>() => {
            job.cones = opt_count(cones, "cones")?
        }
        Some(c) => job.cone_choice = ConeChoice::List(cone_pairs(c)?),
    }
    job.resolution = nonneg(resolution, "resolution")?;
    job.margin = margin;
    job.max_area_spread = max_area_spread;
    job.pack_none = match pack {
        "square" => false,
        "none" => true,
        other => {
            return Err(usage(format!(
                "pack must be \"square\" or \"none\", got {other:?}"
            )))
        }
    };
    job.seamless = seamless;
    job.polish = polish_mode(polish)?;
    job.per_chart_scale = match scale {
        "uniform" => false,
        "per-chart" => true,
        other => {
            return Err(usage(format!(
                "scale must be \"uniform\" or \"per-chart\", got {other:?}"
            )))
        }
    };
    Ok(job)
}

/// `(vertex, angle in degrees)` pairs of any sequence (a list of tuples, an (k, 2) array).
fn cone_pairs(obj: &Bound<'_, PyAny>) -> PyResult<GivenCones> {
    let bad = || {
        usage(
            "cones must be an integer ≥ 0, \"auto\" or a sequence of (vertex, angle in degrees) \
             pairs, e.g. [(12, 270.0), (40, 270.0)]",
        )
    };
    let mut pairs = Vec::new();
    for item in obj.try_iter().map_err(|_| bad())? {
        let item = item?;
        let pair: Vec<f64> = item.extract().map_err(|_| bad())?;
        let [v, a] = pair[..] else { return Err(bad()) };
        if !(v >= 0.0 && v.fract() == 0.0 && v < u32::MAX as f64) {
            return Err(usage(format!(
                "cones[{}]: vertex {v} is not a vertex index (a whole number ≥ 0)",
                pairs.len()
            )));
        }
        pairs.push((v as u64, a));
    }
    Ok(GivenCones::from_pairs(&pairs))
}

/// The keywords a batch of `command` accepts (its map function's, but `max_memory`,
/// which is batch's own).
pub fn accepted(command: BatchCommand) -> &'static [&'static str] {
    match command {
        BatchCommand::Disk => DISK,
        BatchCommand::Sphere => SPHERE,
        BatchCommand::Global => GLOBAL,
        BatchCommand::Flatten => FLATTEN,
        BatchCommand::Atlas => ATLAS,
    }
}

/// The Python function of `command`.
fn function(command: BatchCommand) -> &'static str {
    match command {
        BatchCommand::Disk => "disk_map",
        BatchCommand::Sphere => "sphere_map",
        BatchCommand::Global => "global_map",
        BatchCommand::Flatten => "flatten",
        BatchCommand::Atlas => "atlas",
    }
}

/// The keyword options of one command, checked against the keywords it accepts.
struct Options<'a, 'py> {
    dict: Option<&'a Bound<'py, PyDict>>,
}

impl<'py> Options<'_, 'py> {
    /// The value of keyword `name`; `None` when it is not given or is `None` (the default).
    fn get(&self, name: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        match self.dict {
            Some(d) => Ok(d.get_item(name)?.filter(|v| !v.is_none())),
            None => Ok(None),
        }
    }

    /// The value of keyword `name` as a `T`, or `default`.
    fn value<T: for<'a> FromPyObject<'a, 'py>>(
        &self,
        name: &str,
        what: &str,
        default: T,
    ) -> PyResult<T> {
        match self.get(name)? {
            None => Ok(default),
            Some(v) => v.extract::<T>().map_err(|_| {
                let text = v.repr().map(|r| r.to_string()).unwrap_or_default();
                usage(format!("{name} must be {what}, got {text}"))
            }),
        }
    }

    /// The text of keyword `name`, or `default`.
    fn text(&self, name: &str, default: &str) -> PyResult<String> {
        match self.get(name)? {
            None => Ok(default.to_string()),
            Some(v) if v.is_instance_of::<PyString>() => Ok(v.extract::<String>()?),
            Some(v) => {
                let text = v.repr().map(|r| r.to_string()).unwrap_or_default();
                Err(usage(format!("{name} must be a str, got {text}")))
            }
        }
    }

    /// The flag `name` (`False` by default).
    fn flag(&self, name: &str) -> PyResult<bool> {
        self.value(name, "True or False", false)
    }
}

/// The batch template of `command` built from keyword `options` by the map function's own
/// conversion, with the map function's defaults for the keywords not given.
///
/// # Errors
/// `ConformapError` (usage) naming an unknown keyword and listing the accepted ones; the
/// map function's errors for bad values.
pub fn template(
    command: BatchCommand,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<BatchTemplate> {
    let names = accepted(command);
    if let Some(dict) = options {
        for key in dict.keys() {
            let key = key.str()?.to_string();
            if !names.contains(&key.as_str()) {
                let hint = format!(
                    "{} accepts {} (as {}() takes them); batch_one's own: skip_existing, ext, \
                     png, max_memory",
                    command.name(),
                    names.join(", "),
                    function(command)
                );
                let err = usage(format!(
                    "batch_one: {key} is not a keyword of {}\nhint: {hint}",
                    command.name()
                ));
                err.value(dict.py()).setattr("hint", hint)?;
                return Err(err);
            }
        }
    }
    let kw = Options { dict: options };
    let strict = kw.flag("strict")?;
    Ok(match command {
        BatchCommand::Disk => BatchTemplate::Disk(disk_job(
            &kw.text("method", "ccem-qn")?,
            kw.get("outer")?.as_ref(),
            kw.get("max_iter")?.as_ref(),
            kw.value("tol", "a float", None)?,
            kw.flag("keep_folds")?,
            &kw.text("ordering", "auto")?,
            strict,
        )?),
        BatchCommand::Sphere => {
            BatchTemplate::Sphere(sphere_job(&kw.text("mobius", "none")?, strict)?)
        }
        BatchCommand::Global => {
            let region = kw.get("region")?;
            let job = global_job(
                &kw.text("objective", "uniform")?,
                kw.get("form")?.as_ref(),
                region.as_ref(),
                kw.get("zeros")?.as_ref(),
                kw.get("starts")?.as_ref(),
                &kw.text("conjugate", "nearest")?,
                kw.get("root")?.as_ref(),
                kw.flag("topology_opt")?,
                strict,
            )?;
            BatchTemplate::Global(global_region(job, region.as_ref(), usize::MAX)?)
        }
        BatchCommand::Flatten => BatchTemplate::Flatten(flatten_job(
            &kw.text("boundary", "free")?,
            kw.get("values")?.as_ref(),
            kw.value("corners", "four vertex indices", None)?,
            kw.value("aspect", "a float", None)?,
            &kw.text("interior", "harmonic")?,
            strict,
        )?),
        BatchCommand::Atlas => BatchTemplate::Atlas(atlas_job(
            kw.get("cones")?.as_ref(),
            kw.value("resolution", "an integer ≥ 0", 1024)?,
            kw.value("margin", "a float", 2.0)?,
            kw.value("max_area_spread", "a float", DEFAULT_MAX_AREA_SPREAD)?,
            &kw.text("pack", "square")?,
            &kw.text("scale", "uniform")?,
            kw.flag("seamless")?,
            kw.get("polish")?.as_ref(),
            strict,
        )?),
    })
}
