//! Keyword arguments checked as the CLI's parser checks its flags: counts that must not be
//! negative (`max_iter`, `frames`, `form`, …) and `max_memory`, which must be at least one
//! byte. A bad value raises `ConformapError` (exit code 2, a usage error) naming the
//! keyword, never `OverflowError`.

use pyo3::prelude::*;
use pyo3::types::PyInt;

use crate::errors::usage;

/// `obj` as a count (an integer ≥ 0); `name` is the keyword.
///
/// # Errors
/// `ConformapError` (usage) for a negative or too large integer or a non-integer.
pub fn count(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let text = obj.repr().map(|r| r.to_string()).unwrap_or_default();
    if !obj.is_instance_of::<PyInt>() {
        return Err(usage(format!("{name} must be an integer ≥ 0, got {text}")));
    }
    match obj.extract::<i64>() {
        Ok(v) if v < 0 => Err(usage(format!("{name} must be ≥ 0, got {v}"))),
        Ok(v) => usize::try_from(v).map_err(|_| usage(format!("{name} = {v} is too large"))),
        Err(_) if text.starts_with('-') => Err(usage(format!("{name} must be ≥ 0, got {text}"))),
        Err(_) => Err(usage(format!("{name} = {text} is too large"))),
    }
}

/// [`count`] of an optional keyword.
///
/// # Errors
/// As [`count`].
pub fn opt_count(obj: Option<&Bound<'_, PyAny>>, name: &str) -> PyResult<Option<usize>> {
    obj.map(|o| count(o, name)).transpose()
}

/// `max_memory` in bytes: at least 1 (the CLI refuses `--max-memory 0` when parsing).
///
/// # Errors
/// `ConformapError` (usage) for 0, a negative value or a non-integer.
pub fn max_memory(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    match opt_count(obj, "max_memory")? {
        Some(0) => Err(usage(
            "max_memory must be at least 1 byte, got 0 (None: the memory available)",
        )),
        other => Ok(other.map(|b| b as u64)),
    }
}

/// `value` as a count (≥ 0), for keywords with a literal default; `name` is the keyword.
///
/// # Errors
/// `ConformapError` (usage) for a negative value.
pub fn nonneg(value: i64, name: &str) -> PyResult<usize> {
    usize::try_from(value).map_err(|_| usage(format!("{name} must be ≥ 0, got {value}")))
}
