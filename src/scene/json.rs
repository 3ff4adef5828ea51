//! Reading JSON values of the scene format: each reader names the JSON
//! path of the value it refuses, e.g. `root.difference[1].sphere.radius`.

use glam::DVec3;
use serde_json::{Map, Value};

use super::SceneError;
use super::limits::MAX_JSON_DEPTH;

/// Parses JSON text, naming `name` and the position on failure.
pub(super) fn parse_json(text: &str, name: &str) -> Result<Value, SceneError> {
    // serde_json refuses text nested deeper than its recursion limit.
    serde_json::from_str(text).map_err(|e| {
        let message = if e.to_string().starts_with("recursion limit exceeded") {
            format!("nested deeper than {MAX_JSON_DEPTH} levels (the limit)")
        } else {
            e.to_string()
        };
        SceneError::Json {
            file: name.to_string(),
            line: e.line(),
            column: e.column(),
            message,
        }
    })
}

/// The value as an object.
pub(super) fn object<'v>(value: &'v Value, at: &str) -> Result<&'v Map<String, Value>, SceneError> {
    value.as_object().ok_or_else(|| bad(at, "an object", value))
}

/// The value as an object with only `allowed` keys (`expected` lists them
/// for the message).
pub(super) fn fields<'v>(
    value: &'v Value,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<&'v Map<String, Value>, SceneError> {
    let o = object(value, at)?;
    check_keys(o, at, allowed, expected)?;
    Ok(o)
}

/// Refuses the first key of `o` that is not in `allowed`.
pub(super) fn check_keys(
    o: &Map<String, Value>,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<(), SceneError> {
    match o.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(key) => Err(SceneError::UnknownKey {
            at: at.to_string(),
            key: key.clone(),
            expected,
        }),
        None => Ok(()),
    }
}

/// The value under `key`, which must be there.
pub(super) fn req<'v>(
    o: &'v Map<String, Value>,
    at: &str,
    key: &str,
) -> Result<&'v Value, SceneError> {
    o.get(key).ok_or_else(|| SceneError::Value {
        at: format!("{at}.{key}"),
        message: "missing".into(),
    })
}

/// "expected …, found …", with long values cut short.
pub(super) fn bad(at: &str, expected: &str, found: &Value) -> SceneError {
    let mut shown = found.to_string();
    if shown.len() > 60 {
        // At a character boundary: a value may hold multi-byte characters
        // (found by fuzzing, fixtures/fuzz/scene_load/).
        let cut = (0..=57)
            .rev()
            .find(|&i| shown.is_char_boundary(i))
            .unwrap_or(0);
        shown.truncate(cut);
        shown.push_str("...");
    }
    SceneError::Value {
        at: at.to_string(),
        message: format!("expected {expected}, found {shown}"),
    }
}

/// A finite number.
pub(super) fn number(value: &Value, at: &str) -> Result<f64, SceneError> {
    match value.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(bad(at, "a finite number", value)),
    }
}

/// A finite number above zero.
pub(super) fn positive(value: &Value, at: &str) -> Result<f64, SceneError> {
    match number(value, at) {
        Ok(x) if x > 0.0 => Ok(x),
        _ => Err(bad(at, "a positive number", value)),
    }
}

/// An array of three finite numbers.
pub(super) fn vec3(value: &Value, at: &str) -> Result<DVec3, SceneError> {
    match value.as_array() {
        Some(items) if items.len() == 3 => {
            let mut v = DVec3::ZERO;
            for (k, item) in items.iter().enumerate() {
                v[k] = number(item, &format!("{at}[{k}]"))?;
            }
            Ok(v)
        }
        _ => Err(bad(at, "an array of three numbers", value)),
    }
}

/// An optional three-vector under `key`, or `default`.
pub(super) fn vec3_or(
    o: &Map<String, Value>,
    at: &str,
    key: &str,
    default: DVec3,
) -> Result<DVec3, SceneError> {
    o.get(key)
        .map(|v| vec3(v, &format!("{at}.{key}")))
        .transpose()
        .map(|v| v.unwrap_or(default))
}
