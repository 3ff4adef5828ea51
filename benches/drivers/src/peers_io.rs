//! What the peer programs (`benches/drivers/src/bin/peers_wingedge.rs`,
//! `benches/drivers/src/bin/boolean_bench.rs`, `benches/peers/parry/`) share: the raw input
//! files of `benches/peers/`, answer files and peak memory.

use std::error::Error;
use std::path::Path;

/// The drivers' error type: a message naming the file.
pub type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// Reads a raw little-endian `f64` file whose length is a multiple of
/// `8 * width` bytes.
pub fn read_f64s(path: &Path, width: usize) -> Result<Vec<f64>> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    if bytes.len() % (8 * width) != 0 {
        return Err(format!(
            "{}: {} bytes is not a whole number of {width}-component f64 records",
            path.display(),
            bytes.len()
        )
        .into());
    }
    Ok(bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes([c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7]]))
        .collect())
}

/// Peak resident memory of this process, MiB (Linux).
pub fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

/// Writes one answer file.
pub fn write_answers(path: &Path, bytes: Vec<u8>) -> Result<()> {
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()).into())
}
