//! The dense voxel array as a `.npy` file (numpy's format, version 1.0):
//! `numpy.load` reads it as a `uint8` array of shape `(n, n, n)`.

use std::io::Write;
use std::path::Path;

/// Writes `data`, `n³` bytes in C order, as an `(n, n, n)` `uint8` array,
/// atomically ([`write_atomically`](crate::io::write_atomically)).
///
/// # Errors
///
/// The file system's error; `InvalidInput` when `data` is not `n³` bytes.
pub fn write_npy(path: &Path, data: &[u8], n: usize) -> std::io::Result<()> {
    if n.checked_pow(3) != Some(data.len()) {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{} bytes are not a cube of side {n}", data.len()),
        ));
    }
    let mut header =
        format!("{{'descr': '|u1', 'fortran_order': False, 'shape': ({n}, {n}, {n}), }}");
    // Magic (6) + version (2) + header length (2) + header + '\n', padded
    // with spaces to a multiple of 64.
    let unpadded = 10 + header.len() + 1;
    header.push_str(&" ".repeat(unpadded.next_multiple_of(64) - unpadded));
    header.push('\n');
    crate::io::write_atomically(path, |file| {
        file.write_all(b"\x93NUMPY\x01\x00")?;
        let length = u16::try_from(header.len()).map_err(std::io::Error::other)?;
        file.write_all(&length.to_le_bytes())?;
        file.write_all(header.as_bytes())?;
        file.write_all(data)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_is_aligned_and_names_the_shape() {
        let dir = std::env::temp_dir().join(format!("wingedge-npy-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("cube.npy");
        write_npy(&path, &[0, 1, 2, 1, 0, 2, 2, 1], 2).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        let length = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
        assert_eq!((10 + length) % 64, 0);
        let header = std::str::from_utf8(&bytes[10..10 + length]).unwrap();
        assert!(
            header.contains("'shape': (2, 2, 2)") && header.ends_with('\n'),
            "{header}"
        );
        assert_eq!(&bytes[10 + length..], &[0, 1, 2, 1, 0, 2, 2, 1]);
        assert!(write_npy(&path, &[0; 7], 2).is_err());
    }
}
