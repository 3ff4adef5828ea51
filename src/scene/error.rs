//! Why a scene could not be loaded: every error names the scene file and
//! the JSON path (or the JSON position for text that is not JSON).

use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::csg::CsgError;
use crate::io::JsonError;

/// Why a scene could not be loaded.
#[derive(Debug, Error)]
pub enum SceneError {
    /// The file could not be read, is not JSON, or a value or key in it is
    /// refused (naming the file, the position or the JSON path).
    #[error(transparent)]
    Json(#[from] JsonError),
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
    /// An OBJ file loaded as a one-leaf scene ([`Scene::from_path`]) could
    /// not be read or is not a valid closed solid.
    ///
    /// [`Scene::from_path`]: super::Scene::from_path
    #[error("{}", mesh_file_text(.file, .message))]
    MeshFile {
        /// The mesh file.
        file: PathBuf,
        /// Why (the reader's message, or the validator's report).
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
    /// A leaf (mesh, field document or included scene) names a file that
    /// resolves, symbolic links followed, outside the scene file's folder,
    /// the working directory and every allowed folder.
    #[error("{at}: {} resolves to {}, outside the scene's folder and the working directory; a scene reads leaves only there unless a folder is allowed (--allow-path DIR; ImportOptions::allowed_roots; allow_paths in Python)", .file.display(), .resolved.display())]
    PathOutside {
        /// The JSON path of the leaf.
        at: String,
        /// The path as named, joined to the scene's folder.
        file: PathBuf,
        /// Where it resolves to.
        resolved: PathBuf,
    },
    /// A leaf names something other than a regular file (a directory, a
    /// FIFO, a device): refused before it is opened, so that reading never
    /// blocks.
    #[error("{at}: {} is a {kind}, not a regular file; scene leaves must be regular files", .file.display())]
    NotRegularFile {
        /// The JSON path of the leaf.
        at: String,
        /// The path as named, joined to the scene's folder.
        file: PathBuf,
        /// What it is instead.
        kind: &'static str,
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

/// `file: message`, or the message alone when it already starts with the
/// file (the OBJ reader's messages do).
fn mesh_file_text(file: &Path, message: &str) -> String {
    let file = file.display().to_string();
    if message.starts_with(&file) {
        message.to_string()
    } else {
        format!("{file}: {message}")
    }
}

/// Wraps an error found inside `file` so that it names the file (errors
/// that already do are returned as they are).
pub(super) fn in_file(file: &Path, error: SceneError) -> SceneError {
    match error {
        SceneError::Json(
            JsonError::Read { .. } | JsonError::Syntax { .. } | JsonError::DuplicateKey { .. },
        )
        | SceneError::InFile { .. }
        | SceneError::MeshFile { .. } => error,
        other => SceneError::InFile {
            file: file.to_path_buf(),
            source: Box::new(other),
        },
    }
}
