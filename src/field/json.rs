//! Field documents: a blobby field or a field-CSG tree as JSON, read with
//! errors that name the JSON path of the offending value.
//!
//! ```text
//! DOCUMENT := NODE, optionally with "resolution": N (cells along the longest side)
//! NODE := {"blobs": [SOURCE, ...], "falloff": "soft_object" | "cubic_parabola"}   (falloff optional)
//!       | {"union": [NODE, ...]} | {"intersection": [NODE, ...]}
//!       | {"difference": [NODE, NODE, ...]}                              (the first minus the rest)
//! SOURCE := {"center": [x, y, z], "radius": R, "strength": w}           (R > 0; strength optional, 1)
//! ```
//!
//! A document may stand alone ([`load_json`]) or sit inside a scene file as
//! a `{"field": DOCUMENT}` leaf (`wingedge::scene`), which is meshed into a
//! polyhedron ([`read_document`] reads it at the leaf's JSON path).

use crate::SetOp;
use std::path::Path;

use glam::DVec3;
use serde_json::{Map, Value};

use super::blobs::Blobs;
use super::combine::FieldCsg;
use super::error::FieldError;
use super::falloff::Falloff;
use super::scalar_field::Field;
use super::source::Source;
use crate::io::json_value::{self, JsonError};

/// The most sources a document may hold, all nodes together.
pub const MAX_DOCUMENT_SOURCES: usize = 1_000_000;
/// How deep JSON may nest (arrays and objects; an operator node is two
/// levels): serde_json's recursion limit, refused before any node is read.
pub use crate::io::json_value::MAX_JSON_DEPTH;

const NODE_KEYS: &str = "blobs (with falloff), union, intersection, difference";
const SOURCE_KEYS: &str = "center, radius, strength";

/// A loaded field document: the field and the resolution it asks for.
pub struct FieldDocument {
    /// The field.
    pub field: Box<dyn Field>,
    /// `"resolution"`, when the document gives one.
    pub resolution: Option<usize>,
    /// Sources in all `blobs` nodes.
    pub sources: usize,
}

impl std::fmt::Debug for FieldDocument {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FieldDocument")
            .field("bounds", &self.field.bounds())
            .field("resolution", &self.resolution)
            .field("sources", &self.sources)
            .finish()
    }
}

/// Reads a field document from a file.
///
/// # Errors
///
/// [`JsonError`] naming the file, the JSON position or the JSON path.
pub fn load_json(path: &Path) -> Result<FieldDocument, JsonError> {
    // The bounded reader every input goes through (size limit, stops at a
    // NUL byte); what is not UTF-8 text is refused as binary data.
    let read_error = |source| JsonError::Read {
        file: path.to_path_buf(),
        source,
    };
    let binary = || read_error(std::io::Error::other("binary data (not UTF-8 text)"));
    let bytes =
        crate::io::read_input_at_most(path, crate::io::MAX_JSON_BYTES).map_err(read_error)?;
    if crate::io::text_len(&bytes) < bytes.len() {
        return Err(binary());
    }
    let text = String::from_utf8(bytes).map_err(|_| binary())?;
    parse_named(&text, &path.display().to_string())
}

/// Reads a field document from text.
///
/// # Errors
///
/// As [`load_json`], with `<string>` as the file name.
pub fn parse_json(text: &str) -> Result<FieldDocument, JsonError> {
    parse_named(text, "<string>")
}

fn parse_named(text: &str, name: &str) -> Result<FieldDocument, JsonError> {
    let value = json_value::parse_json::<JsonError>(text, name, "field", "field")?;
    read_document(&value, "field")
}

/// Reads a field document already parsed as JSON; `at` is the JSON path of
/// `value` (`field` for a document of its own, the node's path inside a
/// scene file), and every error names a path below it.
///
/// # Errors
///
/// [`JsonError::Value`] or [`JsonError::UnknownKey`].
pub fn read_document(value: &Value, at: &str) -> Result<FieldDocument, JsonError> {
    let o = value
        .as_object()
        .ok_or_else(|| bad(at, "an object", value))?;
    let resolution = match o.get("resolution") {
        None => None,
        Some(v) => Some(
            v.as_u64()
                .filter(|&n| n >= 1)
                .and_then(|n| usize::try_from(n).ok())
                .ok_or_else(|| bad(&format!("{at}.resolution"), "a whole number ≥ 1", v))?,
        ),
    };
    let mut node = o.clone();
    node.remove("resolution");
    let mut sources = 0;
    let field = read_node(&node, at, &mut sources)?;
    Ok(FieldDocument {
        field,
        resolution,
        sources,
    })
}

