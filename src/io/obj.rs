//! Reading Wavefront OBJ into a polygon soup: tobj parses, a cheap line pass
//! of our own locates.
//!
//! tobj does the parsing (numbers, `v x y z w`, colours, relative indices)
//! but reports neither the line a face came from nor the original vertex
//! numbers (it renumbers the vertices of each object) and drops vertices no
//! face uses. A single pass over the raw bytes ([`scan`]) records, for every
//! `v` line and every face line, its line number, the original vertex
//! indices, and the group and material in force; it also catches every error
//! that tobj would report without a line (index zero or out of range, a face
//! with fewer than three corners, binary data) so that each error names the
//! file and the line. tobj runs only on bytes the pass accepted: the pass
//! also checks texture and normal indices, which tobj overflows on when they
//! are far out of range. Both split words at Unicode whitespace, so they
//! agree on which lines are elements. The two are then aligned face by face.
//!
//! Welding of coincident vertices is done afterwards by [`weld`](super::weld).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use thiserror::Error;

use super::weld::{WeldMode, WeldReport, weld};
use crate::mesh::{FaceAttributes, Polygon, PolygonSoup};

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
    /// The file holds no face at all (empty, comments only, or only
    /// vertices).
    #[error("{}: holds no faces (the file is empty or has no `f` lines)", .path.display())]
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
    /// A face corner that is not `v`, `v/vt`, `v//vn` or `v/vt/vn` with
    /// integer indices.
    #[error("{}:{line}: cannot read face corner `{token}`", .path.display())]
    BadCorner {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// The corner as written.
        token: String,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("{}:{line}: vertex {vertex} has a non-finite coordinate {position}", .path.display())]
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
            | ObjError::BadCorner { line, .. }
            | ObjError::NonFinite { line, .. } => Some(*line),
            ObjError::Parse { line, .. } => *line,
            _ => None,
        }
    }
}

/// How to read an OBJ file.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ObjOptions {
    /// Which coincident vertices to merge; see [`WeldMode`].
    pub weld: WeldMode,
}

