//! Scene files: a CSG tree plus optional camera, light and shadows, in JSON.
//!
//! ```text
//! {"root": NODE, "camera": {...}, "light": {...}, "shadows": false}   (camera, light, shadows optional)
//! NODE := {"mesh": "relative/path.obj"}
//!       | {"halfspace": {"point": [x,y,z], "normal": [x,y,z]}}
//!       | {"box": {"min": [x,y,z], "max": [x,y,z]}}
//!       | {"sphere": {"center": [x,y,z], "radius": r}}
//!       | {"cylinder": {"base": [x,y,z], "axis": [x,y,z], "radius": r}}   (axis: base to top)
//!       | {"union": [NODE, ...]} | {"intersection": [NODE, ...]} | {"difference": [NODE, NODE, ...]}
//!       | {"transform": {"translate": [..], "rotate_deg": [rx,ry,rz], "scale": [..]}, "child": NODE}
//! camera := {"eye": [x,y,z], "look_at": [x,y,z], "up": [x,y,z], "fov_deg": f}   (up, fov_deg optional)
//! light  := {"direction": [x,y,z]} | {"position": [x,y,z]}, plus optional "ambient": a in [0, 1]
//! ```
//!
//! A transform scales, then rotates (about x, then y, then z, in degrees),
//! then translates; each part is optional. Mesh paths are relative to the
//! scene file. Unknown keys and bad values are errors naming the JSON path,
//! e.g. `root.difference[1].sphere.radius`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DAffine3, DQuat, DVec3, EulerRot};
use serde_json::{Map, Value};
use thiserror::Error;

use super::{AxisBox, Csg, CsgError, CsgExpr, Cylinder, HalfSpace, Polyhedron, Primitive, Sphere};

/// Why a scene could not be loaded.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{file}: cannot read: {source}")]
    Read {
        /// The scene file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The text is not JSON.
    #[error("{file}: line {line}, column {column}: not valid JSON: {message}")]
    Json {
        /// The scene file (`<string>` for text).
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
        /// The JSON path, e.g. `root.difference[1].sphere.radius`.
        at: String,
        /// What is wrong.
        message: String,
    },
    /// A key the format does not have.
    #[error("{at}: unknown key \"{key}\" (expected {expected})")]
    UnknownKey {
        /// The JSON path of the object.
        at: String,
        /// The key found.
        key: String,
        /// The keys allowed there.
        expected: &'static str,
    },
    /// A mesh leaf could not be loaded or is not a valid closed solid.
    #[error("{at}: mesh {file}: {message}")]
    Mesh {
        /// The JSON path of the node.
        at: String,
        /// The mesh file, resolved against the scene's folder.
        file: PathBuf,
        /// Why (the validator's report for a defective mesh).
        message: String,
    },
    /// The tree is malformed (a singular transform, an empty operator).
    #[error("{0}")]
    Csg(#[from] CsgError),
}

/// Where the camera is and what it looks at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    /// The eye point.
    pub eye: DVec3,
    /// The point at the centre of the image.
    pub look_at: DVec3,
    /// Which way is up in the image (default +z).
    pub up: DVec3,
    /// The vertical field of view in degrees (default 40).
    pub fov_deg: f64,
}

/// The light of a Lambert-shaded image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSpec {
    /// A light at infinity in `direction` (from the scene towards the
    /// light).
    Directional {
        /// Towards the light.
        direction: DVec3,
        /// Ambient fraction in `[0, 1]`.
        ambient: f64,
    },
    /// A point light.
    Point {
        /// Where it is.
        position: DVec3,
        /// Ambient fraction in `[0, 1]`.
        ambient: f64,
    },
}

/// The default ambient fraction of a light.
pub const DEFAULT_AMBIENT: f64 = 0.15;

/// A loaded scene.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The solid.
    pub csg: Csg,
    /// The camera, if the file gives one.
    pub camera: Option<CameraSpec>,
    /// The light, if the file gives one.
    pub light: Option<LightSpec>,
    /// Whether images cast shadow rays.
    pub shadows: bool,
}

const TOP_KEYS: &str = "root, camera, light, shadows";
const NODE_KEYS: &str = "one of mesh, halfspace, box, sphere, cylinder, union, intersection, difference, or transform with child";

