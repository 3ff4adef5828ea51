//! What a CSG command works on: a scene file, or a single mesh.

use std::path::Path;

use wingedge::csg::{Scene, SceneError};

/// Whether TARGET names a scene file (`.json`) rather than a mesh.
pub fn is_scene(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// Loads TARGET as a scene (`.json`) or as a one-leaf scene of a mesh.
pub fn load(path: &Path) -> Result<Scene, String> {
    if is_scene(path) {
        return Scene::from_file(path).map_err(|e| e.to_string());
    }
    // A mesh is the scene {"root": {"mesh": PATH}}; its errors are about
    // the mesh file, not about a scene the user never wrote.
    let text = serde_json::json!({ "root": { "mesh": path } }).to_string();
    Scene::from_json(&text, &path.display().to_string(), Path::new("")).map_err(|e| match e {
        SceneError::Mesh { file, message, .. } => {
            let file = file.display().to_string();
            if message.starts_with(&file) {
                message
            } else {
                format!("{file}: {message}")
            }
        }
        other => other.to_string(),
    })
}
