//! The model part of a 3MF file (3MF Core Specification, chapters 3–4):
//! the unit, the objects (meshes, or components placing other objects),
//! the build items; parsed by streaming XML, so that memory follows the
//! mesh rather than the text. Refusals name the XML path
//! (`/model/resources/object[@id='3']/mesh/vertices/vertex[7]`).

use std::collections::HashMap;
use std::io::BufRead;

use glam::DVec3;
use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// A 3MF affine transform: rows `m00 m01 m02`, …, `m30 m31 m32`, applied
/// to a row vector `(x, y, z, 1)`.
pub(crate) type Transform = [f64; 12];

/// An object's content.
#[derive(Debug)]
pub(crate) enum Shape {
    Mesh {
        positions: Vec<DVec3>,
        triangles: Vec<[usize; 3]>,
    },
    Components(Vec<(String, Option<Transform>)>),
}

/// An object of the resources.
#[derive(Debug)]
pub(crate) struct Object {
    pub name: Option<String>,
    pub shape: Shape,
}

/// The parsed model: millimetres per unit, objects by id, build items
/// (object id and transform) in order.
#[derive(Debug, Default)]
pub(crate) struct Model {
    pub millimetres: f64,
    pub objects: HashMap<String, Object>,
    pub items: Vec<(String, Option<Transform>)>,
}

/// A refusal at an XML path.
#[derive(Debug)]
pub(crate) struct XmlError {
    pub at: String,
    pub message: String,
}

fn refuse(at: impl Into<String>, message: impl Into<String>) -> XmlError {
    XmlError {
        at: at.into(),
        message: message.into(),
    }
}

/// Millimetres per 3MF unit.
fn unit(name: &str) -> Option<f64> {
    Some(match name {
        "micron" => 0.001,
        "millimeter" => 1.0,
        "centimeter" => 10.0,
        "inch" => 25.4,
        "foot" => 304.8,
        "meter" => 1000.0,
        _ => return None,
    })
}

/// The attribute `key` of `e`, unescaped.
fn attribute(e: &BytesStart, key: &str, at: &str) -> Result<Option<String>, XmlError> {
    for a in e.attributes() {
        let a = a.map_err(|err| refuse(at, format!("malformed attribute: {err}")))?;
        if a.key.local_name().as_ref() == key {
            let value = a
                .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                .map_err(|err| refuse(at, format!("malformed attribute value: {err}")))?;
            return Ok(Some(value.into_owned()));
        }
    }
    Ok(None)
}

fn required(e: &BytesStart, key: &str, at: &str) -> Result<String, XmlError> {
    attribute(e, key, at)?.ok_or_else(|| refuse(at, format!("the attribute `{key}` is missing")))
}

fn number(e: &BytesStart, key: &str, at: &str) -> Result<f64, XmlError> {
    let text = required(e, key, at)?;
    let x: f64 = text.trim().parse().map_err(|_| {
        refuse(
            at,
            format!(
                "`{key}` is not a number: `{}`",
                super::import_error::excerpt(text.as_bytes())
            ),
        )
    })?;
    if !x.is_finite() {
        return Err(refuse(at, format!("`{key}` is not finite: {x}")));
    }
    Ok(x)
}

fn transform(e: &BytesStart, at: &str) -> Result<Option<Transform>, XmlError> {
    let Some(text) = attribute(e, "transform", at)? else {
        return Ok(None);
    };
    let values: Vec<f64> = text
        .split_ascii_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| refuse(at, "the transform is not 12 numbers"))?;
    let m: Transform = values
        .try_into()
        .map_err(|_| refuse(at, "the transform is not 12 numbers"))?;
    if m.iter().any(|x| !x.is_finite()) {
        return Err(refuse(at, "the transform has a non-finite entry"));
    }
    Ok(Some(m))
}

/// Where the parser is inside an object.
struct Current {
    id: String,
    name: Option<String>,
    positions: Vec<DVec3>,
    triangles: Vec<[usize; 3]>,
    components: Vec<(String, Option<Transform>)>,
    has_mesh: bool,
}

