//! The import API: options, the imported file, and the pipeline that runs
//! the checks, the line pass and tobj in turn, aligns their results and
//! welds.

use std::path::Path;

use super::align::align_positions;
use super::error::ObjError;
use super::precheck::precheck;
use super::run_tobj::run_tobj;
use super::scan::scan;
use crate::io::weld::{WeldMode, weld};
use crate::mesh::{FaceAttributes, Polygon, PolygonSoup};

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

/// An imported OBJ file: the soup and where each part of it came from
/// (every polygon and vertex has its line). The import of any format is
/// the same type, [`Import`](crate::io::Import).
pub type ObjImport = crate::io::Import;

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
    let bytes = crate::io::read_input(path).map_err(io)?;
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
    // Hexadecimal floats (`0x1.8p+1`) become the decimals of the same bits.
    let bytes = &*super::hex_float::decimal_floats(bytes);
    precheck(path, bytes, options.max_face_corners)?;
    // The line pass runs first and tobj only on bytes it accepted: tobj
    // overflows (a panic in debug builds, wrong indexing in release) on face
    // indices far out of range, texture and normal indices included (found
    // by fuzzing).
    let scan = scan(path, bytes).map_err(|e| earliest_error(path, bytes, e))?;
    if scan.faces.is_empty() && scan.vertex_lines.is_empty() {
        // No element at all (only comments or nothing): the empty solid,
        // as `to_obj_string` writes it.
        return Ok(ObjImport {
            path: path.to_path_buf(),
            format: crate::io::Format::Obj,
            soup: PolygonSoup::default(),
            vertex_lines: Vec::new(),
            vertex_numbers: Vec::new(),
            weld: crate::io::WeldReport {
                mode: options.weld,
                merged: 0,
                refused: Vec::new(),
            },
            sources: crate::io::Sources::lines(),
            notes: Vec::new(),
            stage_seconds: vec![(
                "parse (line pass, then tobj)",
                start.elapsed().as_secs_f64(),
            )],
        });
    }
    let models = run_tobj(path, bytes)?;
    let parsed = start.elapsed().as_secs_f64();
    let positions = align_positions(path, bytes, &scan, &models)?;
    // tobj's copy of the file is read: freed before the soup is made.
    drop(models);
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
        format: crate::io::Format::Obj,
        soup,
        vertex_lines,
        vertex_numbers,
        weld: report,
        sources: crate::io::Sources::lines(),
        notes: Vec::new(),
        stage_seconds: vec![
            ("parse (line pass, then tobj)", parsed),
            ("align and assemble soup", assembled - parsed),
            ("weld", welded - assembled),
        ],
    })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::obj::fixture::read;

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
        // Nothing at all is the empty solid; vertices without a face are not.
        assert!(read("").unwrap().soup.polygons.is_empty());
        assert!(
            read("# the empty solid\n\n")
                .unwrap()
                .soup
                .positions
                .is_empty()
        );
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
}
