//! The text of a face corner: its shape (`v`, `v/vt`, `v//vn`, `v/vt/vn`)
//! and what each index reads as.

/// What a corner's vertex index reads as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum IndexText {
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
pub(super) fn parse_index(text: &[u8]) -> IndexText {
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
pub(super) fn count_statements(bytes: &[u8], keyword: &[u8]) -> usize {
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
pub(super) type CornerParts<'a> = (&'a [u8], Option<&'a [u8]>, Option<&'a [u8]>);

/// A face corner split into its vertex, texture-coordinate and normal
/// index texts: `v`, `v/vt`, `v//vn` or `v/vt/vn`; `None` for any other
/// shape (`1/`, `1/2/`, `1//`, `1/2/3/4`).
pub(super) fn corner_parts(word: &[u8]) -> Option<CornerParts<'_>> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::ObjError;
    use crate::io::obj::fixture::{TET, read};

    #[test]
    fn an_index_is_an_optional_sign_and_decimal_digits() {
        assert_eq!(parse_index(b"+7"), IndexText::Value(7));
        assert_eq!(parse_index(b"-"), IndexText::NotAnIndex);
        assert_eq!(parse_index(b"1e3"), IndexText::NotAnIndex);
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
}
