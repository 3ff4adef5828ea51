//! A loaded scene and the ways to load one: a scene file, scene text, or
//! a path that is either a scene file or an OBJ mesh.

use std::path::Path;

use serde_json::{Map, Value};

use super::SceneError;
use super::error::in_file;
use super::json::{bad, object, parse_json};
use super::mesh_leaf::{is_scene_path, load_mesh};
use super::reader::{ReadState, Reader, read_scene_file};
use super::view::{CameraSpec, LightSpec, camera, light};
use crate::csg::{Csg, CsgExpr};

/// A loaded scene: a CSG tree and how to picture it.
///
/// # Invariants
///
/// Every mesh leaf of `csg` was validated as a closed solid; a camera or
/// light read from a file meets the invariants of [`CameraSpec`] and
/// [`LightSpec`].
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

impl Scene {
    /// Reads a scene file; mesh paths are relative to its folder, and
    /// leaves must resolve inside its folder or the working directory (see
    /// the module's path policy).
    ///
    /// # Errors
    ///
    /// [`SceneError`] naming the file, the JSON position or the JSON path.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_file_with(path, &crate::io::ImportOptions::default())
    }

    /// [`Scene::from_file`], leaves also allowed inside
    /// `options.allowed_roots` (the other options are for mesh files read
    /// directly: each leaf is read as its node says).
    ///
    /// # Errors
    ///
    /// As [`Scene::from_file`].
    pub fn from_file_with(
        path: &Path,
        options: &crate::io::ImportOptions,
    ) -> Result<Scene, SceneError> {
        let state = ReadState::new(&options.allowed_roots, options.resolve_leaves);
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
        Scene::from_json_with(text, name, base, &crate::io::ImportOptions::default())
    }

    /// [`Scene::from_json`], leaves also allowed inside
    /// `options.allowed_roots` (besides `base` and the working directory).
    ///
    /// # Errors
    ///
    /// As [`Scene::from_json`].
    pub fn from_json_with(
        text: &str,
        name: &str,
        base: &Path,
        options: &crate::io::ImportOptions,
    ) -> Result<Scene, SceneError> {
        let state = ReadState::new(&options.allowed_roots, options.resolve_leaves);
        let value = parse_json(text, name)?;
        let reader = Reader {
            base,
            state: &state,
            files: Vec::new(),
        };
        let (top, root) = reader.top(&value, 0)?;
        Scene::assemble(top, root)
    }

    /// A scene file (`.json`, see [`is_scene_path`]), or a mesh file as the
    /// scene `{"root": {"mesh": PATH}}`: imported, validated and refused
    /// unless it is a valid closed solid, as a scene's mesh leaf is.
    ///
    /// # Errors
    ///
    /// As [`Scene::from_file`] for a scene; for a mesh,
    /// [`SceneError::MeshFile`] naming the mesh file (not a scene the user
    /// never wrote).
    pub fn from_path(path: &Path) -> Result<Scene, SceneError> {
        Scene::from_path_with(path, &crate::io::ImportOptions::default())
    }

    /// [`Scene::from_path`], a mesh read as `options` say (its format
    /// given, say); with a format given, a `.json` path is read as a mesh;
    /// a scene's leaves also allowed inside `options.allowed_roots`.
    ///
    /// # Errors
    ///
    /// As [`Scene::from_path`].
    pub fn from_path_with(
        path: &Path,
        options: &crate::io::ImportOptions,
    ) -> Result<Scene, SceneError> {
        if is_scene_path(path) && options.format.is_none() {
            return Scene::from_file_with(path, options);
        }
        let primitive = load_mesh(path, options).map_err(|message| SceneError::MeshFile {
            file: path.to_path_buf(),
            message,
        })?;
        let root = CsgExpr::Leaf {
            primitive,
            label: "root.mesh".into(),
        };
        Ok(Scene {
            csg: Csg::try_new(root)?,
            camera: None,
            light: None,
            shadows: false,
        })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csg::{Containment, Stats};
    use crate::scene::{MAX_INCLUDE_DEPTH, MAX_JSON_DEPTH};
    use glam::DVec3;
    use std::path::PathBuf;

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
    fn a_key_twice_is_refused_with_its_object_and_key() {
        // serde_json keeps the last of two equal keys silently: the box
        // below read as min [0,0,0] without a word.
        assert_eq!(
            error(r#"{"root": {"box": {"min": [5,5,5], "max": [1,1,1], "min": [0,0,0]}}}"#),
            "test.json: root.box: key \"min\" appears twice"
        );
        assert_eq!(
            error(
                r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"sphere": {"center": [0,0,0], "radius": 1, "radius": 2}}]}}"#
            ),
            "test.json: root.union[1].sphere: key \"radius\" appears twice"
        );
        assert_eq!(
            error(&format!(r#"{{"root": {BOX}, "root": {BOX}}}"#)),
            "test.json: scene: key \"root\" appears twice"
        );
        // Equal after unescaping; quoted escaped.
        assert_eq!(
            error(r#"{"root": {"box": {"min": [0,0,0], "m\u0061x": [1,1,1], "max": [1,1,1]}}}"#),
            "test.json: root.box: key \"max\" appears twice"
        );
        // Equal keys in different objects are fine.
        assert!(parse(r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"box": {"min": [2,0,0], "max": [3,1,1]}}]}}"#).is_ok());
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

    #[test]
    fn a_path_is_a_scene_or_a_mesh_as_a_one_leaf_scene() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let scene = Scene::from_path(&root.join("fixtures/scenes/drilled_cube.json")).unwrap();
        assert!(scene.csg.leaves().len() > 1);
        assert!(scene.shadows);
        let mesh = Scene::from_path(&root.join("fixtures/valid/cube.obj")).unwrap();
        assert_eq!(mesh.csg.leaves().len(), 1);
        assert_eq!(mesh.csg.leaves()[0].label, "root.mesh");
        assert_eq!(
            mesh.csg
                .single_leaf()
                .and_then(|l| l.primitive.exact_volume()),
            Some(8.0)
        );
        assert!(mesh.camera.is_none() && mesh.light.is_none() && !mesh.shadows);

        // A defective mesh is refused with the validator's verdict, naming
        // the mesh file once and no scene.
        let hole = root.join("tests/bad_inputs/hole.obj");
        let e = Scene::from_path(&hole).unwrap_err();
        assert!(matches!(e, SceneError::MeshFile { .. }), "{e}");
        let text = e.to_string();
        let file = hole.display().to_string();
        assert!(
            text.starts_with(&format!("{file}: not a valid closed solid")),
            "{text}"
        );
        // The reader's message already names the file: not repeated.
        let index_zero = root.join("tests/bad_inputs/index_zero.obj");
        let text = Scene::from_path(&index_zero).unwrap_err().to_string();
        let file = index_zero.display().to_string();
        assert!(text.starts_with(&format!("{file}:5: ")), "{text}");
        assert_eq!(text.matches(&file).count(), 1, "{text}");
    }
}