impl Scene {
    /// Reads a scene file; mesh paths are relative to its folder.
    ///
    /// # Errors
    ///
    /// [`SceneError`] naming the file, the JSON position or the JSON path.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|source| SceneError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        Scene::from_json(&text, &path.display().to_string(), base)
    }

    /// Parses scene text; `name` names it in messages and mesh paths are
    /// relative to `base`.
    ///
    /// # Errors
    ///
    /// As [`Scene::from_file`].
    pub fn from_json(text: &str, name: &str, base: &Path) -> Result<Scene, SceneError> {
        let value: Value = serde_json::from_str(text).map_err(|e| SceneError::Json {
            file: name.to_string(),
            line: e.line(),
            column: e.column(),
            message: e.to_string(),
        })?;
        let top = object(&value, "scene")?;
        check_keys(
            top,
            "scene",
            &["root", "camera", "light", "shadows"],
            TOP_KEYS,
        )?;
        let root = top.get("root").ok_or_else(|| SceneError::Value {
            at: "scene".into(),
            message: "missing \"root\"".into(),
        })?;
        let reader = Reader { base };
        let expr = reader.node(root, "root")?;
        let camera = top.get("camera").map(|v| camera(v, "camera")).transpose()?;
        let light = top.get("light").map(|v| light(v, "light")).transpose()?;
        let shadows = match top.get("shadows") {
            None => false,
            Some(Value::Bool(b)) => *b,
            Some(other) => return Err(bad("shadows", "a boolean", other)),
        };
        Ok(Scene {
            csg: Csg::try_new(expr)?,
            camera,
            light,
            shadows,
        })
    }
}

struct Reader<'a> {
    base: &'a Path,
}

impl Reader<'_> {
    fn node(&self, value: &Value, at: &str) -> Result<CsgExpr, SceneError> {
        let obj = object(value, at)?;
        if obj.contains_key("transform") {
            check_keys(obj, at, &["transform", "child"], "transform and child")?;
            let transform = transform(&obj["transform"], &format!("{at}.transform"))?;
            let child = obj.get("child").ok_or_else(|| SceneError::Value {
                at: at.to_string(),
                message: "transform without \"child\"".into(),
            })?;
            let child = self.node(child, &format!("{at}.child"))?;
            return Ok(child.transformed(transform));
        }
        let mut entries = obj.iter();
        let (key, body) = match (entries.next(), entries.next()) {
            (Some(entry), None) => entry,
            (None, _) => {
                return Err(SceneError::Value {
                    at: at.to_string(),
                    message: format!("empty node; expected {NODE_KEYS}"),
                });
            }
            (Some(_), Some((second, _))) => {
                return Err(SceneError::UnknownKey {
                    at: at.to_string(),
                    key: second.clone(),
                    expected: NODE_KEYS,
                });
            }
        };
        let here = format!("{at}.{key}");
        let leaf = |p: Arc<dyn Primitive>| CsgExpr::Leaf {
            primitive: p,
            label: here.clone(),
        };
        match key.as_str() {
            "union" | "intersection" | "difference" => {
                let Value::Array(items) = body else {
                    return Err(bad(&here, "an array of nodes", body));
                };
                let minimum = if key == "difference" { 2 } else { 1 };
                if items.len() < minimum {
                    return Err(SceneError::Value {
                        at: here,
                        message: format!("needs at least {minimum} node(s), found {}", items.len()),
                    });
                }
                let kids = items
                    .iter()
                    .enumerate()
                    .map(|(i, v)| self.node(v, &format!("{here}[{i}]")))
                    .collect::<Result<Vec<_>, _>>()?;
                Ok(match key.as_str() {
                    "union" => CsgExpr::Union(kids),
                    "intersection" => CsgExpr::Intersection(kids),
                    _ => CsgExpr::Difference(kids),
                })
            }
            "halfspace" => {
                let o = fields(body, &here, &["point", "normal"], "point, normal")?;
                let point = vec3(req(o, &here, "point")?, &format!("{here}.point"))?;
                let n_at = format!("{here}.normal");
                let normal = vec3(req(o, &here, "normal")?, &n_at)?;
                let h = HalfSpace::try_new(point, normal).map_err(|e| SceneError::Value {
                    at: n_at,
                    message: e.to_string(),
                })?;
                Ok(leaf(Arc::new(h)))
            }
            "box" => {
                let o = fields(body, &here, &["min", "max"], "min, max")?;
                let min = vec3(req(o, &here, "min")?, &format!("{here}.min"))?;
                let max_at = format!("{here}.max");
                let max = vec3(req(o, &here, "max")?, &max_at)?;
                let b = AxisBox::try_new(min, max).map_err(|e| SceneError::Value {
                    at: max_at,
                    message: e.to_string(),
                })?;
                Ok(leaf(Arc::new(b)))
            }
            "sphere" => {
                let o = fields(body, &here, &["center", "radius"], "center, radius")?;
                let center = vec3(req(o, &here, "center")?, &format!("{here}.center"))?;
                let r_at = format!("{here}.radius");
                let radius = positive(req(o, &here, "radius")?, &r_at)?;
                let s = Sphere::try_new(center, radius).map_err(|e| SceneError::Value {
                    at: r_at,
                    message: e.to_string(),
                })?;
                Ok(leaf(Arc::new(s)))
            }
            "cylinder" => {
                let o = fields(
                    body,
                    &here,
                    &["base", "axis", "radius"],
                    "base, axis, radius",
                )?;
                let base = vec3(req(o, &here, "base")?, &format!("{here}.base"))?;
                let a_at = format!("{here}.axis");
                let axis = vec3(req(o, &here, "axis")?, &a_at)?;
                if axis == DVec3::ZERO {
                    return Err(SceneError::Value {
                        at: a_at,
                        message: "the axis must not be zero".into(),
                    });
                }
                let radius = positive(req(o, &here, "radius")?, &format!("{here}.radius"))?;
                let c = Cylinder::try_new(base, axis, radius).map_err(|e| SceneError::Value {
                    at: here.clone(),
                    message: e.to_string(),
                })?;
                Ok(leaf(Arc::new(c)))
            }
            "mesh" => {
                let Value::String(relative) = body else {
                    return Err(bad(&here, "a file path (string)", body));
                };
                let file = self.base.join(relative);
                let primitive = load_mesh(&file).map_err(|message| SceneError::Mesh {
                    at: here.clone(),
                    file,
                    message,
                })?;
                Ok(leaf(primitive))
            }
            _ => Err(SceneError::UnknownKey {
                at: at.to_string(),
                key: key.clone(),
                expected: NODE_KEYS,
            }),
        }
    }
}

