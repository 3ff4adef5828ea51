//! What the text formats (ASCII STL, ASCII PLY, OFF) share: the text
//! check, numbered lines, and numbers read exactly.

use std::path::Path;

use super::import_error::{ImportError, excerpt};
use super::location::Location;

/// `bytes` as text, or the error naming the first line holding a byte that
/// is not text (a NUL or invalid UTF-8).
pub(crate) fn as_text<'a>(
    path: &Path,
    bytes: &'a [u8],
    what: &str,
) -> Result<&'a str, ImportError> {
    let len = super::read::text_len(bytes);
    if len < bytes.len() {
        let line = 1 + memchr::memchr_iter(b'\n', &bytes[..len]).count();
        return Err(ImportError::malformed(
            path,
            Location::Line(line),
            format!("binary data (not UTF-8 text) in {what}"),
        ));
    }
    // `text_len` checked every byte.
    std::str::from_utf8(bytes).map_err(|_| {
        ImportError::malformed(path, Location::Line(1), "binary data (not UTF-8 text)")
    })
}

/// The lines of `text` with their 1-based numbers, each without its line
/// end (`\n` or `\r\n`).
pub(crate) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.split('\n')
        .enumerate()
        .map(|(i, l)| (i + 1, l.strip_suffix('\r').unwrap_or(l)))
}

/// A number as written (exactly rounded, as Rust's parser is), or an error
/// naming the line and quoting the token. `inf` and `nan` read as such;
/// the caller refuses them where a coordinate must be finite.
pub(crate) fn number(
    path: &Path,
    line: usize,
    token: &str,
    what: &str,
) -> Result<f64, ImportError> {
    token.parse::<f64>().map_err(|_| {
        ImportError::malformed(
            path,
            Location::Line(line),
            format!(
                "cannot read {what}: `{}` is not a number",
                excerpt(token.as_bytes())
            ),
        )
    })
}

/// A non-negative integer as written, or an error naming the line.
pub(crate) fn count(path: &Path, line: usize, token: &str, what: &str) -> Result<u64, ImportError> {
    token.parse::<u64>().map_err(|_| {
        ImportError::malformed(
            path,
            Location::Line(line),
            format!(
                "cannot read {what}: `{}` is not a non-negative integer",
                excerpt(token.as_bytes())
            ),
        )
    })
}

/// How many elements of at least `min_bytes` bytes each fit in `bytes`:
/// the most a declared count may reserve memory for.
pub(crate) fn reservable(declared: u64, bytes: usize, min_bytes: usize) -> usize {
    (declared.min((bytes / min_bytes.max(1)) as u64)) as usize
}
