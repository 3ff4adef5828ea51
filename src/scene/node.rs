//! The nodes of a scene file: operators, transforms, primitives, mesh
//! leaves and included scenes, each read into a [`CsgExpr`].

use std::sync::Arc;

use glam::{DAffine3, DQuat, DVec3, EulerRot};
use serde_json::{Map, Value};

use super::SceneError;
use super::json::{bad, check_keys, fields, object, positive, req, vec3, vec3_or};
use super::reader::Reader;
use super::solid_leaf;
use crate::csg::{AxisBox, CsgExpr, Cylinder, HalfSpace, Primitive, Sphere};
use crate::geom::{Readable, ReadableVec};
use crate::io::JsonError;

const NODE_KEYS: &str = "one of mesh, halfspace, box, sphere, cylinder, sweep, revolve, loft, field, union, intersection, difference, scene, or transform with child";

impl Reader<'_> {
    /// Reads a node `depth` nodes below the outermost root.
    pub(super) fn node(
        &self,
        value: &Value,
        at: &str,
        depth: usize,
    ) -> Result<CsgExpr, SceneError> {
        self.state.budget.enter(at, depth)?;
        let obj = object(value, at)?;
        if obj.contains_key("transform") {
            check_keys(obj, at, &["transform", "child"], "transform and child")?;
            let transform = transform(&obj["transform"], &format!("{at}.transform"))?;
            let child = obj.get("child").ok_or_else(|| {
                SceneError::Json(JsonError::Value {
                    at: at.to_string(),
                    message: "transform without \"child\"".into(),
                })
            })?;
            let child = self.node(child, &format!("{at}.child"), depth + 1)?;
            return Ok(child.transformed(transform));
        }
        let mut entries = obj.iter();
        let (key, body) = match (entries.next(), entries.next()) {
            (Some(entry), None) => entry,
            (None, _) => {
                return Err(SceneError::Json(JsonError::Value {
                    at: at.to_string(),
                    message: format!("empty node; expected {NODE_KEYS}"),
                }));
            }
            (Some(_), Some((second, _))) => {
                return Err(SceneError::Json(JsonError::UnknownKey {
                    at: at.to_string(),
                    key: second.clone(),
                    expected: NODE_KEYS,
                }));
            }
        };
        let here = format!("{at}.{key}");
        let leaf = |p: Arc<dyn Primitive>| CsgExpr::Leaf {
            primitive: p,
            label: here.clone(),
        };
        match key.as_str() {
            "union" | "intersection" | "difference" => self.operator(key, body, &here, depth),
            "halfspace" => halfspace(body, &here).map(leaf),
            "box" => axis_box(body, &here).map(leaf),
            "sphere" => sphere(body, &here).map(leaf),
            "cylinder" => cylinder(body, &here).map(leaf),
            "sweep" => solid_leaf::sweep(body, &here).map(leaf),
            "revolve" => solid_leaf::revolve(body, &here).map(leaf),
            "loft" => solid_leaf::loft(body, &here).map(leaf),
            "mesh" => {
                let (relative, format) = mesh_reference(body, &here)?;
                let file = self.leaf_file(relative, &here)?;
                let primitive =
                    self.state
                        .meshes
                        .get(&file, format)
                        .map_err(|message| SceneError::Mesh {
                            at: here.clone(),
                            file,
                            message,
                        })?;
                Ok(leaf(primitive))
            }
            "field" => super::field_leaf::field_leaf(body, &here, |relative| {
                self.leaf_file(relative, &here)
            })
            .map(leaf),
            "scene" => {
                let Value::String(relative) = body else {
                    return Err(bad(&here, "a scene file path (string)", body));
                };
                self.include(relative, &here, depth)
            }
            _ => Err(SceneError::Json(JsonError::UnknownKey {
                at: at.to_string(),
                key: key.clone(),
                expected: NODE_KEYS,
            })),
        }
    }

    /// A union, intersection or difference of the nodes in `body`.
    fn operator(
        &self,
        key: &str,
        body: &Value,
        here: &str,
        depth: usize,
    ) -> Result<CsgExpr, SceneError> {
        let Value::Array(items) = body else {
            return Err(bad(here, "an array of nodes", body));
        };
        let minimum = if key == "difference" { 2 } else { 1 };
        if items.len() < minimum {
            return Err(SceneError::Json(JsonError::Value {
                at: here.to_string(),
                message: format!("needs at least {minimum} node(s), found {}", items.len()),
            }));
        }
        let kids = items
            .iter()
            .enumerate()
            .map(|(i, v)| self.node(v, &format!("{here}[{i}]"), depth + 1))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(match key {
            "union" => CsgExpr::Union(kids),
            "intersection" => CsgExpr::Intersection(kids),
            _ => CsgExpr::Difference(kids),
        })
    }
}

/// A refusal by a primitive's constructor, placed at `at`.
fn refused(at: &str, error: impl std::fmt::Display) -> SceneError {
    SceneError::Json(JsonError::Value {
        at: at.to_string(),
        message: error.to_string(),
    })
}

