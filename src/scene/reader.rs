//! Reading scene files: the state all files of one scene share, the
//! top-level object, and included scene files (cycles refused, each file
//! read once).

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

use super::SceneError;
use super::error::in_file;
use super::json::{check_keys, object, parse_json};
use super::leaf_path::PathPolicy;
use super::limits::{IncludedSize, NodeBudget};
use super::mesh_leaf::MeshLeaves;
use crate::csg::CsgExpr;
use crate::io::JsonError;

const TOP_KEYS: &str = "root, camera, light, shadows";

/// What all the files of one scene share while being read: the node budget
/// and the meshes and scenes already loaded (by canonical path), so that a
/// file named many times is read once.
#[derive(Default)]
pub(super) struct ReadState {
    pub(super) budget: NodeBudget,
    pub(super) meshes: MeshLeaves,
    /// Where leaves may resolve.
    pub(super) paths: PathPolicy,
    scenes: RefCell<HashMap<PathBuf, IncludedScene>>,
}

impl ReadState {
    /// The state of a scene read with leaves allowed in `allowed_roots`
    /// (besides each scene file's folder and the working directory), mesh
    /// leaves that are no valid solid repaired when `resolve_leaves`.
    pub(super) fn new(allowed_roots: &[PathBuf], resolve_leaves: bool) -> ReadState {
        ReadState {
            paths: PathPolicy::new(allowed_roots),
            meshes: MeshLeaves::new(resolve_leaves),
            ..ReadState::default()
        }
    }
}

/// A scene file read once, for the next inclusions.
#[derive(Clone)]
struct IncludedScene {
    root: CsgExpr,
    size: IncludedSize,
}

/// Reads the nodes of one scene file (the nodes themselves: `node.rs`).
pub(super) struct Reader<'a> {
    /// The folder mesh and scene paths are relative to.
    pub(super) base: &'a Path,
    pub(super) state: &'a ReadState,
    /// Canonical paths of this file and the files including it, outermost
    /// first (empty for text without a file).
    pub(super) files: Vec<PathBuf>,
}

/// Reads a scene file's JSON and its tree, whose root is `depth` nodes
/// below the outermost root; `files` are the canonical paths of the files
/// including it, outermost first.
pub(super) fn read_scene_file(
    path: &Path,
    state: &ReadState,
    mut files: Vec<PathBuf>,
    depth: usize,
) -> Result<(Value, CsgExpr), SceneError> {
    let read_error = |source| {
        SceneError::Json(JsonError::Read {
            file: path.to_path_buf(),
            source,
        })
    };
    if std::fs::metadata(path).map_err(read_error)?.is_dir() {
        return Err(read_error(std::io::Error::other(
            "is a directory, not a scene file",
        )));
    }
    let bytes =
        crate::io::read_input_at_most(path, crate::io::MAX_JSON_BYTES).map_err(read_error)?;
    // The text ends at the first invalid UTF-8 or NUL byte (`read_input`
    // stops at a NUL): anything after it is binary data, named by position.
    let text_len = crate::io::text_len(&bytes);
    let valid = &bytes[..text_len];
    let line_start = valid.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
    let binary = SceneError::Json(JsonError::Syntax {
        file: path.display().to_string(),
        line: 1 + valid.iter().filter(|&&b| b == b'\n').count(),
        column: 1 + valid.len() - line_start,
        message: "binary data (not UTF-8 text)".into(),
    });
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

impl Reader<'_> {
    /// Checks the top-level keys and reads the tree under `root`, `depth`
    /// nodes below the outermost root.
    pub(super) fn top<'v>(
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
        let root = top.get("root").ok_or_else(|| {
            SceneError::Json(JsonError::Value {
                at: "scene".into(),
                message: "missing \"root\"".into(),
            })
        })?;
        Ok((top, self.node(root, "root", depth)?))
    }

    /// The file `relative` names for the leaf at `at`, when the path
    /// policy admits it (see `leaf_path.rs`).
    pub(super) fn leaf_file(&self, relative: &str, at: &str) -> Result<PathBuf, SceneError> {
        self.state.paths.admit(self.base, relative, at)
    }

    /// The root of the scene file `relative` names, included at `at` by a
    /// node `depth` deep; refused if the path policy refuses the file, or
    /// if it would include itself or nest too deep.
    pub(super) fn include(
        &self,
        relative: &str,
        at: &str,
        depth: usize,
    ) -> Result<CsgExpr, SceneError> {
        let file = &self.leaf_file(relative, at)?;
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
        NodeBudget::check_include_depth(at, self.files.len())?;
        let key = std::fs::canonicalize(file).unwrap_or_else(|_| file.to_path_buf());
        let cached = self.state.scenes.borrow().get(&key).cloned();
        if let Some(included) = cached {
            // Read before: count its nodes and depth again, without reading.
            self.state.budget.add_included(at, depth, included.size)?;
            return Ok(included.root);
        }
        // The included root sits one node below this one.
        let start = self.state.budget.start_include(depth + 1);
        let (_, root) =
            read_scene_file(file, self.state, self.files.clone(), depth + 1).map_err(|source| {
                SceneError::Include {
                    at: at.to_string(),
                    source: Box::new(source),
                }
            })?;
        let size = self.state.budget.end_include(start);
        self.state.scenes.borrow_mut().insert(
            key,
            IncludedScene {
                root: root.clone(),
                size,
            },
        );
        Ok(root)
    }
}