/// An imported OBJ file: the soup and where each part of it came from.
///
/// # Invariants
///
/// `vertex_lines` and `vertex_numbers` have one entry per soup position. Every
/// polygon's attributes carry its 1-based OBJ `line`, its `source_index`
/// (the 0-based number of the face in the file) and the group and material
/// in force on that line. Every position is finite and every index in range.
#[derive(Clone, Debug)]
pub struct ObjImport {
    /// The file it was read from.
    pub path: PathBuf,
    /// Positions (after welding) and polygons (faces, in file order).
    pub soup: PolygonSoup,
    /// The `v` line of each soup vertex (of the first of its welded copies).
    pub vertex_lines: Vec<usize>,
    /// The OBJ number (1-based) of each soup vertex (of the first of its
    /// welded copies).
    pub vertex_numbers: Vec<usize>,
    /// What welding did.
    pub weld: WeldReport,
    /// Wall-clock seconds of each import stage, for benchmarks.
    pub stage_seconds: Vec<(&'static str, f64)>,
}

/// Reads every object and group of an OBJ file into one soup, with the
/// default weld (bit-identical positions, only where that closes open edges).
///
/// # Errors
///
/// As for [`import_obj`].
pub fn read_obj(path: &Path) -> Result<PolygonSoup, ObjError> {
    import_obj(path, &ObjOptions::default()).map(|import| import.soup)
}

/// Reads an OBJ file: all objects and groups, polygons kept as polygons,
/// `v`, `v/vt`, `v//vn` and `v/vt/vn` corners (only positions are kept),
/// negative (relative) indices; each face remembers its line, group and
/// material; then welds as `options` say.
///
/// `l` and `p` elements are ignored, as are texture coordinates and normals.
///
/// # Errors
///
/// Every [`ObjError`] variant; the first defect in file order.
pub fn import_obj(path: &Path, options: &ObjOptions) -> Result<ObjImport, ObjError> {
    let io = |source| ObjError::Io {
        path: path.to_path_buf(),
        source,
    };
    let metadata = std::fs::metadata(path).map_err(io)?;
    if metadata.is_dir() {
        return Err(ObjError::Directory {
            path: path.to_path_buf(),
        });
    }
    let bytes = std::fs::read(path).map_err(io)?;
    import_obj_bytes(path, &bytes, options)
}

/// Reads OBJ text already in memory; `path` is only used in messages.
///
/// # Errors
///
/// As for [`import_obj`], except the I/O variants.
pub fn import_obj_bytes(
    path: &Path,
    bytes: &[u8],
    options: &ObjOptions,
) -> Result<ObjImport, ObjError> {
    let start = std::time::Instant::now();
    // The line pass runs first and tobj only on bytes it accepted: tobj
    // overflows (a panic in debug builds, wrong indexing in release) on face
    // indices far out of range, texture and normal indices included.
    let scan = scan(path, bytes)?;
    let models = run_tobj(path, bytes)?;
    let parsed = start.elapsed().as_secs_f64();
    let positions = align_positions(path, bytes, &scan, &models)?;
    let mut soup = PolygonSoup {
        positions,
        polygons: Vec::with_capacity(scan.faces.len()),
    };
    for (number, face) in scan.faces.iter().filter(|f| !f.polyline).enumerate() {
        let corners = &scan.corners[face.start..face.start + face.len];
        soup.polygons.push(Polygon {
            vertices: corners.iter().copied().collect(),
            attributes: FaceAttributes {
                source_index: Some(number),
                line: Some(face.line),
                group: face.group.map(|g| scan.names[g].clone()),
                material: face.material.map(|m| scan.names[m].clone()),
            },
        });
    }
    let vertex_lines = scan.vertex_lines.iter().map(|&l| l as usize).collect();
    drop(scan);
    let assembled = start.elapsed().as_secs_f64();
    let (soup, vertex_lines, vertex_numbers, report) = weld(soup, vertex_lines, options.weld);
    let welded = start.elapsed().as_secs_f64();
    Ok(ObjImport {
        path: path.to_path_buf(),
        soup,
        vertex_lines,
        vertex_numbers,
        weld: report,
        stage_seconds: vec![
            ("parse (line pass, then tobj)", parsed),
            ("align and assemble soup", assembled - parsed),
            ("weld", welded - assembled),
        ],
    })
}

/// One face (or polyline that tobj would read as a face) found by [`scan`].
#[derive(Clone, Debug)]
struct FaceRecord {
    line: usize,
    /// Start of its corners in [`Scan::corners`].
    start: usize,
    len: usize,
    group: Option<usize>,
    material: Option<usize>,
    /// An `l` element with three or more points: tobj reads it as a face, we
    /// drop it.
    polyline: bool,
}

/// What the line pass learns.
#[derive(Debug, Default)]
struct Scan {
    /// The line of each `v` element.
    vertex_lines: Vec<u32>,
    /// The byte offset of each `v` line, to re-read unreferenced vertices.
    vertex_offsets: Vec<usize>,
    faces: Vec<FaceRecord>,
    /// Original 0-based vertex indices of all face corners.
    corners: Vec<usize>,
    /// Group and material names, shared between faces.
    names: Vec<Arc<str>>,
}

/// The per-corner indices besides the vertex's: `v/vt/vn`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Attribute {
    /// `vt`, a texture coordinate.
    Texture = 0,
    /// `vn`, a normal.
    Normal = 1,
}

impl Attribute {
    /// The error for a face naming an element of this kind that does not
    /// exist (index 0, before the first, or after the last); `defined` is
    /// how many there are before the face (for a negative index) or in the
    /// file.
    fn out_of_range(self, path: &Path, line: usize, index: i64, defined: usize) -> ObjError {
        let (what, lines) = match self {
            Attribute::Texture => ("texture coordinate", "vt"),
            Attribute::Normal => ("normal", "vn"),
        };
        let known = if index == 0 {
            "OBJ indices start at 1, or count back from -1".to_string()
        } else if index < 0 {
            format!("{defined} `{lines}` lines come before this face")
        } else {
            format!("the file has {defined} `{lines}` lines")
        };
        ObjError::Parse {
            path: path.to_path_buf(),
            line: Some(line),
            message: format!("{what} index {index} does not exist: {known}"),
        }
    }
}

