//! Running tobj on bytes the line pass accepted, and naming the line and
//! the meaning of an error tobj reports without one.

use std::path::Path;

use super::error::ObjError;

/// Runs tobj over the bytes: polygons kept, points and lines ignored,
/// material libraries not loaded (only material names matter).
pub(super) fn run_tobj(path: &Path, bytes: &[u8]) -> Result<Vec<tobj::Model>, ObjError> {
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

/// The text of a 1-based line as a short, escaped excerpt (see
/// [`excerpt`](crate::io::import_error::excerpt)).
fn excerpt_of_line(bytes: &[u8], line: usize) -> String {
    let text = bytes
        .split(|&b| b == b'\n')
        .nth(line - 1)
        .unwrap_or_default();
    crate::io::import_error::excerpt(text.trim_ascii())
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
