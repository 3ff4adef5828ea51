//! The path policy of leaves: a file a scene names (a mesh leaf, a field
//! document, an included scene) is read only when it resolves, symbolic
//! links followed, inside the naming scene file's own folder, the working
//! directory or a folder the caller allows
//! ([`ImportOptions::allowed_roots`](crate::io::ImportOptions::allowed_roots)),
//! and only when it is a regular file (a FIFO would block the reader
//! forever, a device may never end).

use std::path::{Path, PathBuf};

use super::SceneError;

/// The folders a scene's leaves may resolve into, besides the naming
/// scene's own folder.
///
/// # Invariants
///
/// Every folder is canonical (absolute, symbolic links resolved); an
/// allowed folder that does not exist is left out (nothing can resolve
/// into it).
#[derive(Debug, Default)]
pub(super) struct PathPolicy {
    /// The working directory, when it can be resolved.
    working_dir: Option<PathBuf>,
    /// The folders the caller allows.
    allowed: Vec<PathBuf>,
}

impl PathPolicy {
    /// The policy with the working directory and `allowed` folders.
    pub(super) fn new(allowed: &[PathBuf]) -> PathPolicy {
        PathPolicy {
            working_dir: std::env::current_dir().and_then(std::fs::canonicalize).ok(),
            allowed: allowed
                .iter()
                .filter_map(|root| std::fs::canonicalize(root).ok())
                .collect(),
        }
    }

    /// The file `relative` names from the folder `base` (a scene file's
    /// folder) for the leaf at JSON path `at`, when the policy admits it.
    /// A path that does not resolve (no such file) is returned as joined,
    /// for the reader to report as unreadable.
    ///
    /// # Errors
    ///
    /// [`SceneError::PathOutside`] for a file outside every allowed
    /// folder; [`SceneError::NotRegularFile`] for a directory, a FIFO, a
    /// device or a socket.
    pub(super) fn admit(
        &self,
        base: &Path,
        relative: &str,
        at: &str,
    ) -> Result<PathBuf, SceneError> {
        let file = base.join(relative);
        let Ok(resolved) = std::fs::canonicalize(&file) else {
            return Ok(file);
        };
        // `Path::parent` of a bare file name is the empty path.
        let base = if base.as_os_str().is_empty() {
            Path::new(".")
        } else {
            base
        };
        let scene_dir = std::fs::canonicalize(base).ok();
        let inside = scene_dir
            .iter()
            .chain(&self.working_dir)
            .chain(&self.allowed)
            .any(|root| resolved.starts_with(root));
        if !inside {
            return Err(SceneError::PathOutside {
                at: at.to_string(),
                file,
                resolved,
            });
        }
        let kind = match std::fs::metadata(&resolved) {
            Ok(meta) if meta.is_file() => return Ok(file),
            Ok(meta) => file_kind(&meta.file_type()),
            // Unreadable metadata: the reader reports why.
            Err(_) => return Ok(file),
        };
        Err(SceneError::NotRegularFile {
            at: at.to_string(),
            file,
            kind,
        })
    }
}

/// What a file that is not a regular file is, in a word or two.
fn file_kind(kind: &std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "FIFO (named pipe)";
        }
        if kind.is_char_device() {
            return "character device";
        }
        if kind.is_block_device() {
            return "block device";
        }
        if kind.is_socket() {
            return "socket";
        }
    }
    if kind.is_dir() {
        "directory"
    } else {
        "special file"
    }
}