fn line_of_offset(bytes: &[u8], offset: usize) -> usize {
    1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count()
}

/// The line pass: one walk over the bytes, no allocation per line.
fn scan(path: &Path, bytes: &[u8]) -> Result<Scan, ObjError> {
    let p = || path.to_path_buf();
    if let Some(offset) = memchr::memchr(0, bytes) {
        return Err(ObjError::Binary {
            path: p(),
            line: line_of_offset(bytes, offset),
        });
    }
    let all = match std::str::from_utf8(bytes) {
        Ok(all) => all,
        Err(e) => {
            return Err(ObjError::Binary {
                path: p(),
                line: line_of_offset(bytes, e.valid_up_to()),
            });
        }
    };
    let mut s = Scan::default();
    let mut group: Option<usize> = None;
    let mut material: Option<usize> = None;
    // How many `vt` and `vn` lines came before the current line, and the
    // texture or normal indices that are 0 or name no element before their
    // face, with that count (judged at the end, see below).
    let mut attributes = [0usize; 2];
    let mut suspect: Vec<(usize, Attribute, i64, usize)> = Vec::new();
    let mut offset = 0;
    let mut line = 0usize;
    while offset < all.len() {
        line += 1;
        let end = memchr::memchr(b'\n', &bytes[offset..]).map_or(bytes.len(), |i| offset + i);
        // `\n` is ASCII, so both ends are character boundaries.
        let text = &all[offset..end];
        let start = offset;
        offset = end + 1;
        // Words split at Unicode whitespace, exactly as tobj splits them.
        let mut words = text.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        // What follows the keyword (names may contain spaces).
        let rest = |keyword: &str| {
            let at = keyword.as_ptr() as usize - text.as_ptr() as usize + keyword.len();
            text[at..].trim().to_string()
        };
        match keyword {
            "v" => {
                s.vertex_lines.push(u32::try_from(line).unwrap_or(u32::MAX));
                s.vertex_offsets.push(start);
            }
            "vt" => attributes[Attribute::Texture as usize] += 1,
            "vn" => attributes[Attribute::Normal as usize] += 1,
            "f" | "l" => {
                let polyline = keyword == "l";
                let first = s.corners.len();
                let defined = s.vertex_lines.len();
                for word in words {
                    let bad = || ObjError::BadCorner {
                        path: p(),
                        line,
                        token: word.to_string(),
                    };
                    let mut parts = word.split('/');
                    let index_text = parts.next().unwrap_or_default();
                    let index = parse_index(index_text.as_bytes()).ok_or_else(bad)?;
                    let resolved = match index {
                        0 => return Err(ObjError::ZeroIndex { path: p(), line }),
                        i if i < 0 => {
                            let back = i.unsigned_abs() as usize;
                            if back > defined {
                                return Err(ObjError::IndexOutOfRange {
                                    path: p(),
                                    line,
                                    index,
                                    available: defined,
                                });
                            }
                            defined - back
                        }
                        // Forward references are checked once all `v` lines
                        // are known.
                        i => usize::try_from(i - 1).unwrap_or(usize::MAX),
                    };
                    for kind in [Attribute::Texture, Attribute::Normal] {
                        let Some(text) = parts.next() else { break };
                        if text.is_empty() {
                            continue;
                        }
                        let index = parse_index(text.as_bytes()).ok_or_else(bad)?;
                        let before = attributes[kind as usize];
                        if index == 0 || index.unsigned_abs() as usize > before {
                            suspect.push((line, kind, index, before));
                        }
                    }
                    if parts.next().is_some() {
                        return Err(bad());
                    }
                    s.corners.push(resolved);
                }
                let len = s.corners.len() - first;
                if polyline {
                    if len < 3 {
                        // A line segment: ignored by tobj and by us.
                        s.corners.truncate(first);
                        continue;
                    }
                } else if len < 3 {
                    return Err(ObjError::TooFewCorners {
                        path: p(),
                        line,
                        count: len,
                    });
                }
                s.faces.push(FaceRecord {
                    line,
                    start: first,
                    len,
                    group,
                    material,
                    polyline,
                });
            }
            "g" | "o" => {
                // As tobj: the rest of the line, trimmed, names the group.
                let name = rest(keyword);
                let name = if name.is_empty() {
                    "unnamed_object"
                } else {
                    &name
                };
                group = Some(intern(&mut s.names, name));
            }
            "usemtl" => {
                let name = rest(keyword);
                material = (!name.is_empty()).then(|| intern(&mut s.names, &name));
            }
            _ => {}
        }
    }
    let available = s.vertex_lines.len();
    for face in &s.faces {
        let corners = &s.corners[face.start..face.start + face.len];
        if let Some(&bad) = corners.iter().find(|&&i| i >= available) {
            return Err(ObjError::IndexOutOfRange {
                path: p(),
                line: face.line,
                index: i64::try_from(bad).map_or(i64::MAX, |i| i.saturating_add(1)),
                available,
            });
        }
    }
    // A file without `vt` (or `vn`) lines may carry dangling texture (or
    // normal) indices: tobj ignores them, and so do we. Otherwise every one
    // must exist: negative ones before their face, positive ones anywhere.
    for (line, kind, index, before) in suspect {
        let total = attributes[kind as usize];
        let defined = if index < 0 { before } else { total };
        if total > 0 && (index == 0 || index.unsigned_abs() as usize > defined) {
            return Err(kind.out_of_range(path, line, index, defined));
        }
    }
    if !s.faces.iter().any(|f| !f.polyline) {
        return Err(ObjError::Empty { path: p() });
    }
    Ok(s)
}

