//! Reading an input file whole, without trusting what the path names.
//!
//! A path may name a device or a pipe that never ends (`/dev/zero`,
//! `/dev/urandom`, `yes |`): [`read_input`] stops at the first NUL byte
//! (every input format here is text, so the caller reports binary data at
//! that line) and refuses input beyond [`MAX_INPUT_BYTES`], so memory stays
//! bounded whatever the path names.

use std::fs::File;
use std::io::{self, Read};
use std::path::Path;

/// The largest input file read: 2 GiB, about 50 million triangles of OBJ
/// text, whose winged-edge solid would need some 35 GB of memory.
pub const MAX_INPUT_BYTES: usize = 1 << 31;

/// The bytes of the file at `path`, up to and including its first NUL byte
/// if it has one.
///
/// # Errors
///
/// What opening or reading the file gives, and [`io::ErrorKind::InvalidData`]
/// for input longer than [`MAX_INPUT_BYTES`].
pub fn read_input(path: &Path) -> io::Result<Vec<u8>> {
    let file = File::open(path)?;
    // Room for the whole file up front when it says its size (a regular
    // file): grown by doubling, the buffer would briefly hold the old and
    // the new copy and end up to twice the file's size.
    let hint = file
        .metadata()
        .ok()
        .filter(std::fs::Metadata::is_file)
        .map_or(0, |m| usize::try_from(m.len()).unwrap_or(usize::MAX));
    read_bounded_into(
        Vec::with_capacity(hint.min(MAX_INPUT_BYTES).saturating_add(1)),
        file,
        MAX_INPUT_BYTES,
    )
}

/// [`read_input`] with a smaller limit than [`MAX_INPUT_BYTES`] (JSON
/// documents: `MAX_JSON_BYTES`).
///
/// # Errors
///
/// As [`read_input`], for input longer than `limit`.
pub fn read_input_at_most(path: &Path, limit: usize) -> io::Result<Vec<u8>> {
    read_bounded(File::open(path)?, limit.min(MAX_INPUT_BYTES))
}

/// The bytes of the file at `path`, NUL bytes included (for the binary
/// mesh formats), refusing input beyond [`MAX_INPUT_BYTES`].
///
/// # Errors
///
/// As [`read_input`].
pub fn read_binary_input(path: &Path) -> io::Result<Vec<u8>> {
    let file = File::open(path)?;
    let hint = file.metadata().map_or(0, |m| m.len());
    if hint > MAX_INPUT_BYTES as u64 {
        return Err(too_large(MAX_INPUT_BYTES));
    }
    let mut bytes = Vec::with_capacity(hint as usize);
    file.take(MAX_INPUT_BYTES as u64 + 1)
        .read_to_end(&mut bytes)?;
    if bytes.len() > MAX_INPUT_BYTES {
        return Err(too_large(MAX_INPUT_BYTES));
    }
    Ok(bytes)
}

fn too_large(limit: usize) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!("the input is larger than the limit of {limit} bytes"),
    )
}

/// [`read_input`] on any reader (standard input, say).
///
/// # Errors
///
/// As [`read_input`].
pub fn read_input_from(reader: impl Read) -> io::Result<Vec<u8>> {
    read_bounded(reader, MAX_INPUT_BYTES)
}

/// How many leading bytes of `bytes` are text: up to the first NUL byte or
/// invalid UTF-8 sequence (all of them for text). Every input format here
/// is text; what follows is binary data, reported at its line.
pub fn text_len(bytes: &[u8]) -> usize {
    let utf8 = std::str::from_utf8(bytes).map_or_else(|e| e.valid_up_to(), str::len);
    memchr::memchr(0, bytes).map_or(utf8, |nul| nul.min(utf8))
}

/// [`read_input`] on any reader, with the size limit given.
fn read_bounded(reader: impl Read, limit: usize) -> io::Result<Vec<u8>> {
    read_bounded_into(Vec::new(), reader, limit)
}

/// [`read_bounded`] appending to `bytes` (empty, with the capacity the
/// caller expects to need).
fn read_bounded_into(
    mut bytes: Vec<u8>,
    mut reader: impl Read,
    limit: usize,
) -> io::Result<Vec<u8>> {
    let mut chunk = vec![0u8; 1 << 16];
    loop {
        let n = match reader.read(&mut chunk) {
            Ok(0) => return Ok(bytes),
            Ok(n) => n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if let Some(nul) = memchr::memchr(0, &chunk[..n]) {
            bytes.extend_from_slice(&chunk[..=nul]);
            return Ok(bytes);
        }
        if bytes.len() + n > limit {
            return Err(too_large(limit));
        }
        bytes.extend_from_slice(&chunk[..n]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endless_zeros_stop_at_the_first_nul() {
        let bytes = read_bounded(io::repeat(0), 1 << 20).unwrap();
        assert_eq!(bytes, vec![0]);
        let bytes = read_bounded(b"v 1 2 3\n\0rest".as_slice(), 1 << 20).unwrap();
        assert_eq!(bytes, b"v 1 2 3\n\0");
    }

    #[test]
    fn endless_text_is_refused_at_the_limit() {
        let e = read_bounded(io::repeat(b'v'), 1 << 20).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidData);
        assert!(e.to_string().contains("limit of 1048576 bytes"), "{e}");
        let text = b"v 0 0 0\n".repeat(1000);
        assert_eq!(read_bounded(text.as_slice(), 1 << 20).unwrap(), text);
    }

    #[test]
    fn text_ends_at_a_nul_or_invalid_utf8() {
        assert_eq!(text_len(b"v 1 2 3\n"), 8);
        assert_eq!(text_len(b"v 1\0 2"), 3);
        assert_eq!(text_len(b"v \xff\0"), 2);
        assert_eq!(text_len("é\0".as_bytes()), 2);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn dev_zero_is_read_as_one_nul() {
        assert_eq!(read_input(Path::new("/dev/zero")).unwrap(), vec![0]);
    }
}
