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
    let message = match failure.hint() {
        Some(hint) => format!("{failure}\nhint: {hint}"),
        None => failure.to_string(),
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
        let _ = value.setattr("hint", failure.hint());
    });
    err
}

/// A `ConformapError` for bad data in an argument (exit code 1, as the CLI's bad input).
pub fn bad_input(message: impl Into<String>) -> PyErr {
    to_py(Failure::BadInput(message.into(), None))
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
        let message = format!("{place}: {}", value.str()?);
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
