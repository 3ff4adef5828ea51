//! What the format readers share with the driver that calls them
//! (`io::import`): the options they read under and what they
//! hand back, kept apart so that neither needs the other's file.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::format::Format;
use super::location::Sources;
use super::obj::DEFAULT_MAX_FACE_CORNERS;
use super::weld::WeldMode;
use crate::mesh::Polygon;

/// The most triangles a 3MF build or a glTF scene may place: placing an
/// object or a mesh many times multiplies a small file's triangles.
pub const MAX_PLACED_TRIANGLES: usize = 50_000_000;

/// How to read a mesh file, and which folders a scene's leaves may name.
#[derive(Clone, Debug, PartialEq)]
pub struct ImportOptions {
    /// The format; `None` picks it by the extension ([`Format::of_input`]:
    /// OBJ for an extension that names no format).
    pub format: Option<Format>,
    /// Which coincident vertices to merge; see [`WeldMode`]. STL repeats
    /// every corner, so the default ([`WeldMode::Exact`]) is what makes an
    /// STL file a solid; `Import::weld` says how many were merged.
    pub weld: WeldMode,
    /// The most corners one face may have (OBJ, PLY, OFF, ASCII STL); see
    /// [`ObjOptions::max_face_corners`](super::ObjOptions::max_face_corners).
    pub max_face_corners: usize,
    /// Scenes only: folders, beyond the scene file's own folder and the
    /// working directory, inside which a scene's leaves (mesh, field and
    /// included scene files) may resolve, symbolic links followed. Empty
    /// by default; a mesh file read directly ignores it. See
    /// [`crate::scene`] (the path policy) and docs/hostile-input.md.
    pub allowed_roots: Vec<PathBuf>,
    /// Scenes only: a mesh leaf that is not a valid closed solid is
    /// repaired ([`crate::repair::repair`]: its solid is where its winding
    /// number is positive) instead of refused. Off by default (`csg
    /// --resolve` turns it on).
    pub resolve_leaves: bool,
}

impl Default for ImportOptions {
    fn default() -> Self {
        ImportOptions {
            format: None,
            weld: WeldMode::default(),
            max_face_corners: DEFAULT_MAX_FACE_CORNERS,
            allowed_roots: Vec::new(),
            resolve_leaves: false,
        }
    }
}

impl ImportOptions {
    /// The format `path` is read as under these options.
    #[must_use]
    pub fn format_of(&self, path: &Path) -> Format {
        self.format.unwrap_or_else(|| Format::of_input(path))
    }
}

/// What a reader hands the driver: the soup before welding.
#[derive(Debug, Default)]
pub(crate) struct Parsed {
    pub positions: Vec<DVec3>,
    pub polygons: Vec<Polygon>,
    /// One per position, or empty.
    pub vertex_lines: Vec<usize>,
    /// One per position.
    pub vertex_numbers: Vec<usize>,
    pub sources: Sources,
    pub notes: Vec<String>,
}
