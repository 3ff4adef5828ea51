//! Reading JSON documents by JSON path, shared by the scene format and
//! field documents: each reader names the path of the value it refuses
//! (`root.difference[1].sphere.radius`), and is generic over the caller's
//! error type, which only has to take a [`JsonError`].

use std::cell::{Cell, RefCell};
use std::collections::HashSet;
use std::path::PathBuf;

use glam::DVec3;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};
use thiserror::Error;

/// How deep JSON may nest: serde_json's own recursion limit, refused by the
/// parser before any value is read.
pub const MAX_JSON_DEPTH: usize = 128;

/// The largest JSON document read (a scene file, an included scene, a
/// field document): 256 MiB, refused while reading, before parsing.
pub const MAX_JSON_BYTES: usize = 1 << 28;

/// The most values (objects, arrays, numbers, strings, booleans, nulls)
/// one JSON document may hold: 16 million, counted by a pass over the text
/// that builds nothing, before the document is parsed into memory. A value
/// parsed costs some 40 to 100 bytes whatever its text (`0,` is two bytes),
/// so this, not the size of the text, bounds a document's memory; a scene
/// of the most nodes a scene may have (`scene::MAX_NODES`, a million
/// boxes) holds about 10 million.
pub const MAX_JSON_VALUES: usize = 16_000_000;

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
    /// A key that appears twice in one object (JSON leaves that to the
    /// reader, and taking the last silently would hide the first).
    #[error("{file}: {at}: key {} appears twice", short_key(.key))]
    DuplicateKey {
        /// The file (`<string>` for text).
        file: String,
        /// The JSON path of the object.
        at: String,
        /// The key.
        key: String,
    },
    /// A document larger than [`MAX_JSON_BYTES`] or holding more than
    /// [`MAX_JSON_VALUES`] values, refused before it is parsed.
    #[error("{file}: the document holds more than the limit of {limit} {unit}")]
    TooLarge {
        /// The file (`<string>` for text).
        file: String,
        /// The limit.
        limit: usize,
        /// What is counted: `bytes` or `JSON values`.
        unit: &'static str,
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

/// A key as a message quotes it: escaped, and cut short past 40
/// characters.
fn short_key(key: &str) -> String {
    let mut shown: String = key.chars().take(40).collect();
    if shown.len() < key.len() {
        shown.push_str("...");
    }
    format!("{shown:?}")
}

/// Parses JSON text, naming `name` and the position on failure; a key that
/// appears twice in one object is refused ([`JsonError::DuplicateKey`]),
/// naming the object's JSON path: `top` for the document itself, and
/// `prefix.key` below it (the key alone for an empty `prefix`). A text
/// longer than [`MAX_JSON_BYTES`] or with more than [`MAX_JSON_VALUES`]
/// values is refused ([`JsonError::TooLarge`]) before any value is built:
/// the walk over the keys that finds duplicates counts the values first,
/// and the document is parsed only after it.
pub(crate) fn parse_json<E: From<JsonError>>(
    text: &str,
    name: &str,
    top: &str,
    prefix: &str,
) -> Result<Value, E> {
    let too_large = |limit, unit| {
        E::from(JsonError::TooLarge {
            file: name.to_string(),
            limit,
            unit,
        })
    };
    if text.len() > MAX_JSON_BYTES {
        return Err(too_large(MAX_JSON_BYTES, "bytes"));
    }
    let duplicate = RefCell::new(None);
    let values = Cell::new(0);
    let walk = Walk {
        parent: None,
        step: Step::Document,
        top,
        prefix,
        duplicate: &duplicate,
        values: &values,
    };
    let mut reader = serde_json::Deserializer::from_str(text);
    if walk.deserialize(&mut reader).is_err() {
        if let Some((at, key)) = duplicate.into_inner() {
            return Err(E::from(JsonError::DuplicateKey {
                file: name.to_string(),
                at,
                key,
            }));
        }
        if values.get() > MAX_JSON_VALUES {
            return Err(too_large(MAX_JSON_VALUES, "JSON values"));
        }
        // Otherwise the text is not JSON: the parse below says where.
    }
    parse_value(text, name)
}

/// A walk over JSON text that only looks at the keys of each object,
/// stopping at the first that appears twice (recorded in `duplicate`).
/// A value's JSON path is made only for a duplicate: each step links to
/// its parent's, so an array of millions of numbers costs no string each.
struct Walk<'a> {
    /// The walk of the enclosing value, and the step from it to this one.
    parent: Option<&'a Walk<'a>>,
    step: Step,
    top: &'a str,
    prefix: &'a str,
    duplicate: &'a RefCell<Option<(String, String)>>,
    /// The values met so far; the walk stops past [`MAX_JSON_VALUES`].
    values: &'a Cell<usize>,
}

/// How a walked value is reached from the enclosing one.
enum Step {
    /// It is the document.
    Document,
    /// The value of this key of an object.
    Key(String),
    /// This element of an array.
    Index(usize),
}

impl Walk<'_> {
    /// The JSON path of the value walked (`None` for the document).
    fn at(&self) -> Option<String> {
        let parent_at = || self.parent.and_then(Walk::at);
        match &self.step {
            Step::Document => None,
            Step::Key(key) => Some(match (parent_at(), self.prefix) {
                (None, "") => key.clone(),
                (None, prefix) => format!("{prefix}.{key}"),
                (Some(at), _) => format!("{at}.{key}"),
            }),
            Step::Index(index) => {
                let here = parent_at().unwrap_or_else(|| self.top.to_string());
                Some(format!("{here}[{index}]"))
            }
        }
    }

    fn here(&self) -> String {
        self.at().unwrap_or_else(|| self.top.to_string())
    }

    fn below(&self, step: Step) -> Walk<'_> {
        Walk {
            parent: Some(self),
            step,
            top: self.top,
            prefix: self.prefix,
            duplicate: self.duplicate,
            values: self.values,
        }
    }
}

impl<'de> DeserializeSeed<'de> for Walk<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        self.values.set(self.values.get() + 1);
        if self.values.get() > MAX_JSON_VALUES {
            return Err(de::Error::custom("too many values"));
        }
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Walk<'_> {
    type Value = ();

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<X: de::Error>(self, _: bool) -> Result<(), X> {
        Ok(())
    }

    fn visit_i64<X: de::Error>(self, _: i64) -> Result<(), X> {
        Ok(())
    }

    fn visit_u64<X: de::Error>(self, _: u64) -> Result<(), X> {
        Ok(())
    }

    fn visit_f64<X: de::Error>(self, _: f64) -> Result<(), X> {
        Ok(())
    }

    fn visit_str<X: de::Error>(self, _: &str) -> Result<(), X> {
        Ok(())
    }

    fn visit_unit<X: de::Error>(self) -> Result<(), X> {
        Ok(())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let mut index = 0;
        while seq
            .next_element_seed(self.below(Step::Index(index)))?
            .is_some()
        {
            index += 1;
        }
        Ok(())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let mut seen = HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                *self.duplicate.borrow_mut() = Some((self.here(), key));
                return Err(de::Error::custom("duplicate key"));
            }
            map.next_value_seed(self.below(Step::Key(key)))?;
        }
        Ok(())
    }
}

/// Parses JSON text into a value, naming `name` and the position on
/// failure.
fn parse_value<E: From<JsonError>>(text: &str, name: &str) -> Result<Value, E> {
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