/// An OBJ index: optional sign, decimal digits, nothing else.
fn parse_index(text: &[u8]) -> Option<i64> {
    let (negative, digits) = match text.first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    if digits.is_empty() || digits.len() > 18 {
        return None;
    }
    let mut value: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        value = value * 10 + i64::from(d - b'0');
    }
    Some(if negative { -value } else { value })
}

fn intern(names: &mut Vec<Arc<str>>, name: &str) -> usize {
    if let Some(i) = names.iter().rposition(|n| &**n == name) {
        return i;
    }
    names.push(Arc::from(name));
    names.len() - 1
}

/// Runs tobj over the bytes: polygons kept, points and lines ignored,
/// material libraries not loaded (only material names matter).
fn run_tobj(path: &Path, bytes: &[u8]) -> Result<Vec<tobj::Model>, ObjError> {
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = std::io::Cursor::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ObjError::Parse {
        path: path.to_path_buf(),
        line: locate_tobj_error(bytes, &e),
        message: e.to_string(),
    })?;
    Ok(models)
}

/// Places the positions tobj read at their original vertex numbers;
/// unreferenced vertices (which tobj drops) are read from their own lines.
fn align_positions(
    path: &Path,
    bytes: &[u8],
    scan: &Scan,
    models: &[tobj::Model],
) -> Result<Vec<DVec3>, ObjError> {
    let mismatch = |what: &str| ObjError::Parse {
        path: path.to_path_buf(),
        line: None,
        message: format!("internal: tobj and the line pass disagree ({what})"),
    };
    let vertex_count = scan.vertex_lines.len();
    let mut positions = vec![DVec3::NAN; vertex_count];
    let mut set = vec![false; vertex_count];
    let mut faces = scan.faces.iter();
    let mut local_to_original: Vec<usize> = Vec::new();
    for model in models {
        let mesh = &model.mesh;
        local_to_original.clear();
        local_to_original.resize(mesh.positions.len() / 3, usize::MAX);
        let mut cursor = 0usize;
        let face_count = if mesh.face_arities.is_empty() {
            mesh.indices.len() / 3
        } else {
            mesh.face_arities.len()
        };
        for k in 0..face_count {
            let arity = mesh.face_arities.get(k).map_or(3, |&a| a as usize);
            let record = faces.next().ok_or_else(|| mismatch("face count"))?;
            if record.len != arity {
                return Err(mismatch("face size"));
            }
            let originals = &scan.corners[record.start..record.start + arity];
            let locals = mesh
                .indices
                .get(cursor..cursor + arity)
                .ok_or_else(|| mismatch("index count"))?;
            cursor += arity;
            for (&local, &original) in locals.iter().zip(originals) {
                let local = local as usize;
                let slot = local_to_original
                    .get_mut(local)
                    .ok_or_else(|| mismatch("local index"))?;
                if *slot == usize::MAX {
                    *slot = original;
                    let p = &mesh.positions[3 * local..3 * local + 3];
                    positions[original] = DVec3::new(p[0], p[1], p[2]);
                    set[original] = true;
                } else if *slot != original {
                    return Err(mismatch("vertex identity"));
                }
            }
        }
    }
    if faces.next().is_some() {
        return Err(mismatch("face count"));
    }
    for (i, done) in set.iter().enumerate() {
        if !done {
            positions[i] =
                read_vertex_line(bytes, scan.vertex_offsets[i]).ok_or_else(|| ObjError::Parse {
                    path: path.to_path_buf(),
                    line: Some(scan.vertex_lines[i] as usize),
                    message: "cannot read vertex position".to_string(),
                })?;
        }
        if !positions[i].is_finite() {
            return Err(ObjError::NonFinite {
                path: path.to_path_buf(),
                line: scan.vertex_lines[i] as usize,
                vertex: i + 1,
                position: positions[i],
            });
        }
    }
    Ok(positions)
}