/// How many violations a refused mesh's message lists.
const VIOLATIONS_SHOWN: usize = 5;

/// Loads a mesh leaf: imports the OBJ file, validates it (the default
/// options of the validation layer) and refuses it with the validator's
/// verdict and first violations unless it is a valid closed solid.
fn load_mesh(file: &Path) -> Result<Arc<dyn Primitive>, String> {
    let import = crate::io::import_obj(file, &crate::io::ObjOptions::default())
        .map_err(|e| e.to_string())?;
    let (report, solid) =
        crate::validate::validate_and_build(&import, &crate::validate::Options::default())
            .map_err(|e| e.to_string())?;
    match solid {
        Some(solid) if report.is_valid() => Polyhedron::try_new(solid)
            .map(|p| Arc::new(p) as Arc<dyn Primitive>)
            .map_err(|e| e.to_string()),
        _ => {
            let mut message = format!(
                "not a valid closed solid ({}); {} violation(s)",
                report.validity.describe(),
                report.violations.len()
            );
            for v in report.violations.iter().take(VIOLATIONS_SHOWN) {
                message.push_str(&format!("\n  {}: {}", v.rule, v.message));
            }
            Err(message)
        }
    }
}

fn transform(value: &Value, at: &str) -> Result<DAffine3, SceneError> {
    let o = fields(
        value,
        at,
        &["translate", "rotate_deg", "scale"],
        "translate, rotate_deg, scale",
    )?;
    let translate = o
        .get("translate")
        .map(|v| vec3(v, &format!("{at}.translate")))
        .transpose()?
        .unwrap_or(DVec3::ZERO);
    let rotate = o
        .get("rotate_deg")
        .map(|v| vec3(v, &format!("{at}.rotate_deg")))
        .transpose()?
        .unwrap_or(DVec3::ZERO);
    let s_at = format!("{at}.scale");
    let scale = o
        .get("scale")
        .map(|v| vec3(v, &s_at))
        .transpose()?
        .unwrap_or(DVec3::ONE);
    if scale.cmpeq(DVec3::ZERO).any() {
        return Err(SceneError::Value {
            at: s_at,
            message: format!("scale {scale:?} has a zero component: the solid would be flat"),
        });
    }
    let r = rotate * (std::f64::consts::PI / 180.0);
    // Intrinsic ZYX equals rotating about x first, then y, then z.
    let rotation = DQuat::from_euler(EulerRot::ZYX, r.z, r.y, r.x);
    Ok(DAffine3::from_scale_rotation_translation(
        scale, rotation, translate,
    ))
}