fn read_node(
    o: &Map<String, Value>,
    at: &str,
    sources: &mut usize,
) -> Result<Box<dyn Field>, JsonError> {
    let op = |name: &str| match name {
        "union" => Some(SetOp::Union),
        "intersection" => Some(SetOp::Intersection),
        "difference" => Some(SetOp::Difference),
        _ => None,
    };
    let Some(kind) = o.keys().find(|k| k.as_str() == "blobs" || op(k).is_some()) else {
        return match o.keys().next() {
            Some(key) => Err(JsonError::UnknownKey {
                at: at.to_string(),
                key: key.clone(),
                expected: NODE_KEYS,
            }),
            None => Err(value_error(
                at,
                format!("an empty object; expected one of {NODE_KEYS}"),
            )),
        };
    };
    let allowed: &[&str] = if kind == "blobs" {
        &["blobs", "falloff"]
    } else {
        &[kind.as_str()]
    };
    json_value::check_keys::<JsonError>(o, at, allowed, NODE_KEYS)?;
    let here = format!("{at}.{kind}");
    let list = o[kind.as_str()]
        .as_array()
        .ok_or_else(|| bad(&here, "an array", &o[kind.as_str()]))?;
    if let Some(op) = op(kind) {
        let least = if op == SetOp::Difference { 2 } else { 1 };
        if list.len() < least {
            return Err(value_error(
                &here,
                format!(
                    "{} needs at least {least} operands, found {}",
                    op.name(),
                    list.len()
                ),
            ));
        }
        let mut children = list.iter().enumerate().map(|(i, v)| {
            let child_at = format!("{here}[{i}]");
            let child = v
                .as_object()
                .ok_or_else(|| bad(&child_at, "an object", v))?;
            read_node(child, &child_at, sources)
        });
        let mut field = children
            .next()
            .unwrap_or_else(|| Err(value_error(&here, "no operand".into())))?;
        for child in children {
            field = Box::new(FieldCsg::new(op, field, child?));
        }
        return Ok(field);
    }
    let falloff = match o.get("falloff") {
        None => Falloff::default(),
        Some(Value::String(s)) if s == "soft_object" => Falloff::SoftObject,
        Some(Value::String(s)) if s == "cubic_parabola" => Falloff::CubicParabola,
        Some(v) => {
            return Err(bad(
                &format!("{at}.falloff"),
                "\"soft_object\" or \"cubic_parabola\"",
                v,
            ));
        }
    };
    *sources += list.len();
    if *sources > MAX_DOCUMENT_SOURCES {
        return Err(value_error(
            &here,
            format!("more than {MAX_DOCUMENT_SOURCES} sources in the document (the limit)"),
        ));
    }
    let parsed: Vec<Source> = list
        .iter()
        .enumerate()
        .map(|(i, v)| read_source(v, &format!("{here}[{i}]")))
        .collect::<Result<_, _>>()?;
    let blobs = Blobs::try_new(parsed, falloff).map_err(|e| located(&here, e))?;
    Ok(Box::new(blobs))
}

fn read_source(v: &Value, at: &str) -> Result<Source, JsonError> {
    let o = json_value::fields::<JsonError>(v, at, &["center", "radius", "strength"], SOURCE_KEYS)?;
    let center = match o.get("center") {
        Some(c) => point(c, &format!("{at}.center"))?,
        None => return Err(value_error(&format!("{at}.center"), "missing".into())),
    };
    let radius = match o.get("radius") {
        Some(r) => number(r, &format!("{at}.radius"))?,
        None => return Err(value_error(&format!("{at}.radius"), "missing".into())),
    };
    if radius <= 0.0 {
        return Err(value_error(
            &format!("{at}.radius"),
            format!("expected a positive number, found {radius}"),
        ));
    }
    let strength = match o.get("strength") {
        Some(s) => number(s, &format!("{at}.strength"))?,
        None => 1.0,
    };
    Ok(Source {
        center,
        radius,
        strength,
    })
}

fn number(v: &Value, at: &str) -> Result<f64, JsonError> {
    json_value::number(v, at)
}

fn point(v: &Value, at: &str) -> Result<DVec3, JsonError> {
    json_value::vec3(v, at)
}

fn value_error(at: &str, message: String) -> JsonError {
    json_value::value_error(at, message)
}

