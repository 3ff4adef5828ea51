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
//!       | {"scene": "relative/path.json"}       (the root of another scene file)
//! camera := {"eye": [x,y,z], "look_at": [x,y,z], "up": [x,y,z], "fov_deg": f}   (up, fov_deg optional)
//! light  := {"direction": [x,y,z]} | {"position": [x,y,z]}, plus optional "ambient": a in [0, 1]
//! ```
//!
//! A transform scales, then rotates (about x, then y, then z, in degrees),
//! then translates; each part is optional. Mesh paths are relative to the
//! scene file. Unknown keys and bad values are errors naming the JSON path,
//! e.g. `root.difference[1].sphere.radius`.
//!
//! # Limits
//!
//! Hostile files are refused quickly, with the limit named in the error:
//! JSON nested deeper than [`MAX_JSON_DEPTH`] (the JSON reader's own
//! limit), nodes nested deeper than [`MAX_NODE_DEPTH`] counting through
//! included files, more than [`MAX_NODES`] nodes in all (each inclusion
//! counted again), included files nested deeper than
//! [`MAX_INCLUDE_DEPTH`], and a file that includes itself, directly or
//! through others (paths compared after canonicalization). The camera,
//! light and shadows of an included scene are ignored; a mesh named twice
//! is read and validated once.

use std::cell::{Cell, RefCell};
use std::collections::HashMap;
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
    /// A limit of the scene format was exceeded: nodes nested too deep,
    /// too many nodes, or includes nested too deep (the error names which,
    /// where, and the limit).
    #[error("{at}: {what} exceeds the limit of {limit}")]
    Limit {
        /// The JSON path where the limit was crossed.
        at: String,
        /// What was counted.
        what: &'static str,
        /// The limit.
        limit: usize,
    },
    /// A scene file includes itself, directly or through other files.
    #[error("{at}: scene {} includes itself: {}", .chain.last().map_or(String::new(), |f| f.display().to_string()), chain_text(.chain))]
    IncludeCycle {
        /// The JSON path of the `scene` node that closes the cycle.
        at: String,
        /// The files of the cycle, from the first to the one included again.
        chain: Vec<PathBuf>,
    },
    /// An included scene file is unreadable or wrong.
    #[error("{at}: included scene: {source}")]
    Include {
        /// The JSON path of the `scene` node.
        at: String,
        /// What is wrong with the included file (naming it).
        source: Box<SceneError>,
    },
    /// An error inside a scene file, with the file it is in.
    #[error("{}: {source}", .file.display())]
    InFile {
        /// The scene file.
        file: PathBuf,
        /// The error, naming its JSON path.
        source: Box<SceneError>,
    },
    /// The tree is malformed (a singular transform, an empty operator).
    #[error("{0}")]
    Csg(#[from] CsgError),
}

fn chain_text(chain: &[PathBuf]) -> String {
    chain
        .iter()
        .map(|f| f.display().to_string())
        .collect::<Vec<_>>()
        .join(" → ")
}

/// How deep JSON may nest (arrays and objects); deeper text is refused by
/// the JSON reader before any node is read.
pub const MAX_JSON_DEPTH: usize = 128;
/// How deep nodes may nest, counting through included scene files (a node
/// per operator, transform or inclusion).
pub const MAX_NODE_DEPTH: usize = 256;
/// How many nodes a scene may have, counting included scenes once per
/// inclusion.
pub const MAX_NODES: usize = 1_000_000;
/// How deep scene files may include scene files.
pub const MAX_INCLUDE_DEPTH: usize = 16;

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
const NODE_KEYS: &str = "one of mesh, halfspace, box, sphere, cylinder, union, intersection, difference, scene, or transform with child";

