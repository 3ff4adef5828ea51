//! The line pass: one walk over the raw bytes that records, for every `v`
//! line and every face line, its line number, the original vertex indices
//! and the group and material in force, and catches every error tobj would
//! report without a line.

use std::path::Path;
use std::sync::Arc;

use super::attribute_index::{AttributeCount, check_attribute_index, first_attribute_out_of_range};
use super::corner::{IndexText, corner_parts, count_statements, parse_index};
use super::error::ObjError;

/// One face (or polyline that tobj would read as a face) found by [`scan`].
#[derive(Clone, Debug)]
pub(super) struct FaceRecord {
    pub(super) line: usize,
    /// Start of its corners in [`Scan::corners`].
    pub(super) start: usize,
    pub(super) len: usize,
    pub(super) group: Option<usize>,
    pub(super) material: Option<usize>,
    /// An `l` element with three or more points: tobj reads it as a face, we
    /// drop it.
    pub(super) polyline: bool,
}

/// What the line pass learns.
#[derive(Debug, Default)]
pub(super) struct Scan {
    /// The line of each `v` element.
    pub(super) vertex_lines: Vec<u32>,
    /// The byte offset of each `v` line, to re-read unreferenced vertices.
    pub(super) vertex_offsets: Vec<usize>,
    pub(super) faces: Vec<FaceRecord>,
    /// Original 0-based vertex indices of all face corners.
    pub(super) corners: Vec<usize>,
    /// Group and material names, shared between faces.
    pub(super) names: Vec<Arc<str>>,
}

/// The line pass: one walk over the bytes, no allocation per line. The
/// bytes have passed [`precheck`](super::precheck::precheck).
pub(super) fn scan(path: &Path, bytes: &[u8]) -> Result<Scan, ObjError> {
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
                        token: crate::io::import_error::excerpt(word),
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
                                token: crate::io::import_error::excerpt(index_text),
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
    // A file with no element at all is the empty solid; vertices or
    // polylines without a face are not a solid of any kind.
    let nothing = s.faces.is_empty() && s.vertex_lines.is_empty();
    if !nothing && !s.faces.iter().any(|f| !f.polyline) {
        return Err(ObjError::Empty { path: p() });
    }
    Ok(s)
}

fn intern(names: &mut Vec<Arc<str>>, name: &str) -> usize {
    if let Some(i) = names.iter().rposition(|n| &**n == name) {
        return i;
    }
    names.push(Arc::from(name));
    names.len() - 1
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::io::ObjError;
    use crate::io::obj::fixture::{TET, read};

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