fn camera(value: &Value, at: &str) -> Result<CameraSpec, SceneError> {
    let o = fields(
        value,
        at,
        &["eye", "look_at", "up", "fov_deg"],
        "eye, look_at, up, fov_deg",
    )?;
    let eye = vec3(req(o, at, "eye")?, &format!("{at}.eye"))?;
    let look_at = vec3(req(o, at, "look_at")?, &format!("{at}.look_at"))?;
    if eye == look_at {
        return Err(SceneError::Value {
            at: format!("{at}.look_at"),
            message: "the camera looks at its own eye point".into(),
        });
    }
    let up = o
        .get("up")
        .map(|v| vec3(v, &format!("{at}.up")))
        .transpose()?
        .unwrap_or(DVec3::Z);
    let fov_at = format!("{at}.fov_deg");
    let fov_deg = o
        .get("fov_deg")
        .map(|v| positive(v, &fov_at))
        .transpose()?
        .unwrap_or(40.0);
    if fov_deg >= 180.0 {
        return Err(SceneError::Value {
            at: fov_at,
            message: format!("field of view {fov_deg} must be below 180 degrees"),
        });
    }
    let forward = look_at - eye;
    if up == DVec3::ZERO || forward.cross(up) == DVec3::ZERO {
        return Err(SceneError::Value {
            at: format!("{at}.up"),
            message: "up must not be zero or parallel to the view direction".into(),
        });
    }
    Ok(CameraSpec {
        eye,
        look_at,
        up,
        fov_deg,
    })
}

fn light(value: &Value, at: &str) -> Result<LightSpec, SceneError> {
    let o = fields(
        value,
        at,
        &["direction", "position", "ambient"],
        "direction or position, ambient",
    )?;
    let a_at = format!("{at}.ambient");
    let ambient = match o.get("ambient") {
        None => DEFAULT_AMBIENT,
        Some(v) => match v.as_f64() {
            Some(a) if (0.0..=1.0).contains(&a) => a,
            _ => return Err(bad(&a_at, "a number from 0 to 1", v)),
        },
    };
    match (o.get("direction"), o.get("position")) {
        (Some(d), None) => {
            let d_at = format!("{at}.direction");
            let direction = vec3(d, &d_at)?;
            if direction == DVec3::ZERO {
                return Err(SceneError::Value {
                    at: d_at,
                    message: "the light direction must not be zero".into(),
                });
            }
            Ok(LightSpec::Directional { direction, ambient })
        }
        (None, Some(p)) => Ok(LightSpec::Point {
            position: vec3(p, &format!("{at}.position"))?,
            ambient,
        }),
        _ => Err(SceneError::Value {
            at: at.to_string(),
            message: "give exactly one of \"direction\" and \"position\"".into(),
        }),
    }
}

fn object<'v>(value: &'v Value, at: &str) -> Result<&'v Map<String, Value>, SceneError> {
    value.as_object().ok_or_else(|| bad(at, "an object", value))
}

fn fields<'v>(
    value: &'v Value,
    at: &str,
    allowed: &[&str],
    expected: &'static str,
) -> Result<&'v Map<String, Value>, SceneError> {
    let o = object(value, at)?;
    check_keys(o, at, allowed, expected)?;
    Ok(o)
}

fn check_keys(
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

fn req<'v>(o: &'v Map<String, Value>, at: &str, key: &str) -> Result<&'v Value, SceneError> {
    o.get(key).ok_or_else(|| SceneError::Value {
        at: format!("{at}.{key}"),
        message: "missing".into(),
    })
}

fn bad(at: &str, expected: &str, found: &Value) -> SceneError {
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

fn number(value: &Value, at: &str) -> Result<f64, SceneError> {
    match value.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        _ => Err(bad(at, "a finite number", value)),
    }
}

fn positive(value: &Value, at: &str) -> Result<f64, SceneError> {
    match number(value, at) {
        Ok(x) if x > 0.0 => Ok(x),
        _ => Err(bad(at, "a positive number", value)),
    }
}

