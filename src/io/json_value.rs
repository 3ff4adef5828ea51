//! Reading JSON documents by JSON path, shared by the scene format and
//! field documents: each reader names the path of the value it refuses
//! (`root.difference[1].sphere.radius`), and is generic over the caller's
//! error type, which only has to take a [`JsonError`].

use std::path::PathBuf;

use glam::DVec3;
use serde_json::{Map, Value};
use thiserror::Error;

/// How deep JSON may nest: serde_json's own recursion limit, refused by the
/// parser before any value is read.
pub const MAX_JSON_DEPTH: usize = 128;

/// Why a JSON document (a scene file, a field document) cannot be read:
/// each variant names the file, the position in its text, or the JSON path
/// of the value refused (`root.difference[1].sphere.radius`).
#[derive(Debug, Error)]
pub enum JsonError {
    /// The file could not be read.
    #[error("{}: cannot read: {source}", .file.display())]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The text is not JSON (or nests deeper than [`MAX_JSON_DEPTH`]).
    #[error("{file}: line {line}, column {column}: not valid JSON: {message}")]
    Syntax {
        /// The file (`<string>` for text).
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
    /// A value is missing, has the wrong type or is out of range.
    #[error("{at}: {message}")]
    Value {
        /// The JSON path.
        at: String,
        /// What is wrong.
        message: String,
    },
    /// A key the format does not have there.
    #[error("{at}: unknown key \"{}\" (expected {expected})", super::import_error::excerpt(.key.as_bytes()))]
    UnknownKey {
        /// The JSON path of the object.
        at: String,
        /// The key found (the message quotes a short, escaped excerpt).
        key: String,
        /// The keys allowed there.
        expected: &'static str,
    },
}

/// Parses JSON text, naming `name` and the position on failure.
pub(crate) fn parse_json<E: From<JsonError>>(text: &str, name: &str) -> Result<Value, E> {
    serde_json::from_str(text).map_err(|e| {
        let message = if e.to_string().starts_with("recursion limit exceeded") {
            format!("nested deeper than {MAX_JSON_DEPTH} levels (the limit)")
        } else {
            e.to_string()
        };
        E::from(JsonError::Syntax {
            file: name.to_string(),
            line: e.line(),
            column: e.column(),
            message,
        })
    })
}

/// A refusal of the value at `at`.
pub(crate) fn value_error<E: From<JsonError>>(at: &str, message: impl Into<String>) -> E {
    E::from(JsonError::Value {
        at: at.to_string(),
        message: message.into(),
    })
}

/// "expected …, found …", with long values cut short.
pub(crate) fn bad<E: From<JsonError>>(at: &str, expected: &str, found: &Value) -> E {
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
    value_error(at, format!("expected {expected}, found {shown}"))
}

/// The value as an object.
pub(crate) fn object<'v, E: From<JsonError>>(
    value: &'v Value,
    at: &str,
) -> Result<&'v Map<String, Value>, E> {
    value.as_object().ok_or_else(|| bad(at, "an object", value))
}

/// The value as an object with only `allowed` keys (`expected` lists them
/// for the message).
pub(crate) fn fields<'v, E: From<JsonError>>(
    value: &'v Value,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<&'v Map<String, Value>, E> {
    let o = object(value, at)?;
    check_keys(o, at, allowed, expected)?;
    Ok(o)
}

/// Refuses the first key of `o` that is not in `allowed`.
pub(crate) fn check_keys<E: From<JsonError>>(
    o: &Map<String, Value>,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<(), E> {
    match o.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(key) => Err(E::from(JsonError::UnknownKey {
            at: at.to_string(),
            key: key.clone(),
            expected,
        })),
        None => Ok(()),
    }
}

/// The value under `key`, which must be there.
pub(crate) fn req<'v, E: From<JsonError>>(
    o: &'v Map<String, Value>,
    at: &str,
    key: &str,
) -> Result<&'v Value, E> {
    o.get(key)
        .ok_or_else(|| value_error(&format!("{at}.{key}"), "missing"))
}

/// A finite number.
pub(crate) fn number<E: From<JsonError>>(value: &Value, at: &str) -> Result<f64, E> {
    match value.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(bad(at, "a finite number", value)),
    }
}

/// A finite number above zero.
pub(crate) fn positive<E: From<JsonError>>(value: &Value, at: &str) -> Result<f64, E> {
    match value.as_f64() {
        Some(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(bad(at, "a positive number", value)),
    }
}

/// An array of three finite numbers.
pub(crate) fn vec3<E: From<JsonError>>(value: &Value, at: &str) -> Result<DVec3, E> {
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
pub(crate) fn vec3_or<E: From<JsonError>>(
    o: &Map<String, Value>,
    at: &str,
    key: &str,
    default: DVec3,
) -> Result<DVec3, E> {
    o.get(key)
        .map(|v| vec3(v, &format!("{at}.{key}")))
        .transpose()
        .map(|v| v.unwrap_or(default))
}
