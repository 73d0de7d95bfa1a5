//! The module's exceptions, from the CLI's [`Failure`]s: bad input and usage errors raise
//! `ConformapError` (a `ValueError`), numerical failures `NumericalError` (a
//! `RuntimeError`). The message is the CLI's `error:` line, followed by its `hint:` line
//! when it has one.

use conformap::failure::Failure;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    conformap,
    ConformapError,
    PyValueError,
    "Bad input (invalid mesh, wrong topology for the map, bad option): the CLI's message, \
     naming the element (vertex, face, boundary loop) and what to do."
);

pyo3::create_exception!(
    conformap,
    NumericalError,
    PyRuntimeError,
    "A numerical failure (a factorization or solve that failed, a map that does not \
     converge where that is required): the CLI's exit-3 message."
);

/// The exception for `failure`, with the CLI's message (and hint on a second line), and
/// the attributes `exit_code` (the CLI's: 1 bad input, 2 usage, 3 numerical) and `hint`
/// (`None` when there is none), as `conformap batch` puts them in its JSON lines.
pub fn to_py(failure: Failure) -> PyErr {
    let text = pythonize(&failure.to_string());
    let hint = failure.hint().map(python_hint);
    let message = match &hint {
        Some(hint) => format!("{text}\nhint: {hint}"),
        None => text,
    };
    let err = match failure {
        Failure::BadInput(..) | Failure::Usage(_) => ConformapError::new_err(message),
        Failure::Numerical(_) => NumericalError::new_err(message),
    };
    Python::attach(|py| {
        let value = err.value(py);
        // setting an attribute on a fresh exception instance cannot fail in practice; if it
        // did, the exception without it is still the right one
        let _ = value.setattr("exit_code", failure.exit_code());
        let _ = value.setattr("hint", hint);
    });
    err
}

/// A `ConformapError` for bad data in an argument (exit code 1, as the CLI's bad input),
/// prefixed `<arrays>: ` as every error about the arrays passed (unless the message names
/// its own place, `<surfaces[1]>: …`).
pub fn bad_input(message: impl Into<String>) -> PyErr {
    to_py(Failure::BadInput(at_arrays(message.into()), None))
}

/// [`bad_input`] with a hint.
pub fn bad_input_hint(message: impl Into<String>, hint: impl Into<String>) -> PyErr {
    to_py(Failure::BadInput(
        at_arrays(message.into()),
        Some(hint.into()),
    ))
}

fn at_arrays(message: String) -> String {
    if message.starts_with('<') {
        message
    } else {
        format!("{}: {message}", crate::arrays::MEMORY_PATH)
    }
}

/// The Python keyword for a CLI flag: `--max-iter` → `max_iter`, `--lambda` → `lambda_`.
fn keyword(flag: &str) -> String {
    match flag {
        "lambda" => "lambda_".to_string(),
        other => other.replace('-', "_"),
    }
}

/// A CLI message in the package's spellings: each `--flag` becomes its keyword
/// (`--tol` → `tol`, `--outer 5` → `outer=5`, `--lambda` → `lambda_`).
pub fn pythonize(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("--") {
        out.push_str(&rest[..at]);
        let after = &rest[at + 2..];
        let len = after
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(after.len());
        let flag = &after[..len];
        if flag.is_empty() || !flag.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str("--");
            rest = after;
            continue;
        }
        out.push_str(&keyword(flag));
        rest = &after[len..];
        // `--outer 5` → `outer=5`: a number after the flag is its value
        let value = rest.strip_prefix(' ').filter(|r| {
            r.starts_with(|c: char| c.is_ascii_digit())
                || (r.starts_with('-') && r[1..].starts_with(|c: char| c.is_ascii_digit()))
        });
        if let Some(v) = value {
            out.push('=');
            rest = v;
        }
    }
    out.push_str(rest);
    out
}

/// A CLI hint for arrays: the repairs of `--repair` are `conformap.repair(V, F)` (or
/// `read_mesh(path, repair=True)`), the memory limit is `max_memory=BYTES`, the file is the
/// arrays; other flags in their keyword spelling.
pub fn python_hint(hint: &str) -> String {
    if hint.contains("--repair") {
        return "conformap.repair(V, F) (or conformap.read_mesh(path, repair=True)) applies \
                the CLI's repairs (duplicate faces and unreferenced vertices dropped, \
                coincident vertices welded, faces re-oriented, the largest component kept)"
            .to_string();
    }
    if hint.contains("--max-memory SIZE") {
        return "free memory or use a larger machine, or decimate the mesh; if the estimate \
                is too cautious, max_memory=BYTES raises the limit"
            .to_string();
    }
    pythonize(
        &hint
            .replace("in the file", "in the arrays")
            .replace("the file", "the arrays"),
    )
}

/// A `ConformapError` for an option the CLI's parser would refuse (exit code 2, a usage
/// error): an unknown choice, options that exclude or need each other.
pub fn usage(message: impl Into<String>) -> PyErr {
    to_py(Failure::Usage(message.into()))
}

/// `err` with its message prefixed by `place` (`<surfaces[1]>: …`), the same exception
/// class, `exit_code` and `hint`.
pub fn in_place(py: Python<'_>, err: PyErr, place: &str) -> PyErr {
    let value = err.value(py);
    let prefixed = (|| -> PyResult<PyErr> {
        let text = value.str()?.to_string();
        let own = format!("{}: ", crate::arrays::MEMORY_PATH);
        let message = format!("{place}: {}", text.strip_prefix(&own).unwrap_or(&text));
        let new = value.get_type().call1((message,))?;
        for attr in ["exit_code", "hint"] {
            if let Ok(a) = value.getattr(attr) {
                new.setattr(attr, a)?;
            }
        }
        Ok(PyErr::from_value(new))
    })();
    prefixed.unwrap_or(err)
}
