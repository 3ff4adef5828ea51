//! The error of `io::import`: an OBJ file's own error as it
//! always was, and for every other format the file and the place in it
//! (line, byte offset, element, XML or JSON path).

use std::path::{Path, PathBuf};

use glam::DVec3;
use thiserror::Error;

use super::format::Format;
use super::location::{At, Location};
use super::obj::ObjError;

/// Why a mesh file could not be read. Every variant names the file; every
/// defect that sits somewhere names the place.
#[derive(Debug, Error)]
pub enum ImportError {
    /// An OBJ file's error, unchanged.
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The path names a directory.
    #[error("{}: is a directory, not a mesh file", .path.display())]
    Directory {
        /// The path.
        path: PathBuf,
    },
    /// The path names something other than a regular file (a device, a
    /// pipe), which a binary format is not read from.
    #[error("{}: is not a regular file ({format} files are read only from regular files)", .path.display())]
    NotAFile {
        /// The path.
        path: PathBuf,
        /// The format it was to be read as.
        format: Format,
    },
    /// The file holds no faces.
    #[error("{}: holds no faces ({format} file with no triangles or polygons)", .path.display())]
    Empty {
        /// The file.
        path: PathBuf,
        /// Its format.
        format: Format,
    },
    /// The content does not follow the format.
    #[error("{}: {message}", At(.path, .at))]
    Malformed {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is wrong.
        message: String,
    },
    /// The data ends before what the file declares.
    #[error("{}: the file ends after {size} bytes, but {what} needs {needed} bytes (truncated, or a count that lies)", At(.path, .at))]
    Truncated {
        /// The file.
        path: PathBuf,
        /// Where the declaration is.
        at: Location,
        /// What was declared (`the header's 1000000000 triangles`).
        what: String,
        /// The bytes it needs, from the start of the file (or part).
        needed: u64,
        /// The bytes there are.
        size: u64,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("{}: vertex {vertex} has a non-finite coordinate {}", At(.path, .at), crate::geom::ReadableVec(*.position))]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// The vertex (0-based, as the format counts; for STL the corner).
        vertex: usize,
        /// Its position as read.
        position: DVec3,
    },
    /// A face naming a vertex that does not exist.
    #[error("{}: vertex index {index} is out of range: {available} vertices are defined", At(.path, .at))]
    IndexOutOfRange {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// The index as written.
        index: i64,
        /// How many vertices it could have named.
        available: usize,
    },
    /// A face with fewer than three corners.
    #[error("{}: a face needs at least 3 corners, this one has {count}", At(.path, .at))]
    TooFewCorners {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// How many it has.
        count: usize,
    },
    /// A face with more corners than the limit.
    #[error("{}: a face with {count} corners exceeds the limit of {limit} corners per face (checking a face costs time quadratic in its corners; raise the limit with --max-face-corners or ImportOptions::max_face_corners)", At(.path, .at))]
    FaceTooLarge {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// How many corners it has.
        count: usize,
        /// The limit in force.
        limit: usize,
    },
    /// A size beyond a limit of the reader (a zip entry that inflates too
    /// far, too many triangles instantiated, a buffer too large).
    #[error("{}: {what} exceeds the limit of {limit} (refused before reading it)", At(.path, .at))]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// Where.
        at: Location,
        /// What is too large, with its size.
        what: String,
        /// The limit.
        limit: u64,
    },
}

impl ImportError {
    /// The place in the file, when the error has one.
    #[must_use]
    pub fn location(&self) -> Option<Location> {
        match self {
            ImportError::Obj(e) => e.line().map(Location::Line),
            ImportError::Malformed { at, .. }
            | ImportError::Truncated { at, .. }
            | ImportError::NonFinite { at, .. }
            | ImportError::IndexOutOfRange { at, .. }
            | ImportError::TooFewCorners { at, .. }
            | ImportError::FaceTooLarge { at, .. }
            | ImportError::TooLarge { at, .. } => Some(at.clone()),
            ImportError::Io { .. }
            | ImportError::Directory { .. }
            | ImportError::NotAFile { .. }
            | ImportError::Empty { .. } => None,
        }
    }

    /// The line the error sits on, for the text formats.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self.location() {
            Some(Location::Line(line)) => Some(line),
            _ => None,
        }
    }

    /// A [`ImportError::Malformed`].
    pub(crate) fn malformed(path: &Path, at: Location, message: impl Into<String>) -> ImportError {
        ImportError::Malformed {
            path: path.to_path_buf(),
            at,
            message: message.into(),
        }
    }
}

/// A short, escaped excerpt of input for a message: at most 40
/// characters, control characters and quotes escaped.
pub(crate) fn excerpt(bytes: &[u8]) -> String {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(160)]);
    let mut out: String = text.chars().take(40).flat_map(char::escape_debug).collect();
    if text.chars().count() > 40 || bytes.len() > 160 {
        out.push('…');
    }
    out
}