fn vec3(value: &Value, at: &str) -> Result<DVec3, SceneError> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csg::{Containment, Stats};

    fn parse(text: &str) -> Result<Scene, SceneError> {
        Scene::from_json(text, "test.json", Path::new("."))
    }

    fn error(text: &str) -> String {
        parse(text).map(|_| ()).unwrap_err().to_string()
    }

    #[test]
    fn a_full_scene_parses() {
        let scene = parse(
            r#"{"root": {"difference": [
                    {"box": {"min": [-1,-1,-1], "max": [1,1,1]}},
                    {"sphere": {"center": [0,0,0], "radius": 1.2}},
                    {"transform": {"translate": [0,0,5], "rotate_deg": [0,90,0], "scale": [1,1,2]},
                     "child": {"cylinder": {"base": [0,0,0], "axis": [0,0,1], "radius": 0.1}}},
                    {"intersection": [{"halfspace": {"point": [0,0,0], "normal": [0,0,1]}},
                                      {"union": [{"box": {"min": [5,5,5], "max": [6,6,6]}}]}]}]},
                "camera": {"eye": [5,-5,4], "look_at": [0,0,0]},
                "light": {"direction": [1,-1,2], "ambient": 0.2},
                "shadows": true}"#,
        )
        .unwrap();
        assert!(scene.shadows);
        assert_eq!(scene.csg.leaves().len(), 5);
        assert_eq!(scene.csg.leaves()[1].label, "root.difference[1].sphere");
        assert_eq!(scene.camera.unwrap().fov_deg, 40.0);
        let mut stats = Stats::default();
        // The box corner is outside the sphere of radius 1.2.
        assert_eq!(
            scene.csg.classify_point(DVec3::splat(0.95), &mut stats),
            Containment::Inside
        );
        assert_eq!(
            scene.csg.classify_point(DVec3::ZERO, &mut stats),
            Containment::Outside
        );
    }

    #[test]
    fn errors_name_the_json_path() {
        assert_eq!(
            error(
                r#"{"root": {"difference": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"sphere": {"center": [0,0,0], "radius": -1}}]}}"#
            ),
            "root.difference[1].sphere.radius: expected a positive number, found -1"
        );
        assert_eq!(
            error(r#"{"root": {"sphere": {"center": [0,0,0], "radius": 1, "color": "red"}}}"#),
            "root.sphere: unknown key \"color\" (expected center, radius)"
        );
        assert!(error(r#"{"root": {"cube": {}}}"#).starts_with("root: unknown key \"cube\""));
        assert_eq!(
            error(r#"{"root": {"box": {"min": [0,0,"a"], "max": [1,1,1]}}}"#),
            "root.box.min[2]: expected a finite number, found \"a\""
        );
        assert_eq!(
            error(r#"{"root": {"box": {"min": [0,0,0], "max": [1,1,1]}}, "lights": 1}"#),
            "scene: unknown key \"lights\" (expected root, camera, light, shadows)"
        );
        assert!(
            error(r#"{"root": {"difference": [{"box": {"min": [0,0,0], "max": [1,1,1]}}]}}"#)
                .starts_with("root.difference: needs at least 2")
        );
        assert!(error(r#"{"root": {"transform": {"scale": [1,0,1]}, "child": {"sphere": {"center": [0,0,0], "radius": 1}}}}"#)
            .starts_with("root.transform.scale: "));
        assert!(
            error(r#"{"root": {"box": {"min": [0,0,0], "max": [1,1,1]}}, "shadows": "yes"}"#)
                .starts_with("shadows: expected a boolean")
        );
        assert!(error("{\"root\": \n [1,").starts_with("test.json: line 2"));
        assert!(error(r#"{"camera": {}}"#).contains("missing \"root\""));
        assert!(
            error(r#"{"root": {"box": {"min": [1,0,0], "max": [0,1,1]}}}"#)
                .starts_with("root.box.max: ")
        );
        assert!(
            error(r#"{"root": {"halfspace": {"point": [0,0,0], "normal": [0,0,0]}}}"#)
                .starts_with("root.halfspace.normal: ")
        );
        assert!(error(r#"{"root": {"mesh": "nowhere.obj"}}"#).starts_with("root.mesh: mesh "));
        // A long value is cut at a character boundary, not inside one
        // (byte 57 falls inside an `é` here).
        let long = format!(
            r#"{{"root": {{"sphere": {{"center": [0,0,0], "radius": "a{}"}}}}}}"#,
            "é".repeat(40)
        );
        let message = error(&long);
        assert!(message.ends_with("éé..."), "{message}");
    }
}
