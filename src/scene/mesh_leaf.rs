//! Mesh leaves: a mesh file (any format [`crate::io::import`] reads)
//! imported, validated and, only when it is a valid closed solid, made a
//! [`Polyhedron`] leaf; each file read once per scene.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::csg::{Polyhedron, Primitive};
use crate::io::{Format, ImportOptions, import};
use crate::repair::{RepairOptions, repair};
use crate::validate::{Options, validate_and_build};

/// How many violations a refused mesh's message lists.
const VIOLATIONS_SHOWN: usize = 5;

/// Whether `path` names a scene file (extension `.json`, any case) rather
/// than a mesh file.
#[must_use]
pub fn is_scene_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// A mesh leaf's canonical path and the format it is read as.
type LeafKey = (PathBuf, Option<Format>);

/// The mesh leaves of one scene, by canonical path, so that a mesh named
/// many times is read and validated once.
#[derive(Default)]
pub(super) struct MeshLeaves {
    loaded: RefCell<HashMap<LeafKey, Arc<dyn Primitive>>>,
    /// Whether a leaf that is no valid solid is repaired.
    resolve: bool,
}

impl MeshLeaves {
    /// No leaves loaded yet; those that are no valid solid are repaired
    /// when `resolve`.
    pub(super) fn new(resolve: bool) -> MeshLeaves {
        MeshLeaves {
            resolve,
            ..MeshLeaves::default()
        }
    }

    /// The leaf of `file`, read as `format` (`None`: by its extension),
    /// loaded on first use.
    ///
    /// # Errors
    ///
    /// A message saying why the file is not a usable mesh (a scene file,
    /// unreadable, or not a valid closed solid).
    pub(super) fn get(
        &self,
        file: &Path,
        format: Option<Format>,
    ) -> Result<Arc<dyn Primitive>, String> {
        if is_scene_path(file) && format.is_none() {
            return Err(
                "is a scene file (JSON), not an OBJ mesh; include it with {\"scene\": PATH}".into(),
            );
        }
        let key = (
            std::fs::canonicalize(file).unwrap_or_else(|_| file.to_path_buf()),
            format,
        );
        if let Some(p) = self.loaded.borrow().get(&key) {
            return Ok(Arc::clone(p));
        }
        let options = ImportOptions {
            format,
            resolve_leaves: self.resolve,
            ..ImportOptions::default()
        };
        let primitive = load_mesh(file, &options)?;
        self.loaded.borrow_mut().insert(key, Arc::clone(&primitive));
        Ok(primitive)
    }
}

/// Loads a mesh leaf: imports the mesh file, validates it (the default
/// options of the validation layer) and refuses it with the validator's
/// verdict and first violations unless it is a valid closed solid.
///
/// # Errors
///
/// The reader's message (naming the file and the place in it) or the
/// validator's verdict.
pub(super) fn load_mesh(
    file: &Path,
    options: &ImportOptions,
) -> Result<Arc<dyn Primitive>, String> {
    let import = import(file, options).map_err(|e| e.to_string())?;
    let (report, solid) =
        validate_and_build(&import, &Options::default()).map_err(|e| e.to_string())?;
    match solid {
        Some(solid) if report.is_valid() => Polyhedron::try_new(solid)
            .map(|p| Arc::new(p) as Arc<dyn Primitive>)
            .map_err(|e| e.to_string()),
        _ if options.resolve_leaves => {
            let repaired = repair(&import.soup, &RepairOptions::default())
                .map_err(|e| format!("not a valid closed solid, and repairing it failed: {e}"))?;
            let Some(solid) = repaired.solid else {
                return Err(format!(
                    "not a valid closed solid, and repairing it left {} hole(s) open",
                    repaired.report.left_open.len()
                ));
            };
            Polyhedron::try_new(solid)
                .map(|p| Arc::new(p) as Arc<dyn Primitive>)
                .map_err(|e| e.to_string())
        }
        _ => {
            let mut message = format!(
                "not a valid closed solid ({}); {} violation(s)",
                report.validity.describe(),
                report.violations.len()
            );
            for v in report.violations.iter().take(VIOLATIONS_SHOWN) {
                message.push_str(&format!("\n  {}: {}", v.rule, v.message));
            }
            message.push_str(
                "\n  (csg --resolve, ImportOptions::resolve_leaves, takes it by its winding number instead: `wingedge repair` shows what that changes)",
            );
            Err(message)
        }
    }
}
