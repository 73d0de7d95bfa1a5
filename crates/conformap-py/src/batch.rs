//! `batch_one`: one input of `conformap batch`, run by the same Rust function
//! ([`conformap::batch::one::run_one`]) with the command's options parsed by the CLI's own parser
//! ([`conformap_cli::cli::batch_job`]), so a cohort distributed over a cluster writes the
//! outputs and JSON lines `conformap batch` would.

use std::path::PathBuf;

use conformap::{BatchCommand, Choice};
use conformap_cli::commands::batch::BatchArgs;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::arrays::to_py_json;
use crate::errors::{to_py, usage};

/// The command-line options of keyword `options` (`max_iter=50` → `--max-iter 50`,
/// `strict=True` → `--strict`, `False`/`None` left out, lists joined by commas), in the
/// order given.
fn option_args(options: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<String>> {
    let mut argv = Vec::new();
    let Some(options) = options else {
        return Ok(argv);
    };
    for (key, value) in options.iter() {
        let flag = format!("--{}", key.str()?.extract::<String>()?.replace('_', "-"));
        if value.is_none() {
            continue;
        }
        if let Ok(b) = value.cast::<pyo3::types::PyBool>() {
            if b.is_true() {
                argv.push(flag);
            }
            continue;
        }
        let text = if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
            let parts: PyResult<Vec<String>> = value
                .try_iter()?
                .map(|x| x?.str()?.extract::<String>())
                .collect();
            parts?.join(",")
        } else {
            value.str()?.extract::<String>()?
        };
        argv.extend([flag, text]);
    }
    Ok(argv)
}

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
    max_memory: Option<u64>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let command = BatchCommand::parse_name(command).map_err(|e| {
        usage(format!(
            "command must be one of {}, got {command:?}",
            e.names.join(", ")
        ))
    })?;
    let args = BatchArgs {
        command,
        out_dir,
        jobs: 1,
        skip_existing,
        report: None,
        ext,
        png,
        max_memory,
        inputs: vec![path.clone()],
        options: option_args(options)?,
    };
    let line = py
        .detach(|| {
            let job = conformap_cli::cli::batch_job(&args)?;
            conformap::batch::one::run_one(&job, &path)
        })
        .map_err(to_py)?;
    to_py_json(py, &line)
}
