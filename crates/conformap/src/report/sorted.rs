//! [`Sorted`]: a typed value written with its object keys in sorted order at every depth,
//! the order the report has always had for the parts built from library reports (the
//! solver's own part, the command's extra metrics, the `global` and `topology_opt`
//! sections, `info` and `metrics` output): serde_json writes a JSON object held as a value
//! with its keys sorted.

use serde::ser::Error as _;
use serde::{Serialize, Serializer};
use serde_json::{Map, Value};

/// `T`, written with its object keys sorted at every depth.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Sorted<T>(pub T);

impl<T: Serialize> Serialize for Sorted<T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serde_json::to_value(&self.0)
            .map_err(S::Error::custom)?
            .serialize(serializer)
    }
}

/// `value` as a JSON object with sorted keys (empty when it is not an object: a unit or
/// `None` has no fields to write).
pub(crate) fn sorted_object(
    value: &impl Serialize,
) -> Result<Map<String, Value>, serde_json::Error> {
    Ok(match serde_json::to_value(value)? {
        Value::Object(m) => m,
        _ => Map::new(),
    })
}