/// Parses the model XML from `source`; `bytes_read` says how far the
/// stream got (for errors of the XML itself).
pub(crate) fn parse(source: impl BufRead) -> Result<Model, XmlError> {
    let mut reader = Reader::from_reader(source);
    let mut buf = Vec::new();
    let mut model = Model {
        millimetres: 1.0,
        ..Model::default()
    };
    let mut stack: Vec<String> = Vec::new();
    let mut current: Option<Current> = None;
    let mut object_at = String::new();
    loop {
        let event = reader.read_event_into(&mut buf).map_err(|e| {
            refuse(
                format!("byte {}", reader.error_position()),
                format!("not well-formed XML: {e}"),
            )
        })?;
        let (e, empty) = match event {
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(_) => {
                if stack.pop().as_deref() == Some("object")
                    && let Some(c) = current.take()
                {
                    finish_object(&mut model, c, &object_at)?;
                }
                buf.clear();
                continue;
            }
            Event::Eof => break,
            _ => {
                buf.clear();
                continue;
            }
        };
        let name = e.local_name().as_ref().to_string();
        let parent = stack.last().map(String::as_str);
        match (parent, name.as_str()) {
            (None, "model") => {
                if let Some(u) = attribute(&e, "unit", "/model")? {
                    model.millimetres = unit(&u).ok_or_else(|| {
                        refuse(
                            "/model",
                            format!(
                                "unknown unit `{}`",
                                super::import_error::excerpt(u.as_bytes())
                            ),
                        )
                    })?;
                }
            }
            (None, other) => {
                return Err(refuse(
                    "/",
                    format!(
                        "the root element is `{}`, not `model`",
                        super::import_error::excerpt(other.as_bytes())
                    ),
                ));
            }
            (Some("resources"), "object") => {
                let id = required(&e, "id", "/model/resources/object")?;
                object_at = format!(
                    "/model/resources/object[@id='{}']",
                    super::import_error::excerpt(id.as_bytes())
                );
                let name = attribute(&e, "name", &object_at)?;
                current = Some(Current {
                    id,
                    name,
                    positions: Vec::new(),
                    triangles: Vec::new(),
                    components: Vec::new(),
                    has_mesh: false,
                });
            }
            (Some("object"), "mesh") => {
                if let Some(c) = current.as_mut() {
                    c.has_mesh = true;
                }
            }
            (Some("vertices"), "vertex") => {
                if let Some(c) = current.as_mut() {
                    let k = c.positions.len() + 1;
                    let at = || format!("{object_at}/mesh/vertices/vertex[{k}]");
                    let p = DVec3::new(
                        number(&e, "x", &at())?,
                        number(&e, "y", &at())?,
                        number(&e, "z", &at())?,
                    );
                    c.positions.push(p);
                }
            }
            (Some("triangles"), "triangle") => {
                if let Some(c) = current.as_mut() {
                    let k = c.triangles.len() + 1;
                    let at = format!("{object_at}/mesh/triangles/triangle[{k}]");
                    let mut t = [0usize; 3];
                    for (slot, key) in t.iter_mut().zip(["v1", "v2", "v3"]) {
                        let text = required(&e, key, &at)?;
                        let index: i64 = text.trim().parse().map_err(|_| {
                            refuse(
                                &at,
                                format!(
                                    "`{key}` is not an integer: `{}`",
                                    super::import_error::excerpt(text.as_bytes())
                                ),
                            )
                        })?;
                        if !(0..c.positions.len() as i64).contains(&index) {
                            return Err(refuse(
                                &at,
                                format!(
                                    "vertex index {index} is out of range: {} vertices are defined",
                                    c.positions.len()
                                ),
                            ));
                        }
                        *slot = index as usize;
                    }
                    c.triangles.push(t);
                }
            }
            (Some("components"), "component") => {
                if let Some(c) = current.as_mut() {
                    let at = format!(
                        "{object_at}/components/component[{}]",
                        c.components.len() + 1
                    );
                    let id = required(&e, "objectid", &at)?;
                    c.components.push((id, transform(&e, &at)?));
                }
            }
            (Some("build"), "item") => {
                let at = format!("/model/build/item[{}]", model.items.len() + 1);
                let id = required(&e, "objectid", &at)?;
                model.items.push((id, transform(&e, &at)?));
            }
            _ => {}
        }
        if !empty {
            stack.push(name);
        } else if name == "object"
            && let Some(c) = current.take()
        {
            finish_object(&mut model, c, &object_at)?;
        }
        buf.clear();
    }
    Ok(model)
}

fn finish_object(model: &mut Model, c: Current, at: &str) -> Result<(), XmlError> {
    let shape = if c.has_mesh {
        Shape::Mesh {
            positions: c.positions,
            triangles: c.triangles,
        }
    } else {
        Shape::Components(c.components)
    };
    let object = Object {
        name: c.name,
        shape,
    };
    if model.objects.insert(c.id, object).is_some() {
        return Err(refuse(at, "a second object with this id"));
    }
    Ok(())
}