impl Scene {
    /// Reads a scene file; mesh paths are relative to its folder.
    ///
    /// # Errors
    ///
    /// [`SceneError`] naming the file, the JSON position or the JSON path.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let state = ReadState::default();
        let (value, root) = read_scene_file(path, &state, Vec::new(), 0)?;
        object(&value, "scene")
            .and_then(|top| Scene::assemble(top, root))
            .map_err(|e| in_file(path, e))
    }

    /// Parses scene text; `name` names it in messages and mesh and scene
    /// paths are relative to `base`.
    ///
    /// # Errors
    ///
    /// As [`Scene::from_file`]; errors other than JSON syntax name the JSON
    /// path only (the text has no file).
    pub fn from_json(text: &str, name: &str, base: &Path) -> Result<Scene, SceneError> {
        let state = ReadState::default();
        let value = parse_json(text, name)?;
        let reader = Reader {
            base,
            state: &state,
            files: Vec::new(),
        };
        let (top, root) = reader.top(&value, 0)?;
        Scene::assemble(top, root)
    }

    /// The camera, light and shadows of a checked top-level object, and the
    /// tree.
    fn assemble(top: &Map<String, Value>, expr: CsgExpr) -> Result<Scene, SceneError> {
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

/// Parses JSON text, naming `name` and the position on failure.
fn parse_json(text: &str, name: &str) -> Result<Value, SceneError> {
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

/// Wraps an error found inside `file` so that it names the file (errors
/// that already do are returned as they are).
fn in_file(file: &Path, error: SceneError) -> SceneError {
    match error {
        SceneError::Read { .. } | SceneError::Json { .. } | SceneError::InFile { .. } => error,
        other => SceneError::InFile {
            file: file.to_path_buf(),
            source: Box::new(other),
        },
    }
}

/// Reads a scene file's JSON and its tree, whose root is
/// `depth` nodes below the outermost root; `files` are the canonical paths
/// of the files including it, outermost first.
fn read_scene_file(
    path: &Path,
    state: &ReadState,
    mut files: Vec<PathBuf>,
    depth: usize,
) -> Result<(Value, CsgExpr), SceneError> {
    let read_error = |source| SceneError::Read {
        file: path.to_path_buf(),
        source,
    };
    if std::fs::metadata(path).map_err(read_error)?.is_dir() {
        return Err(read_error(std::io::Error::other(
            "is a directory, not a scene file",
        )));
    }
    let bytes = crate::io::read_input(path).map_err(read_error)?;
    // The text ends at the first invalid UTF-8 or NUL byte (`read_input`
    // stops at a NUL): anything after it is binary data, named by position.
    let text_len = crate::io::text_len(&bytes);
    let valid = &bytes[..text_len];
    let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let binary = SceneError::Json {
        file: path.display().to_string(),
        line: 1 + valid.iter().filter(|&&b| b == b'\n').count(),
        column: 1 + valid.len() - line_start,
        message: "binary data (not UTF-8 text)".into(),
    };
    if text_len < bytes.len() {
        return Err(binary);
    }
    let text = String::from_utf8(bytes).map_err(|_| binary)?;
    files.push(std::fs::canonicalize(path).map_err(read_error)?);
    let value = parse_json(&text, &path.display().to_string())?;
    let reader = Reader {
        base: path.parent().unwrap_or(Path::new(".")),
        state,
        files,
    };
    let (_, root) = reader.top(&value, depth).map_err(|e| in_file(path, e))?;
    Ok((value, root))
}

/// What all the files of one scene share while being read: the node count
/// and the meshes and scenes already loaded (by canonical path), so that a
/// file named many times is read once.
#[derive(Default)]
struct ReadState {
    nodes: Cell<usize>,
    /// The deepest node depth reached since it was last reset.
    deepest: Cell<usize>,
    meshes: RefCell<HashMap<PathBuf, Arc<dyn Primitive>>>,
    scenes: RefCell<HashMap<PathBuf, IncludedScene>>,
}

/// A scene file read once, for the next inclusions.
#[derive(Clone)]
struct IncludedScene {
    root: CsgExpr,
    /// Scene nodes it was read from.
    nodes: usize,
    /// Levels of scene nodes below its root.
    height: usize,
}

/// Reads the nodes of one scene file.
struct Reader<'a> {
    /// The folder mesh and scene paths are relative to.
    base: &'a Path,
    state: &'a ReadState,
    /// Canonical paths of this file and the files including it, outermost
    /// first (empty for text without a file).
    files: Vec<PathBuf>,
}

impl Reader<'_> {
    /// Checks the top-level keys and reads the tree under `root`, `depth`
    /// nodes below the outermost root.
    fn top<'v>(
        &self,
        value: &'v Value,
        depth: usize,
    ) -> Result<(&'v Map<String, Value>, CsgExpr), SceneError> {
        let top = object(value, "scene")?;
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
        Ok((top, self.node(root, "root", depth)?))
    }

    /// Reads a node `depth` nodes below the outermost root.
    fn node(&self, value: &Value, at: &str, depth: usize) -> Result<CsgExpr, SceneError> {
        let limit = |what, limit| SceneError::Limit {
            at: at.to_string(),
            what,
            limit,
        };
        if depth >= MAX_NODE_DEPTH {
            return Err(limit(
                "node nesting (counting through included scenes)",
                MAX_NODE_DEPTH,
            ));
        }
        let count = self.state.nodes.get() + 1;
        if count > MAX_NODES {
            return Err(limit(
                "the number of nodes (counting included scenes)",
                MAX_NODES,
            ));
        }
        self.state.nodes.set(count);
        self.state.deepest.set(self.state.deepest.get().max(depth));
        let obj = object(value, at)?;
        if obj.contains_key("transform") {
            check_keys(obj, at, &["transform", "child"], "transform and child")?;
            let transform = transform(&obj["transform"], &format!("{at}.transform"))?;
            let child = obj.get("child").ok_or_else(|| SceneError::Value {
                at: at.to_string(),
                message: "transform without \"child\"".into(),
            })?;
            let child = self.node(child, &format!("{at}.child"), depth + 1)?;
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
                    .map(|(i, v)| self.node(v, &format!("{here}[{i}]"), depth + 1))
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
                let primitive = self.mesh(&file).map_err(|message| SceneError::Mesh {
                    at: here.clone(),
                    file,
                    message,
                })?;
                Ok(leaf(primitive))
            }
            "scene" => {
                let Value::String(relative) = body else {
                    return Err(bad(&here, "a scene file path (string)", body));
                };
                self.include(&self.base.join(relative), &here, depth)
            }
            _ => Err(SceneError::UnknownKey {
                at: at.to_string(),
                key: key.clone(),
                expected: NODE_KEYS,
            }),
        }
    }

    /// A mesh leaf, loaded once per canonical path.
    fn mesh(&self, file: &Path) -> Result<Arc<dyn Primitive>, String> {
        if file
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("json"))
        {
            return Err(
                "is a scene file (JSON), not an OBJ mesh; include it with {\"scene\": PATH}".into(),
            );
        }
        let key = std::fs::canonicalize(file).unwrap_or_else(|_| file.to_path_buf());
        if let Some(p) = self.state.meshes.borrow().get(&key) {
            return Ok(Arc::clone(p));
        }
        let primitive = load_mesh(file)?;
        self.state
            .meshes
            .borrow_mut()
            .insert(key, Arc::clone(&primitive));
        Ok(primitive)
    }

    /// The root of another scene file, refused if it would include itself
    /// or nest too deep.
    fn include(&self, file: &Path, at: &str, depth: usize) -> Result<CsgExpr, SceneError> {
        let include_error = |source| SceneError::Include {
            at: at.to_string(),
            source: Box::new(source),
        };
        if let Ok(canonical) = std::fs::canonicalize(file)
            && let Some(first) = self.files.iter().position(|f| *f == canonical)
        {
            let mut chain = self.files[first..].to_vec();
            chain.push(canonical);
            return Err(SceneError::IncludeCycle {
                at: at.to_string(),
                chain,
            });
        }
        if self.files.len() >= MAX_INCLUDE_DEPTH {
            return Err(SceneError::Limit {
                at: at.to_string(),
                what: "the nesting of included scene files",
                limit: MAX_INCLUDE_DEPTH,
            });
        }
        let key = std::fs::canonicalize(file).unwrap_or_else(|_| file.to_path_buf());
        let cached = self.state.scenes.borrow().get(&key).cloned();
        if let Some(included) = cached {
            // Read before: count its nodes and depth again, without reading.
            if depth + 1 + included.height >= MAX_NODE_DEPTH {
                return Err(SceneError::Limit {
                    at: at.to_string(),
                    what: "node nesting (counting through included scenes)",
                    limit: MAX_NODE_DEPTH,
                });
            }
            let count = self.state.nodes.get() + included.nodes;
            if count > MAX_NODES {
                return Err(SceneError::Limit {
                    at: at.to_string(),
                    what: "the number of nodes (counting included scenes)",
                    limit: MAX_NODES,
                });
            }
            self.state.nodes.set(count);
            return Ok(included.root);
        }
        let before = self.state.nodes.get();
        let deepest_before = self.state.deepest.replace(0);
        // The included root sits one node below this one.
        let (_, root) = read_scene_file(file, self.state, self.files.clone(), depth + 1)
            .map_err(include_error)?;
        let deepest = self.state.deepest.get();
        self.state.deepest.set(deepest.max(deepest_before));
        let included = IncludedScene {
            height: deepest - (depth + 1),
            nodes: self.state.nodes.get() - before,
            root: root.clone(),
        };
        self.state.scenes.borrow_mut().insert(key, included);
        Ok(root)
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
        assert!(error(r#"{"root": {"mesh": "other.json"}}"#).contains("is a scene file (JSON)"),);
        // A long value is cut at a character boundary, not inside one
        // (byte 57 falls inside an `é` here).
        let long = format!(
            r#"{{"root": {{"sphere": {{"center": [0,0,0], "radius": "a{}"}}}}}}"#,
            "é".repeat(40)
        );
        let message = error(&long);
        assert!(message.ends_with("éé..."), "{message}");
    }

    #[test]
    fn json_nested_too_deep_is_refused_by_the_reader() {
        let depth = 100_000;
        let text = format!(
            "{{\"root\": {}{{\"box\": {{\"min\": [0,0,0], \"max\": [1,1,1]}}}}{}}}",
            "{\"union\": [".repeat(depth),
            "]}".repeat(depth)
        );
        let e = error(&text);
        assert!(e.starts_with("test.json: line 1, column "), "{e}");
        assert!(
            e.ends_with("nested deeper than 128 levels (the limit)"),
            "{e}"
        );
        // Just under the reader's limit the tree is read (the top object,
        // two levels per union, three for the box).
        let depth = (MAX_JSON_DEPTH - 5) / 2;
        let text = format!(
            "{{\"root\": {}{{\"box\": {{\"min\": [0,0,0], \"max\": [1,1,1]}}}}{}}}",
            "{\"union\": [".repeat(depth),
            "]}".repeat(depth)
        );
        parse(&text).unwrap();
    }

    /// A scratch folder removed when dropped.
    struct Folder(PathBuf);

    impl Folder {
        fn new(name: &str) -> Folder {
            let dir = std::env::temp_dir()
                .join(format!("wingedge-scene-unit-{name}-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            Folder(dir)
        }

        fn write(&self, name: &str, text: &str) -> PathBuf {
            let path = self.0.join(name);
            std::fs::write(&path, text).unwrap();
            path
        }
    }

    impl Drop for Folder {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    const BOX: &str = r#"{"box": {"min": [0,0,0], "max": [1,1,1]}}"#;

    #[test]
    fn included_scenes_are_read_and_cycles_refused() {
        let dir = Folder::new("include");
        dir.write(
            "part.json",
            &format!(r#"{{"root": {BOX}, "shadows": true}}"#),
        );
        let whole = dir.write(
            "whole.json",
            r#"{"root": {"union": [{"scene": "part.json"}, {"transform": {"translate": [2,0,0]}, "child": {"scene": "part.json"}}]}}"#,
        );
        let scene = Scene::from_file(&whole).unwrap();
        assert_eq!(scene.csg.leaves().len(), 2);
        // The included scene's settings are ignored.
        assert!(!scene.shadows);

        let me = dir.write("me.json", r#"{"root": {"scene": "me.json"}}"#);
        let e = Scene::from_file(&me).unwrap_err();
        assert!(
            matches!(&e, SceneError::InFile { source, .. } if matches!(**source, SceneError::IncludeCycle { ref chain, .. } if chain.len() == 2)),
            "{e}"
        );
        assert!(e.to_string().contains("me.json: root.scene: scene "), "{e}");
        assert!(e.to_string().contains("includes itself"), "{e}");

        let a = dir.write(
            "a.json",
            &format!(r#"{{"root": {{"union": [{BOX}, {{"scene": "b.json"}}]}}}}"#),
        );
        dir.write("b.json", r#"{"root": {"scene": "./a.json"}}"#);
        let e = Scene::from_file(&a).unwrap_err().to_string();
        assert!(
            e.contains("a.json: root.union[1].scene: included scene: "),
            "{e}"
        );
        assert!(e.contains("b.json: root.scene: scene "), "{e}");
        assert!(e.contains("a.json → ") && e.contains("b.json → "), "{e}");

        let bad = dir.write("bad.json", r#"{"root": {"scene": "broken.json"}}"#);
        dir.write(
            "broken.json",
            r#"{"root": {"sphere": {"center": [0,0,0], "radius": -1}}}"#,
        );
        let e = Scene::from_file(&bad).unwrap_err().to_string();
        assert!(
            e.ends_with("broken.json: root.sphere.radius: expected a positive number, found -1"),
            "{e}"
        );
        assert!(e.contains("bad.json: root.scene: included scene: "), "{e}");
    }

    #[test]
    fn include_chains_and_node_counts_are_limited() {
        let dir = Folder::new("limits");
        let n = MAX_INCLUDE_DEPTH + 2;
        for i in 0..n {
            dir.write(
                &format!("chain{i}.json"),
                &format!(r#"{{"root": {{"scene": "chain{}.json"}}}}"#, i + 1),
            );
        }
        dir.write(&format!("chain{n}.json"), &format!(r#"{{"root": {BOX}}}"#));
        let e = Scene::from_file(&dir.0.join("chain0.json"))
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with("the nesting of included scene files exceeds the limit of 16"),
            "{e}"
        );
        // Each file names its part 10 times: 10^7 boxes from 8 small files.
        for i in 0..7 {
            let parts = vec![format!(r#"{{"scene": "fan{}.json"}}"#, i + 1); 10].join(", ");
            dir.write(
                &format!("fan{i}.json"),
                &format!(r#"{{"root": {{"union": [{parts}]}}}}"#),
            );
        }
        dir.write("fan7.json", &format!(r#"{{"root": {BOX}}}"#));
        let e = Scene::from_file(&dir.0.join("fan0.json"))
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with(
                "the number of nodes (counting included scenes) exceeds the limit of 1000000"
            ),
            "{e}"
        );
    }
}
