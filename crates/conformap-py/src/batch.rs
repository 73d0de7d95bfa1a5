//! `batch_one`: one input of `conformap batch`, run by the same Rust function
//! ([`conformap::batch::one::run_one`]), its job built from the keyword options by the map
//! functions' own conversion ([`crate::keywords::template`]: `batch_one(..., "disk",
//! **kw)` accepts what `disk_map(V, F, **kw)` accepts), so a cohort distributed over a
//! cluster writes the outputs and JSON lines `conformap batch` would.

use std::path::PathBuf;

use conformap::{BatchCommand, BatchJob, Choice};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::to_py_json;
use crate::errors::{to_py, usage};
use crate::keywords;
use crate::options;

/// Maps one mesh as `conformap batch --command COMMAND --out-dir OUT_DIR MESH -- OPTIONS`
/// does and returns its JSON line as a dict. See `conformap.pyi`.
#[pyfunction]
#[pyo3(signature = (path, command, out_dir, *, skip_existing = false, ext = None,
    png = false, max_memory = None, **options))]
#[allow(clippy::too_many_arguments)]
pub fn batch_one<'py>(
    py: Python<'py>,
    path: PathBuf,
    command: &str,
    out_dir: PathBuf,
    skip_existing: bool,
    ext: Option<String>,
    png: bool,
    max_memory: Option<&Bound<'py, PyAny>>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let command = BatchCommand::parse_name(command).map_err(|e| {
        usage(format!(
            "command must be one of {}, got {command:?}",
            e.names.join(", ")
        ))
    })?;
    let template = keywords::template(command, options)?;
    let mut job = BatchJob::new(template, out_dir, vec![path.clone()]);
    job.skip_existing = skip_existing;
    job.ext = ext;
    job.png = png;
    job.max_memory = options::max_memory(max_memory)?;
    let line = py
        .detach(|| conformap::batch::one::run_one(&job, &path))
        .map_err(to_py)?;
    to_py_json(py, &line)
}
