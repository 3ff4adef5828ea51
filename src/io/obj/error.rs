//! The error of the OBJ reader: every variant names the file, every defect
//! that sits on a line names the line.

use std::path::PathBuf;

use glam::DVec3;
use thiserror::Error;

/// Why an OBJ file could not be read. Every variant names the file; every
/// defect that sits on a line names the line (1-based).
#[derive(Debug, Error)]
pub enum ObjError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The path names a directory.
    #[error("{}: is a directory, not an OBJ file", .path.display())]
    Directory {
        /// The path.
        path: PathBuf,
    },
    /// The file holds bytes that are not text (a NUL byte or invalid UTF-8).
    #[error("{}:{line}: binary data (not UTF-8 text); this is not an OBJ file", .path.display())]
    Binary {
        /// The file.
        path: PathBuf,
        /// The first line holding a non-text byte.
        line: usize,
    },
    /// The file holds vertices or polylines but no face. (A file with no
    /// element at all, only comments or nothing, is the empty solid.)
    #[error("{}: holds vertices but no faces (no `f` lines)", .path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// A face with fewer than three corners.
    #[error("{}:{line}: a face needs at least 3 corners, this one has {count}", .path.display())]
    TooFewCorners {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// How many corners it has.
        count: usize,
    },
    /// A face corner with vertex index 0 (OBJ indices start at 1).
    #[error("{}:{line}: vertex index 0 is invalid (OBJ indices start at 1, or count back from -1)", .path.display())]
    ZeroIndex {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
    },
    /// A face corner naming a vertex that does not exist.
    #[error("{}:{line}: vertex index {index} is out of range: {available} vertices are defined", .path.display())]
    IndexOutOfRange {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// The index as written.
        index: i64,
        /// How many vertices it could have named (for a negative index: the
        /// vertices defined before the line).
        available: usize,
    },
    /// A face corner whose vertex index is too large for any file to define
    /// (beyond 64-bit integers, e.g. `18446744073709551616`).
    #[error("{}:{line}: vertex index {token} is out of range: {available} vertices are defined", .path.display())]
    IndexTooLarge {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// The index as written (a short, escaped excerpt).
        token: String,
        /// How many vertices the file defines (for a negative index: the
        /// vertices defined before the line).
        available: usize,
    },
    /// A face with more corners than [`ObjOptions::max_face_corners`](crate::io::ObjOptions::max_face_corners).
    #[error("{}:{line}: a face with {count} corners exceeds the limit of {limit} corners per face (checking a face costs time quadratic in its corners; raise the limit with --max-face-corners or ObjOptions::max_face_corners)", .path.display())]
    FaceTooLarge {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// How many corners it has.
        count: usize,
        /// The limit in force.
        limit: usize,
    },
    /// A face corner that is not `v`, `v/vt`, `v//vn` or `v/vt/vn` with
    /// integer indices.
    #[error("{}:{line}: cannot read face corner `{token}`", .path.display())]
    BadCorner {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// The corner as written (a short, escaped excerpt).
        token: String,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("{}:{line}: vertex {vertex} has a non-finite coordinate {}", .path.display(), crate::geom::ReadableVec(*.position))]
    NonFinite {
        /// The file.
        path: PathBuf,
        /// The vertex's `v` line.
        line: usize,
        /// The vertex (1-based, as OBJ counts).
        vertex: usize,
        /// Its position as read.
        position: DVec3,
    },
    /// tobj rejected the file (`line` is where our own pass found the
    /// problem, when it could), or a face names a texture coordinate or a
    /// normal that does not exist.
    #[error("{}{}: {message}", .path.display(), .line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The offending line, when located.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },
}

impl ObjError {
    /// The line the error sits on, if it has one.
    #[must_use]
    pub fn line(&self) -> Option<usize> {
        match self {
            ObjError::Binary { line, .. }
            | ObjError::TooFewCorners { line, .. }
            | ObjError::ZeroIndex { line, .. }
            | ObjError::IndexOutOfRange { line, .. }
            | ObjError::IndexTooLarge { line, .. }
            | ObjError::FaceTooLarge { line, .. }
            | ObjError::BadCorner { line, .. }
            | ObjError::NonFinite { line, .. } => Some(*line),
            ObjError::Parse { line, .. } => *line,
            _ => None,
        }
    }
}
