//! Texture-coordinate and normal indices of face corners: their form is
//! checked as the line pass reads them, their range once the whole file is
//! read (an attribute may be defined after the face using it).

use std::path::Path;

use super::corner::{IndexText, corner_parts, count_statements, parse_index};
use super::error::ObjError;

/// A kind of face-corner attribute (`vt` or `vn`): how many the file
/// defines so far and whether a corner named one beyond them.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct AttributeCount {
    /// `vt` or `vn` lines read so far.
    pub(super) defined: usize,
    /// The largest positive index used so far (checked at the end, since
    /// an attribute may be defined after the face using it).
    pub(super) largest_used: usize,
    /// A negative index reached back before the first definition.
    pub(super) negative_out_of_range: bool,
}

impl AttributeCount {
    /// Whether some corner names an attribute the file does not define.
    /// As tobj, a file that defines none of this kind has its indices
    /// ignored (only positions are read).
    pub(super) fn out_of_range(&self) -> bool {
        self.defined > 0 && (self.negative_out_of_range || self.largest_used > self.defined)
    }
}

/// Checks the form of a texture-coordinate or normal index written as
/// `text` on `line` and records its range in `count` (checked once the
/// whole file is read).
pub(super) fn check_attribute_index(
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
            crate::io::import_error::excerpt(text)
        ))),
        IndexText::TooLarge { negative } => Err(error(format!(
            "{what} index {} is out of range: {} `{keyword}` lines are defined",
            crate::io::import_error::excerpt(text),
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
pub(super) fn first_attribute_out_of_range(
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

#[cfg(test)]
mod tests {
    use crate::io::ObjError;
    use crate::io::obj::fixture::{TET, read};

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
}