/// A field error, at the path of the source value it concerns (below the
/// blobs list `at`).
fn located(at: &str, e: FieldError) -> JsonError {
    let path = match &e {
        FieldError::NonFiniteCenter { source_index, .. } => format!("{at}[{source_index}].center"),
        FieldError::BadRadius { source_index, .. } => format!("{at}[{source_index}].radius"),
        FieldError::BadStrength { source_index, .. } => format!("{at}[{source_index}].strength"),
        FieldError::OutOfRange {
            source_index, what, ..
        } => {
            let key = if *what == "radius" {
                "radius"
            } else {
                "center"
            };
            format!("{at}[{source_index}].{key}")
        }
        _ => at.to_string(),
    };
    value_error(&path, e.to_string())
}

fn bad(at: &str, expected: &str, found: &Value) -> JsonError {
    json_value::bad(at, expected, found)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error(text: &str) -> String {
        parse_json(text).unwrap_err().to_string()
    }

    #[test]
    fn a_document_reads_blobs_and_operators() {
        let doc = parse_json(
            r#"{"resolution": 20, "difference": [
                {"blobs": [{"center": [0,0,0], "radius": 2}, {"center": [1,0,0], "radius": 2, "strength": 0.8}]},
                {"blobs": [{"center": [0,0,1], "radius": 1}], "falloff": "cubic_parabola"}]}"#,
        )
        .unwrap();
        assert_eq!(doc.resolution, Some(20));
        assert_eq!(doc.sources, 3);
        assert!(doc.field.contains(DVec3::new(0.5, 0.0, -0.5)));
        assert!(!doc.field.contains(DVec3::new(0.0, 0.0, 0.9)));
    }

    #[test]
    fn errors_name_the_json_path() {
        assert_eq!(
            error(
                r#"{"blobs": [{"center": [0,0,0], "radius": 1}, {"center": [0,0,0], "radius": 0}]}"#
            ),
            "field.blobs[1].radius: expected a positive number, found 0"
        );
        assert_eq!(
            error(r#"{"union": [{"blobs": []}, {"blobs": [{"center": [0,"x",0], "radius": 1}]}]}"#),
            "field.union[1].blobs[0].center[1]: expected a finite number, found \"x\""
        );
        assert_eq!(
            error(r#"{"blobs": [{"center": [0,0,0], "radius": -2}]}"#),
            "field.blobs[0].radius: expected a positive number, found -2"
        );
        assert_eq!(
            error(r#"{"resolution": 0, "blobs": []}"#),
            "field.resolution: expected a whole number ≥ 1, found 0"
        );
        assert!(error(r#"{"blob": []}"#).contains("unknown key \"blob\""));
        assert!(
            error(r#"{"blobs": [{"centre": [0,0,0], "radius": 1}]}"#)
                .contains("field.blobs[0]: unknown key \"centre\"")
        );
        assert!(
            error(r#"{"difference": [{"blobs": []}]}"#)
                .starts_with("field.difference: difference needs at least 2")
        );
        assert!(error("{\"blobs\": [").starts_with("<string>: line 1"));
        // A key twice, at the top or nested, is refused (serde_json keeps
        // the last one silently).
        assert_eq!(
            error(r#"{"resolution": 8, "blobs": [], "resolution": 9}"#),
            "<string>: field: key \"resolution\" appears twice"
        );
        assert_eq!(
            error(
                r#"{"union": [{"blobs": []}, {"blobs": [{"center": [0,0,0], "radius": 1, "center": [1,1,1]}]}]}"#
            ),
            "<string>: field.union[1].blobs[0]: key \"center\" appears twice"
        );
        assert!(
            error(r#"{"blobs": [{"center": [0,0,0], "radius": 1}, {"center": [0,0,0], "radius": 1e-300}]}"#)
                .starts_with("field.blobs[1].radius: source 1 (radius 1e-300) is out of range"),
            "{}",
            error(r#"{"blobs": [{"center": [0,0,0], "radius": 1}, {"center": [0,0,0], "radius": 1e-300}]}"#)
        );
        assert!(
            error(r#"{"blobs": [{"center": [1e200,0,0], "radius": 1}]}"#)
                .starts_with("field.blobs[0].center: source 0")
        );
        let nested = format!(
            "{}{{\"blobs\": []}}{}",
            "{\"union\": [".repeat(70),
            "]}".repeat(70)
        );
        assert!(
            error(&nested).contains("nested deeper than 128 levels"),
            "{}",
            error(&nested)
        );
    }

    #[test]
    fn an_empty_document_gives_an_empty_field() {
        let doc = parse_json(r#"{"blobs": []}"#).unwrap();
        assert!(doc.field.bounds().is_empty());
    }
}