/// The position on a `v` line, as tobj reads it (`x y z [w]`, or
/// `x y z r g b`).
fn read_vertex_line(bytes: &[u8], offset: usize) -> Option<DVec3> {
    let end = bytes[offset..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| offset + i);
    let text = std::str::from_utf8(&bytes[offset..end]).ok()?;
    let values: Vec<&str> = text.split_whitespace().skip(1).collect();
    let number = |i: usize| values.get(i).and_then(|v| v.parse::<f64>().ok());
    let p = DVec3::new(number(0)?, number(1)?, number(2)?);
    match values.len() {
        4 => Some(p / number(3)?),
        _ => Some(p),
    }
}

/// The first line that makes tobj fail with `error`, found by re-checking
/// each line the way tobj does.
fn locate_tobj_error(bytes: &[u8], error: &tobj::LoadError) -> Option<usize> {
    let text = std::str::from_utf8(bytes).ok()?;
    let (mut vt, mut vn) = (0usize, 0usize);
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        let values: Vec<&str> = words.collect();
        let floats =
            |n: usize| values.len() >= n && values[..n].iter().all(|v| v.parse::<f64>().is_ok());
        let bad = match (keyword, error) {
            (Some("v"), tobj::LoadError::PositionParseError) => {
                !floats(3) || (values.len() == 4 && values[3].parse::<f64>().is_err())
            }
            (Some("v"), tobj::LoadError::ScalingByZeroError) => {
                values.len() == 4 && values[3].parse::<f64>().ok() == Some(0.0)
            }
            (Some("v"), tobj::LoadError::ColorParseError) => values.len() == 5 || values.len() > 6,
            (Some("vt"), tobj::LoadError::TexcoordParseError) => !floats(2),
            (Some("vn"), tobj::LoadError::NormalParseError) => !floats(3),
            (Some("f"), tobj::LoadError::FaceTexCoordOutOfBounds) => {
                corner_out_of_range(&values, 1, vt)
            }
            (Some("f"), tobj::LoadError::FaceNormalOutOfBounds) => {
                corner_out_of_range(&values, 2, vn)
            }
            (Some("usemtl"), tobj::LoadError::MaterialParseError) => values.is_empty(),
            _ => false,
        };
        if bad {
            return Some(i + 1);
        }
        match keyword {
            Some("vt") => vt += 1,
            Some("vn") => vn += 1,
            _ => {}
        }
    }
    None
}