fn halfspace(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(body, here, &["point", "normal"], "point, normal")?;
    let point = vec3(req(o, here, "point")?, &format!("{here}.point"))?;
    let n_at = format!("{here}.normal");
    let normal = vec3(req(o, here, "normal")?, &n_at)?;
    let h = HalfSpace::try_new(point, normal).map_err(|e| refused(&n_at, e))?;
    Ok(Arc::new(h))
}

fn axis_box(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(body, here, &["min", "max"], "min, max")?;
    let min = vec3(req(o, here, "min")?, &format!("{here}.min"))?;
    let max_at = format!("{here}.max");
    let max = vec3(req(o, here, "max")?, &max_at)?;
    let b = AxisBox::try_new(min, max).map_err(|e| refused(&max_at, e))?;
    Ok(Arc::new(b))
}

fn sphere(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(body, here, &["center", "radius"], "center, radius")?;
    let center = vec3(req(o, here, "center")?, &format!("{here}.center"))?;
    let r_at = format!("{here}.radius");
    let radius = positive(req(o, here, "radius")?, &r_at)?;
    let s = Sphere::try_new(center, radius).map_err(|e| refused(&r_at, e))?;
    Ok(Arc::new(s))
}

fn cylinder(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o: &Map<String, Value> = fields(
        body,
        here,
        &["base", "axis", "radius"],
        "base, axis, radius",
    )?;
    let base = vec3(req(o, here, "base")?, &format!("{here}.base"))?;
    let a_at = format!("{here}.axis");
    let axis = vec3(req(o, here, "axis")?, &a_at)?;
    if axis == DVec3::ZERO {
        return Err(refused(&a_at, "the axis must not be zero"));
    }
    let radius = positive(req(o, here, "radius")?, &format!("{here}.radius"))?;
    let c = Cylinder::try_new(base, axis, radius).map_err(|e| refused(here, e))?;
    Ok(Arc::new(c))
}

/// A `transform` object: scale, then rotate (about x, then y, then z, in
/// degrees), then translate.
fn transform(value: &Value, at: &str) -> Result<DAffine3, SceneError> {
    let o = fields(
        value,
        at,
        &["translate", "rotate_deg", "scale"],
        "translate, rotate_deg, scale",
    )?;
    let translate = vec3_or(o, at, "translate", DVec3::ZERO)?;
    let rotate = vec3_or(o, at, "rotate_deg", DVec3::ZERO)?;
    let scale = vec3_or(o, at, "scale", DVec3::ONE)?;
    if scale.cmpeq(DVec3::ZERO).any() {
        return Err(refused(
            &format!("{at}.scale"),
            format!(
                "scale {} has a zero component: the solid would be flat",
                ReadableVec(scale)
            ),
        ));
    }
    let r = rotate * (std::f64::consts::PI / 180.0);
    // Intrinsic ZYX equals rotating about x first, then y, then z.
    let rotation = DQuat::from_euler(EulerRot::ZYX, r.z, r.y, r.x);
    let affine = DAffine3::from_scale_rotation_translation(scale, rotation, translate);
    // The scale is the value at fault when the transform cannot be
    // inverted in f64 (its determinant overflows or underflows); refused
    // here, at its path, rather than at the leaf it moves.
    let determinant = affine.matrix3.determinant();
    if determinant == 0.0 || !determinant.is_finite() {
        return Err(refused(
            &format!("{at}.scale"),
            format!(
                "scale {} gives the transform the determinant {}, beyond f64's range: it cannot be inverted",
                ReadableVec(scale),
                Readable(determinant)
            ),
        ));
    }
    Ok(affine)
}

/// A mesh leaf's file and format: `"PATH"` (the format by the extension),
/// or `{"path": PATH, "format": NAME}`.
fn mesh_reference<'a>(
    body: &'a Value,
    here: &str,
) -> Result<(&'a str, Option<crate::io::Format>), SceneError> {
    let expected = "a file path (string), or {\"path\": PATH, \"format\": NAME}";
    match body {
        Value::String(relative) => Ok((relative, None)),
        Value::Object(map) => {
            if let Some(key) = map
                .keys()
                .find(|k| !matches!(k.as_str(), "path" | "format"))
            {
                return Err(SceneError::Json(JsonError::UnknownKey {
                    at: here.to_string(),
                    key: key.clone(),
                    expected: "path, format",
                }));
            }
            let Some(Value::String(relative)) = map.get("path") else {
                return Err(bad(
                    &format!("{here}.path"),
                    "a file path (string)",
                    map.get("path").unwrap_or(&Value::Null),
                ));
            };
            let format = match map.get("format") {
                None => None,
                Some(Value::String(name)) => {
                    Some(name.parse().map_err(|e: crate::io::UnknownFormat| {
                        SceneError::Json(JsonError::Value {
                            at: format!("{here}.format"),
                            message: e.to_string(),
                        })
                    })?)
                }
                Some(other) => {
                    return Err(bad(
                        &format!("{here}.format"),
                        "a format name (string)",
                        other,
                    ));
                }
            };
            Ok((relative, format))
        }
        other => Err(bad(here, expected, other)),
    }
}
