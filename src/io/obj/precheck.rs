//! Checks that need no parsing, made before either parser runs: binary data
//! and faces with too many corners.

use std::path::Path;

use super::error::ObjError;

fn line_of_offset(bytes: &[u8], offset: usize) -> usize {
    1 + bytes[..offset].iter().filter(|&&b| b == b'\n').count()
}

/// Checks that need no parsing, made before either parser runs so that a
/// hostile file is refused before anything is built from it: binary data
/// (a NUL byte or invalid UTF-8: the first such line is named) and faces
/// with more than `max_face_corners` corners (tobj would otherwise read the
/// whole face first).
pub(super) fn precheck(path: &Path, bytes: &[u8], max_face_corners: usize) -> Result<(), ObjError> {
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::io::obj::fixture::TET;
    use crate::io::{ObjError, ObjOptions, import_obj_bytes};

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
}