fn corner_out_of_range(corners: &[&str], slot: usize, defined: usize) -> bool {
    corners.iter().any(|c| {
        c.split('/')
            .nth(slot)
            .filter(|s| !s.is_empty())
            .and_then(|s| s.parse::<i64>().ok())
            .is_some_and(|i| i == 0 || i.unsigned_abs() as usize > defined)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<ObjImport, ObjError> {
        import_obj_bytes(Path::new("t.obj"), text.as_bytes(), &ObjOptions::default())
    }

    const TET: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";

    #[test]
    fn faces_remember_their_lines_groups_and_materials() {
        let text = "# tet\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ng a\nusemtl red\nf 1 3 2\nf 1 2 4\ng b\nf 2/1 3/1 4/1\nusemtl blue\nf -2//1 -4//1 -1//1\n";
        let import = read(text).unwrap();
        let lines: Vec<_> = import
            .soup
            .polygons
            .iter()
            .map(|p| p.attributes.line.unwrap())
            .collect();
        assert_eq!(lines, [8, 9, 11, 13]);
        let groups: Vec<_> = import
            .soup
            .polygons
            .iter()
            .map(|p| p.attributes.group.as_deref().unwrap().to_string())
            .collect();
        assert_eq!(groups, ["a", "a", "b", "b"]);
        let materials: Vec<_> = import
            .soup
            .polygons
            .iter()
            .map(|p| p.attributes.material.as_deref().unwrap().to_string())
            .collect();
        assert_eq!(materials, ["red", "red", "red", "blue"]);
        assert_eq!(&import.soup.polygons[3].vertices[..], &[2, 0, 3]);
        assert_eq!(import.vertex_lines, [2, 3, 4, 5]);
        // Vertices shared across groups stay shared (tobj splits them).
        assert_eq!(import.soup.positions.len(), 4);
    }

    #[test]
    fn unreferenced_vertices_are_kept() {
        let import = read(&format!("{TET}v 5 5 5 2\n")).unwrap();
        assert_eq!(import.soup.positions.len(), 5);
        assert_eq!(import.soup.positions[4], DVec3::splat(2.5));
        assert_eq!(import.vertex_lines[4], 9);
    }

    #[test]
    fn errors_name_the_line() {
        let e = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n").unwrap_err();
        assert!(matches!(e, ObjError::ZeroIndex { line: 4, .. }), "{e}");
        let e = read("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n").unwrap_err();
        assert!(
            matches!(
                e,
                ObjError::IndexOutOfRange {
                    line: 5,
                    index: 4,
                    ..
                }
            ),
            "{e}"
        );
        let e = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n").unwrap_err();
        assert!(
            matches!(
                e,
                ObjError::IndexOutOfRange {
                    line: 4,
                    index: -4,
                    ..
                }
            ),
            "{e}"
        );
        let e = read("v 0 0 0\nv 1 0 0\nf 1 2\n").unwrap_err();
        assert!(
            matches!(
                e,
                ObjError::TooFewCorners {
                    line: 3,
                    count: 2,
                    ..
                }
            ),
            "{e}"
        );
        let e = read("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n").unwrap_err();
        assert!(
            matches!(
                e,
                ObjError::NonFinite {
                    line: 2,
                    vertex: 2,
                    ..
                }
            ),
            "{e}"
        );
        let e = read("v 0 0 0\nv 1 x 0\nv 0 1 0\nf 1 2 3\n").unwrap_err();
        assert!(matches!(e, ObjError::Parse { line: Some(2), .. }), "{e}");
        let e = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 a 3\n").unwrap_err();
        assert!(matches!(e, ObjError::BadCorner { line: 4, .. }), "{e}");
        assert!(matches!(read("").unwrap_err(), ObjError::Empty { .. }));
        assert!(matches!(
            read("# only\nv 1 2 3\n").unwrap_err(),
            ObjError::Empty { .. }
        ));
        let junk = import_obj_bytes(
            Path::new("j"),
            b"v 0 0 0\n\x7fELF\x02\x01\x00\xff",
            &ObjOptions::default(),
        )
        .unwrap_err();
        assert!(matches!(junk, ObjError::Binary { line: 2, .. }), "{junk}");
        assert!(junk.to_string().starts_with("j:2:"));
    }

    #[test]
    fn texture_and_normal_indices_that_name_nothing_are_errors() {
        // Found by fuzzing (fixtures/fuzz/obj_validate/): a normal index
        // counting back past the first `vn` made tobj overflow (`vn * 3`).
        let attributes = "vt 0 0\nvn 0 0 1\n";
        for (corner, what) in [
            ("1/1/-125", "normal index -125"),
            ("1/-2", "texture coordinate index -2"),
            (
                "1/1/6148914691236517207",
                "normal index 6148914691236517207",
            ),
            ("1/2", "texture coordinate index 2"),
            ("1/0/1", "texture coordinate index 0"),
            ("1//0", "normal index 0"),
        ] {
            let text = format!("{TET}{attributes}f {corner} 2 3\n");
            let e = read(&text).unwrap_err();
            assert_eq!(e.line(), Some(11), "{corner}: {e}");
            let message = e.to_string();
            // Indices of more than 18 digits are not read as numbers.
            if corner.len() > 20 {
                assert!(matches!(e, ObjError::BadCorner { .. }), "{message}");
            } else {
                assert!(message.contains(what), "{corner}: {message}");
            }
        }
        // Without any `vt` or `vn` lines, such indices are ignored (as tobj
        // does), and in range they are accepted.
        assert!(read(&format!("{TET}f 1/9/-9 2/9/-9 3/9/-9\n")).is_ok());
        assert!(read(&format!("{TET}{attributes}f 1/1/1 2/-1/-1 3//1\n")).is_ok());
        let e = read(&format!("{TET}{attributes}f 1/1/1/1 2 3\n")).unwrap_err();
        assert!(matches!(e, ObjError::BadCorner { line: 11, .. }), "{e}");
    }

    #[test]
    fn the_most_negative_index_is_an_error() {
        for corner in [
            "-9223372036854775808",
            "9223372036854775807",
            "-999999999999999999",
        ] {
            let e = read(&format!("{TET}f 1 2 {corner}\n")).unwrap_err();
            assert_eq!(e.line(), Some(9), "{corner}: {e}");
        }
    }

    #[test]
    fn words_split_at_unicode_whitespace_as_tobj_splits_them() {
        // A vertical tab or a no-break space separates words for tobj; the
        // line pass once split at ASCII whitespace only, so it missed the
        // `v` line and numbered the later vertices differently.
        for space in ['\u{b}', '\u{a0}', '\u{2003}'] {
            let text = format!("v 9 9 9\nv{space}5 5 5\n{TET}f{space}4 6 5\n");
            let import = read(&text).unwrap();
            assert_eq!(import.soup.positions[1], DVec3::splat(5.0));
            assert_eq!(import.soup.positions[2], DVec3::ZERO);
            assert_eq!(import.vertex_lines[2], 3);
            assert_eq!(&import.soup.polygons[4].vertices[..], &[3, 5, 4]);
            assert_eq!(import.soup.polygons[4].attributes.line, Some(11));
        }
    }

    #[test]
    fn polylines_and_points_are_ignored() {
        let import = read(&format!("{TET}l 1 2\nl 1 2 3\np 1\n")).unwrap();
        assert_eq!(import.soup.polygons.len(), 4);
    }
}
