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
    /// A face corner whose vertex index is too large for any file to define
    /// (beyond 64-bit integers, e.g. `18446744073709551616`).
    #[error("{}:{line}: vertex index {token} is out of range: {available} vertices are defined", .path.display())]
    IndexTooLarge {
        /// The file.
        path: PathBuf,
        /// The face's line.
        line: usize,
        /// The index as written.
        token: String,
        /// How many vertices the file defines (for a negative index: the
        /// vertices defined before the line).
        available: usize,
    },
    /// A face with more corners than [`ObjOptions::max_face_corners`].
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
            | ObjError::IndexTooLarge { line, .. }
            | ObjError::FaceTooLarge { line, .. }
            | ObjError::BadCorner { line, .. }
            | ObjError::NonFinite { line, .. } => Some(*line),
            ObjError::Parse { line, .. } => *line,
            _ => None,
        }
    }
}

/// The default of [`ObjOptions::max_face_corners`].
pub const DEFAULT_MAX_FACE_CORNERS: usize = 4096;

/// How to read an OBJ file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjOptions {
    /// Which coincident vertices to merge; see [`WeldMode`].
    pub weld: WeldMode,
    /// The most corners one face (or polyline) may have; a larger one is
    /// refused with [`ObjError::FaceTooLarge`] before anything is parsed.
    ///
    /// Validating a face of `n` corners costs `O(n²)` (the simplicity test
    /// of its outline, its ear-clipped triangulation and the tests of its
    /// neighbours against it): at the default of
    /// [`DEFAULT_MAX_FACE_CORNERS`] a single face takes a few seconds.
    /// Raise it for files with larger faces if waiting is acceptable.
    pub max_face_corners: usize,
}

