//! The module's exceptions, from the CLI's [`Failure`]s: bad input and usage errors raise
//! `ConformapError` (a `ValueError`), numerical failures `NumericalError` (a
//! `RuntimeError`). The message is the CLI's `error:` line, followed by its `hint:` line
//! when it has one.

use conformap_cli::failure::Failure;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::PyErr;

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

/// The exception for `failure`, with the CLI's message (and hint on a second line).
pub fn to_py(failure: Failure) -> PyErr {
    let message = match failure.hint() {
        Some(hint) => format!("{failure}\nhint: {hint}"),
        None => failure.to_string(),
    };
    match failure {
        Failure::BadInput(..) | Failure::Usage(_) => ConformapError::new_err(message),
        Failure::Numerical(_) => NumericalError::new_err(message),
    }
}

/// A `ConformapError` with `message`.
pub fn bad_input(message: impl Into<String>) -> PyErr {
    ConformapError::new_err(message.into())
}
