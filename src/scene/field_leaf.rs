//! Field leaves: a field document (inline or a file) meshed by marching
//! cubes into a validated [`Polyhedron`] leaf.

use std::path::PathBuf;
use std::sync::Arc;

use serde_json::Value;

use super::SceneError;
use crate::csg::{Polyhedron, Primitive};
use crate::field::{FieldError, MarchingOptions, read_document, try_mesh_solid};
use crate::io::JsonError;
use crate::validate::{Options, Validity, validate_soup};

/// The resolution of a field leaf whose document gives none.
pub const DEFAULT_FIELD_RESOLUTION: usize = 64;
/// The finest resolution a scene's field leaf may ask for (a scene may hold
/// many leaves; the command `wingedge mesh` allows finer grids).
pub const MAX_FIELD_RESOLUTION: usize = 256;

/// The leaf of `{"field": BODY}` at JSON path `at`: BODY is a field
/// document, or the path of a field document file, which `leaf_file`
/// resolves (and refuses where the path policy does).
///
/// # Errors
///
/// [`SceneError::Json`] naming the JSON path (inside the scene, or the
/// file and its own path), a resolution above [`MAX_FIELD_RESOLUTION`],
/// or an empty field; `leaf_file`'s refusal.
pub(super) fn field_leaf(
    body: &Value,
    at: &str,
    leaf_file: impl FnOnce(&str) -> Result<PathBuf, SceneError>,
) -> Result<Arc<dyn Primitive>, SceneError> {
    let doc = match body {
        Value::String(relative) => {
            let file = leaf_file(relative)?;
            crate::field::load_json(&file).map_err(|e| {
                value_error(
                    at,
                    match e {
                        JsonError::Read { .. }
                        | JsonError::Syntax { .. }
                        | JsonError::DuplicateKey { .. }
                        | JsonError::TooLarge { .. } => e.to_string(),
                        _ => format!("{}: {e}", file.display()),
                    },
                )
            })?
        }
        _ => read_document(body, at)?,
    };
    let resolution = doc.resolution.unwrap_or(DEFAULT_FIELD_RESOLUTION);
    if resolution > MAX_FIELD_RESOLUTION {
        return Err(value_error(
            &format!("{at}.resolution"),
            format!("resolution {resolution} is above the scene limit {MAX_FIELD_RESOLUTION}"),
        ));
    }
    let options = MarchingOptions {
        resolution,
        ..MarchingOptions::default()
    };
    let (solid, meshed) = try_mesh_solid(doc.field.as_ref(), &options).map_err(|e| match e {
        FieldError::Empty => value_error(
            at,
            format!("the field is below 1/2 at every sample (resolution {resolution}): the solid is empty"),
        ),
        other => value_error(at, other.to_string()),
    })?;
    let report = validate_soup(&meshed.soup, None, &Options::default())
        .map_err(|e| value_error(at, e.to_string()))?;
    if report.validity != Validity::ValidSolid {
        return Err(value_error(
            at,
            format!(
                "the meshed field is not a valid solid ({})",
                report.validity.describe()
            ),
        ));
    }
    Polyhedron::try_new(solid)
        .map(|p| Arc::new(p) as Arc<dyn Primitive>)
        .map_err(|e| value_error(at, e.to_string()))
}

fn value_error(at: &str, message: String) -> SceneError {
    SceneError::Json(JsonError::Value {
        at: at.to_string(),
        message,
    })
}