impl Default for ObjOptions {
    fn default() -> Self {
        ObjOptions {
            weld: WeldMode::default(),
            max_face_corners: DEFAULT_MAX_FACE_CORNERS,
        }
    }
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
    let bytes = super::read_input(path).map_err(io)?;
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
    precheck(path, bytes, options.max_face_corners)?;
    // The line pass runs first and tobj only on bytes it accepted: tobj
    // overflows (a panic in debug builds, wrong indexing in release) on face
    // indices far out of range, texture and normal indices included (found
    // by fuzzing).
    let scan = scan(path, bytes).map_err(|e| earliest_error(path, bytes, e))?;
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

fn line_of_offset(bytes: &[u8], offset: usize) -> usize {
    1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count()
}

/// The first error of the file, given the line pass's `error`: tobj may
/// refuse an earlier line (a `v` line whose numbers do not parse), so it
/// reads the lines before the error — but only when the line pass accepts
/// those lines on their own, so that tobj never sees an index it would
/// overflow on.
fn earliest_error(path: &Path, bytes: &[u8], error: ObjError) -> ObjError {
    // An error without a line (no faces) comes after every line.
    let start = match error.line() {
        None => bytes.len(),
        Some(line) if line <= 1 => 0,
        Some(line) => memchr::memchr_iter(b'\n', bytes)
            .nth(line - 2)
            .map_or(bytes.len(), |i| i + 1),
    };
    let before = &bytes[..start];
    // Those lines need not hold a face themselves.
    if !matches!(scan(path, before), Ok(_) | Err(ObjError::Empty { .. })) {
        return error;
    }
    match run_tobj(path, before) {
        Err(theirs) => earlier(error, theirs),
        Ok(_) => error,
    }
}

/// Of two errors found by different passes, the one on the earlier line
/// (an error without a line counts as after every line; `first` wins ties).
fn earlier(first: ObjError, second: ObjError) -> ObjError {
    let key = |e: &ObjError| e.line().unwrap_or(usize::MAX);
    if key(&second) < key(&first) {
        second
    } else {
        first
    }
}

/// Checks that need no parsing, made before either parser runs so that a
/// hostile file is refused before anything is built from it: binary data
/// (a NUL byte or invalid UTF-8: the first such line is named) and faces
/// with more than `max_face_corners` corners (tobj would otherwise read the
/// whole face first).
fn precheck(path: &Path, bytes: &[u8], max_face_corners: usize) -> Result<(), ObjError> {
    if let Some(offset) = memchr::memchr(0, bytes) {
        return Err(ObjError::Binary {
            path: path.to_path_buf(),
            line: line_of_offset(bytes, offset),
        });
    }
    if let Err(e) = std::str::from_utf8(bytes) {
        return Err(ObjError::Binary {
            path: path.to_path_buf(),
            line: line_of_offset(bytes, e.valid_up_to()),
        });
    }
    // Every corner takes at least two bytes (a digit and a separator), so
    // only lines longer than this can hold too many corners.
    let shortest_too_long = max_face_corners.saturating_mul(2).saturating_add(2);
    let mut start = 0;
    for (index, end) in memchr::memchr_iter(b'\n', bytes)
        .chain(std::iter::once(bytes.len()))
        .enumerate()
    {
        let text = &bytes[start..end];
        start = end + 1;
        if text.len() < shortest_too_long {
            continue;
        }
        let mut words = text
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        if !matches!(words.next(), Some(b"f" | b"l")) {
            continue;
        }
        let count = words.count();
        if count > max_face_corners {
            return Err(ObjError::FaceTooLarge {
                path: path.to_path_buf(),
                line: index + 1,
                count,
                limit: max_face_corners,
            });
        }
    }
    Ok(())
}

/// The line pass: one walk over the bytes, no allocation per line. The
/// bytes have passed [`precheck`].
fn scan(path: &Path, bytes: &[u8]) -> Result<Scan, ObjError> {
    let p = || path.to_path_buf();
    let mut s = Scan::default();
    let mut textures = AttributeCount::default();
    let mut normals = AttributeCount::default();
    let mut group: Option<usize> = None;
    let mut material: Option<usize> = None;
    let mut offset = 0;
    let mut line = 0usize;
    while offset < bytes.len() {
        line += 1;
        let end = memchr::memchr(b'\n', &bytes[offset..]).map_or(bytes.len(), |i| offset + i);
        let text = &bytes[offset..end];
        let start = offset;
        offset = end + 1;
        // The bytes are UTF-8 (checked by `precheck`) and `\n` is ASCII, so
        // every line is too. Words split at Unicode whitespace, exactly as
        // tobj splits them (a vertical tab or a no-break space separates
        // words for tobj; splitting at ASCII whitespace only once numbered
        // vertices differently from tobj; found by fuzzing).
        let Ok(line_text) = std::str::from_utf8(text) else {
            return Err(ObjError::Binary { path: p(), line });
        };
        let mut words = line_text.split_whitespace().map(str::as_bytes);
        let Some(keyword) = words.next() else {
            continue;
        };
        // What follows the keyword (names may contain spaces).
        let rest = |keyword: &[u8]| {
            let at = keyword.as_ptr() as usize - text.as_ptr() as usize + keyword.len();
            String::from_utf8_lossy(&text[at..]).trim().to_string()
        };
        match keyword {
            b"v" => {
                s.vertex_lines.push(u32::try_from(line).unwrap_or(u32::MAX));
                s.vertex_offsets.push(start);
            }
            b"vt" => textures.defined += 1,
            b"vn" => normals.defined += 1,
            b"f" | b"l" => {
                let polyline = keyword == b"l";
                let first = s.corners.len();
                let defined = s.vertex_lines.len();
                for word in words {
                    let bad = || ObjError::BadCorner {
                        path: p(),
                        line,
                        token: String::from_utf8_lossy(word).into_owned(),
                    };
                    let (index_text, texture, normal) = corner_parts(word).ok_or_else(bad)?;
                    if let Some(text) = texture {
                        check_attribute_index(path, bytes, line, text, "vt", &mut textures)?;
                    }
                    if let Some(text) = normal {
                        check_attribute_index(path, bytes, line, text, "vn", &mut normals)?;
                    }
                    let index = match parse_index(index_text) {
                        IndexText::Value(index) => index,
                        IndexText::TooLarge { negative } => {
                            return Err(ObjError::IndexTooLarge {
                                path: p(),
                                line,
                                token: String::from_utf8_lossy(index_text).into_owned(),
                                available: if negative {
                                    defined
                                } else {
                                    count_statements(bytes, b"v")
                                },
                            });
                        }
                        IndexText::NotAnIndex => return Err(bad()),
                    };
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
            b"g" | b"o" => {
                // As tobj: the rest of the line, trimmed, names the group.
                let name = rest(keyword);
                let name = if name.is_empty() {
                    "unnamed_object"
                } else {
                    &name
                };
                group = Some(intern(&mut s.names, name));
            }
            b"usemtl" => {
                let name = rest(keyword);
                material = (!name.is_empty()).then(|| intern(&mut s.names, &name));
            }
            _ => {}
        }
    }
    for (keyword, count) in [("vt", textures), ("vn", normals)] {
        if count.out_of_range() {
            return Err(first_attribute_out_of_range(
                path,
                bytes,
                keyword,
                count.defined,
            ));
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
    if !s.faces.iter().any(|f| !f.polyline) {
        return Err(ObjError::Empty { path: p() });
    }
    Ok(s)
}

/// What a corner's vertex index reads as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum IndexText {
    /// An integer that fits in 64 bits.
    Value(i64),
    /// Digits whose value is beyond 64 bits (beyond `i64`): no file can
    /// define that many vertices.
    TooLarge {
        /// Written with a minus sign.
        negative: bool,
    },
    /// Not an optionally signed run of decimal digits.
    NotAnIndex,
}

/// An OBJ index: optional sign, decimal digits, nothing else.
fn parse_index(text: &[u8]) -> IndexText {
    let (negative, digits) = match text.first() {
        Some(b'-') => (true, &text[1..]),
        Some(b'+') => (false, &text[1..]),
        _ => (false, text),
    };
    if digits.is_empty() || !digits.iter().all(u8::is_ascii_digit) {
        return IndexText::NotAnIndex;
    }
    let magnitude = digits.iter().try_fold(0u64, |value, &d| {
        value.checked_mul(10)?.checked_add(u64::from(d - b'0'))
    });
    let value = magnitude.and_then(|m| {
        if negative {
            0i64.checked_sub_unsigned(m)
        } else {
            i64::try_from(m).ok()
        }
    });
    value.map_or(IndexText::TooLarge { negative }, IndexText::Value)
}

/// How many lines of the file start with `keyword` (for the message of an
/// index found before the end of the file).
fn count_statements(bytes: &[u8], keyword: &[u8]) -> usize {
    bytes
        .split(|&b| b == b'\n')
        .filter(|line| {
            line.split(|b| b.is_ascii_whitespace())
                .find(|w| !w.is_empty())
                == Some(keyword)
        })
        .count()
}

/// The vertex, texture-coordinate and normal index texts of a corner.
type CornerParts<'a> = (&'a [u8], Option<&'a [u8]>, Option<&'a [u8]>);

/// A face corner split into its vertex, texture-coordinate and normal
/// index texts: `v`, `v/vt`, `v//vn` or `v/vt/vn`; `None` for any other
/// shape (`1/`, `1/2/`, `1//`, `1/2/3/4`).
fn corner_parts(word: &[u8]) -> Option<CornerParts<'_>> {
    let mut parts = word.split(|&b| b == b'/');
    let vertex = parts.next()?;
    let texture = parts.next();
    let normal = parts.next();
    if parts.next().is_some() {
        return None;
    }
    match (texture, normal) {
        (None, _) => Some((vertex, None, None)),
        (Some(t), None) if !t.is_empty() => Some((vertex, Some(t), None)),
        (Some(t), Some(n)) if !n.is_empty() => {
            Some((vertex, (!t.is_empty()).then_some(t), Some(n)))
        }
        _ => None,
    }
}

/// A kind of face-corner attribute (`vt` or `vn`): how many the file
/// defines so far and whether a corner named one beyond them.
#[derive(Clone, Copy, Debug, Default)]
struct AttributeCount {
    /// `vt` or `vn` lines read so far.
    defined: usize,
    /// The largest positive index used so far (checked at the end, since
    /// an attribute may be defined after the face using it).
    largest_used: usize,
    /// A negative index reached back before the first definition.
    negative_out_of_range: bool,
}

impl AttributeCount {
    /// Whether some corner names an attribute the file does not define.
    /// As tobj, a file that defines none of this kind has its indices
    /// ignored (only positions are read).
    fn out_of_range(&self) -> bool {
        self.defined > 0 && (self.negative_out_of_range || self.largest_used > self.defined)
    }
}

/// Checks the form of a texture-coordinate or normal index written as
/// `text` on `line` and records its range in `count` (checked once the
/// whole file is read).
fn check_attribute_index(
    path: &Path,
    bytes: &[u8],
    line: usize,
    text: &[u8],
    keyword: &'static str,
    count: &mut AttributeCount,
) -> Result<(), ObjError> {
    let what = attribute_name(keyword);
    let error = |message: String| ObjError::Parse {
        path: path.to_path_buf(),
        line: Some(line),
        message,
    };
    match parse_index(text) {
        IndexText::NotAnIndex => Err(error(format!(
            "cannot read {what} index `{}`",
            String::from_utf8_lossy(text)
        ))),
        IndexText::TooLarge { negative } => Err(error(format!(
            "{what} index {} is out of range: {} `{keyword}` lines are defined",
            String::from_utf8_lossy(text),
            if negative {
                count.defined
            } else {
                count_statements(bytes, keyword.as_bytes())
            },
        ))),
        IndexText::Value(0) => Err(error(format!(
            "{what} index 0 is invalid (OBJ indices start at 1, or count back from -1)"
        ))),
        IndexText::Value(i) if i < 0 => {
            if usize::try_from(i.unsigned_abs()).map_or(true, |back| back > count.defined) {
                count.negative_out_of_range = true;
            }
            Ok(())
        }
        IndexText::Value(i) => {
            let i = usize::try_from(i).unwrap_or(usize::MAX);
            count.largest_used = count.largest_used.max(i);
            Ok(())
        }
    }
}

fn attribute_name(keyword: &str) -> &'static str {
    if keyword == "vt" {
        "texture coordinate"
    } else {
        "normal"
    }
}

/// The first face line naming a `keyword` attribute (`vt` or `vn`) that
/// the file does not define, of which it holds `defined` (only called once
/// such a line is known to exist).
fn first_attribute_out_of_range(
    path: &Path,
    bytes: &[u8],
    keyword: &'static str,
    defined: usize,
) -> ObjError {
    let what = attribute_name(keyword);
    let mut before = 0usize;
    for (i, text) in bytes.split(|&b| b == b'\n').enumerate() {
        let mut words = text
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        match words.next() {
            Some(k) if k == keyword.as_bytes() => before += 1,
            Some(b"f" | b"l") => {
                for word in words {
                    let Some((_, texture, normal)) = corner_parts(word) else {
                        continue;
                    };
                    let index = if keyword == "vt" { texture } else { normal };
                    let Some(IndexText::Value(index)) = index.map(parse_index) else {
                        continue;
                    };
                    let available = if index < 0 { before } else { defined };
                    let reach = usize::try_from(index.unsigned_abs()).unwrap_or(usize::MAX);
                    if reach > available {
                        return ObjError::Parse {
                            path: path.to_path_buf(),
                            line: Some(i + 1),
                            message: format!(
                                "{what} index {index} is out of range: {available} `{keyword}` lines are defined"
                            ),
                        };
                    }
                }
            }
            _ => {}
        }
    }
    ObjError::Parse {
        path: path.to_path_buf(),
        line: None,
        message: format!("a {what} index is out of range"),
    }
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
    .map_err(|e| {
        let line = locate_tobj_error(bytes, &e);
        let what = describe_tobj_error(&e);
        ObjError::Parse {
            path: path.to_path_buf(),
            line,
            message: match line {
                Some(line) => format!("{what}: `{}`", excerpt_of_line(bytes, line)),
                None => what,
            },
        }
    })?;
    Ok(models)
}

/// What a tobj error means, in the terms of the OBJ format.
fn describe_tobj_error(error: &tobj::LoadError) -> String {
    use tobj::LoadError as E;
    match error {
        E::PositionParseError => {
            "cannot read vertex position: a `v` line needs the numbers x y z (then optionally w, or r g b)"
        }
        E::ScalingByZeroError => "a `v` line has weight w = 0",
        E::ColorParseError => {
            "a `v` line has 5 or more than 6 numbers (x y z, then optionally w, or r g b)"
        }
        E::NormalParseError => "cannot read normal: a `vn` line needs the numbers x y z",
        E::TexcoordParseError => "cannot read texture coordinate: a `vt` line needs the numbers u v",
        E::FaceTexCoordOutOfBounds => {
            "a face corner names a texture coordinate (`v/vt`) that is not defined"
        }
        E::FaceNormalOutOfBounds => "a face corner names a normal (`v//vn`) that is not defined",
        E::MaterialParseError => "`usemtl` without a material name",
        other => return format!("cannot parse: {other}"),
    }
    .to_string()
}

/// The text of a 1-based line, shortened to at most 60 characters.
fn excerpt_of_line(bytes: &[u8], line: usize) -> String {
    const SHOWN: usize = 60;
    let text = bytes
        .split(|&b| b == b'\n')
        .nth(line - 1)
        .unwrap_or_default();
    let text = String::from_utf8_lossy(text);
    let text = text.trim();
    match text.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text.to_string(),
    }
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
    fn indices_beyond_64_bits_are_out_of_range() {
        for index in [
            "9223372036854775808",
            "18446744073709551616",
            "-9223372036854775809",
            "99999999999999999999999999999999",
        ] {
            let e = read(&format!(
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {index}\nv 0 0 1\n"
            ))
            .unwrap_err();
            assert!(matches!(e, ObjError::IndexTooLarge { line: 4, .. }), "{e}");
            let available = if index.starts_with('-') { 3 } else { 4 };
            assert_eq!(
                e.to_string(),
                format!(
                    "t.obj:4: vertex index {index} is out of range: {available} vertices are defined"
                )
            );
        }
        for (index, available) in [("9223372036854775807", 3), ("-9223372036854775808", 3)] {
            let e = read(&format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {index}\n")).unwrap_err();
            assert!(
                matches!(e, ObjError::IndexOutOfRange { line: 4, available: a, .. } if a == available),
                "{e}"
            );
        }
        assert_eq!(parse_index(b"+7"), IndexText::Value(7));
        assert_eq!(parse_index(b"-"), IndexText::NotAnIndex);
        assert_eq!(parse_index(b"1e3"), IndexText::NotAnIndex);
    }

    #[test]
    fn faces_above_the_corner_limit_are_refused_before_parsing() {
        let options = ObjOptions {
            max_face_corners: 5,
            ..ObjOptions::default()
        };
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1 2 3\n";
        let e = import_obj_bytes(Path::new("t.obj"), text.as_bytes(), &options).unwrap_err();
        assert!(
            matches!(
                e,
                ObjError::FaceTooLarge {
                    line: 4,
                    count: 6,
                    limit: 5,
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string()
                .starts_with("t.obj:4: a face with 6 corners exceeds the limit of 5")
        );
        // At the limit the face is read (and found degenerate later).
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1 2\n";
        assert!(import_obj_bytes(Path::new("t.obj"), text.as_bytes(), &options).is_ok());
        // Long lines that are not faces are not faces.
        let text = format!("# {}\n{TET}", "x ".repeat(100));
        assert!(import_obj_bytes(Path::new("t.obj"), text.as_bytes(), &options).is_ok());
    }

    #[test]
    fn the_first_bad_line_wins_whichever_pass_finds_it() {
        // tobj refuses line 2, our pass line 4 (and would say "no faces").
        let e = read("v 0 0 0\nv 1 y 0\nv 0 1 0\nf 1 2 0\n").unwrap_err();
        assert_eq!(e.line(), Some(2), "{e}");
        let e = read("v a b c\nv a b c\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:1: cannot read vertex position: a `v` line needs the numbers x y z (then optionally w, or r g b): `v a b c`"
        );
        let e = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\nv 1 y 0\n").unwrap_err();
        assert!(matches!(e, ObjError::ZeroIndex { line: 4, .. }), "{e}");
    }

    #[test]
    fn corners_must_have_one_of_the_four_shapes_and_indices_in_range() {
        for corner in ["1/", "1/2/", "1//", "1/2/3/4", "/1"] {
            let e = read(&format!("{TET}f 1 2 {corner}\n")).unwrap_err();
            assert!(
                matches!(e, ObjError::BadCorner { line: 9, .. }),
                "{corner}: {e}"
            );
        }
        let e = read(&format!("{TET}f 1 2/x 3\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:9: cannot read texture coordinate index `x`"
        );
        // Attributes may be defined after the faces using them; a file
        // without any has their indices ignored.
        let text = format!("{TET}f 2/1/1 3/1/1 4/1/1\nvt 0 0\nvn 0 0 1\n");
        read(&text).unwrap();
        read(&format!("{TET}f 2/7 3/-9 4/1\n")).unwrap();
        let e = read(&format!("{TET}f 1/3 2/1 3/1\nvt 0 0\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:9: texture coordinate index 3 is out of range: 1 `vt` lines are defined"
        );
        let e = read(&format!("{TET}vn 0 0 1\nf 1//1 2//-2 3//1\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:10: normal index -2 is out of range: 1 `vn` lines are defined"
        );
        let e = read(&format!("{TET}vt 0 0\nf 1/1 2/1 3/1 4/-2\n")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.obj:10: texture coordinate index -2 is out of range: 1 `vt` lines are defined"
        );
        let e = read(&format!("{TET}f 1/0 2/1 3/1\n")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("t.obj:9: texture coordinate index 0 is invalid"),
            "{e}"
        );
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
            assert!(message.contains(what), "{corner}: {message}");
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
