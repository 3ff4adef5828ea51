//! Reading JSON values of the scene format by JSON path (the readers are
//! shared with field documents: `io::json_value`), refusing with
//! [`SceneError::Json`].

use glam::DVec3;
use serde_json::{Map, Value};

use super::SceneError;
use crate::io::json_value as shared;

/// Parses JSON text, naming `name` and the position on failure, or the
/// JSON path of an object with a key twice (`root.box`; `scene` for the
/// top-level object).
pub(super) fn parse_json(text: &str, name: &str) -> Result<Value, SceneError> {
    shared::parse_json(text, name, "scene", "")
}

/// The value as an object.
pub(super) fn object<'v>(value: &'v Value, at: &str) -> Result<&'v Map<String, Value>, SceneError> {
    shared::object(value, at)
}

/// The value as an object with only `allowed` keys.
pub(super) fn fields<'v>(
    value: &'v Value,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<&'v Map<String, Value>, SceneError> {
    shared::fields(value, at, allowed, expected)
}

/// Refuses the first key of `o` that is not in `allowed`.
pub(super) fn check_keys(
    o: &Map<String, Value>,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<(), SceneError> {
    shared::check_keys(o, at, allowed, expected)
}

/// The value under `key`, which must be there.
pub(super) fn req<'v>(
    o: &'v Map<String, Value>,
    at: &str,
    key: &str,
) -> Result<&'v Value, SceneError> {
    shared::req(o, at, key)
}

/// "expected …, found …" at `at`.
pub(super) fn bad(at: &str, expected: &str, found: &Value) -> SceneError {
    shared::bad(at, expected, found)
}

/// A finite number.
pub(super) fn number(value: &Value, at: &str) -> Result<f64, SceneError> {
    shared::number(value, at)
}

/// A finite number above zero.
pub(super) fn positive(value: &Value, at: &str) -> Result<f64, SceneError> {
    shared::positive(value, at)
}

/// An array of three finite numbers.
pub(super) fn vec3(value: &Value, at: &str) -> Result<DVec3, SceneError> {
    shared::vec3(value, at)
}

/// An optional three-vector under `key`, or `default`.
pub(super) fn vec3_or(
    o: &Map<String, Value>,
    at: &str,
    key: &str,
    default: DVec3,
) -> Result<DVec3, SceneError> {
    shared::vec3_or(o, at, key, default)
}
