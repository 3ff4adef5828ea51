//! Reading any mesh format into a located polygon soup: the options, the
//! imported file, and the driver that picks the reader, reads the file
//! within the size limit and welds.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::format::Format;
use super::import_error::ImportError;
use super::location::Sources;
use super::obj::{DEFAULT_MAX_FACE_CORNERS, ObjOptions, import_obj, import_obj_bytes};
use super::weld::{WeldMode, WeldRefusal, WeldReport, weld};
use super::{gltf, off, ply, stl, threemf};
use crate::mesh::{Polygon, PolygonSoup};

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
    /// STL file a solid; [`Import::weld`] says how many were merged.
    pub weld: WeldMode,
    /// The most corners one face may have (OBJ, PLY, OFF, ASCII STL); see
    /// [`ObjOptions::max_face_corners`].
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

/// An imported mesh file: the soup and where each part of it came from.
///
/// # Invariants
///
/// `vertex_numbers` has one entry per soup position; `vertex_lines` too for
/// the text formats that give vertices lines (OBJ, ASCII STL and PLY, OFF)
/// and is empty otherwise. Every polygon's attributes carry its
/// `source_index` (the 0-based number of the face in the file, in file
/// order) and, in the text formats, its `line`; `sources` locates every
/// polygon. Every position is finite and every index in range.
#[derive(Clone, Debug)]
pub struct Import {
    /// The file it was read from.
    pub path: PathBuf,
    /// The format it was read as.
    pub format: Format,
    /// Positions (after welding) and polygons (faces, in file order).
    pub soup: PolygonSoup,
    /// The line of each soup vertex (of the first of its welded copies), in
    /// the text formats; empty in the others.
    pub vertex_lines: Vec<usize>,
    /// The number of each soup vertex in the file, as the format counts
    /// (OBJ from 1; the others from 0; STL counts corners, three per
    /// triangle), of the first of its welded copies.
    pub vertex_numbers: Vec<usize>,
    /// What welding did (for STL: the corners merged).
    pub weld: WeldReport,
    /// Where each polygon came from.
    pub sources: Sources,
    /// Things the reader skipped, said once each (primitives that are
    /// points or lines, say).
    pub notes: Vec<String>,
    /// Wall-clock seconds of each import stage, for benchmarks.
    pub stage_seconds: Vec<(&'static str, f64)>,
}

impl Import {
    /// Where polygon `polygon` of the soup came from.
    #[must_use]
    pub fn location(&self, polygon: usize) -> Option<super::Location> {
        let line = self.soup.polygons.get(polygon)?.attributes.line;
        self.sources.locate(polygon, line)
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

/// Reads a mesh file of any format into one soup, located and welded as
/// `options` say.
///
/// # Errors
///
/// [`ImportError`]: for OBJ the [`ObjError`](super::ObjError) it always
/// gave ([`ImportError::Obj`]); for the others the file and the place.
pub fn import(path: &Path, options: &ImportOptions) -> Result<Import, ImportError> {
    let format = options.format_of(path);
    if format == Format::Obj {
        let obj = import_obj(path, &obj_options(options))?;
        return Ok(obj);
    }
    let io = |source| ImportError::Io {
        path: path.to_path_buf(),
        source,
    };
    let metadata = std::fs::metadata(path).map_err(io)?;
    if metadata.is_dir() {
        return Err(ImportError::Directory {
            path: path.to_path_buf(),
        });
    }
    if !metadata.is_file() {
        return Err(ImportError::NotAFile {
            path: path.to_path_buf(),
            format,
        });
    }
    let bytes = super::read::read_binary_input(path).map_err(io)?;
    import_bytes(path, &bytes, format, options)
}

/// Reads a mesh file of the given format already in memory; `path` is
/// used in messages, and a glTF file's external buffers are looked for
/// beside it.
///
/// # Errors
///
/// As for [`import`], except the I/O variants (a glTF file's external
/// buffer aside).
pub fn import_bytes(
    path: &Path,
    bytes: &[u8],
    format: Format,
    options: &ImportOptions,
) -> Result<Import, ImportError> {
    let start = std::time::Instant::now();
    let parsed = match format {
        Format::Obj => return Ok(import_obj_bytes(path, bytes, &obj_options(options))?),
        Format::Stl => stl::read(path, bytes, options)?,
        Format::Ply => ply::read(path, bytes, options)?,
        Format::Off => off::read(path, bytes, options)?,
        Format::ThreeMf => threemf::read(path, bytes)?,
        Format::Gltf | Format::Glb => gltf::read(path, bytes)?,
    };
    if parsed.polygons.is_empty() {
        return Err(ImportError::Empty {
            path: path.to_path_buf(),
            format,
        });
    }
    let parsed_at = start.elapsed().as_secs_f64();
    let Parsed {
        positions,
        polygons,
        vertex_lines,
        vertex_numbers,
        sources,
        notes,
    } = parsed;
    let soup = PolygonSoup {
        positions,
        polygons,
    };
    let (soup, vertex_lines, numbers, mut report) = weld(soup, vertex_lines, options.weld);
    // The weld numbers vertices from 1 in input order: use the format's
    // own numbers instead.
    for refusal in &mut report.refused {
        if let WeldRefusal::WouldPinch { vertex, line: None } = refusal {
            *vertex = vertex_numbers[*vertex - 1];
        }
    }
    let vertex_numbers = numbers.iter().map(|&n| vertex_numbers[n - 1]).collect();
    let welded = start.elapsed().as_secs_f64();
    Ok(Import {
        path: path.to_path_buf(),
        format,
        soup,
        vertex_lines,
        vertex_numbers,
        weld: report,
        sources,
        notes,
        stage_seconds: vec![("parse", parsed_at), ("weld", welded - parsed_at)],
    })
}

/// Reads a mesh file with the default options (format by extension,
/// bit-identical positions welded where that closes open edges).
///
/// # Errors
///
/// As for [`import`].
pub fn read_mesh(path: &Path) -> Result<PolygonSoup, ImportError> {
    import(path, &ImportOptions::default()).map(|import| import.soup)
}

fn obj_options(options: &ImportOptions) -> ObjOptions {
    ObjOptions {
        weld: options.weld,
        max_face_corners: options.max_face_corners,
    }
}
