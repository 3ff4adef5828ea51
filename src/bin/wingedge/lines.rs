//! Reading POINTS and RAYS files: numbers per line, `-` for standard input.

use std::io::Read;
use std::path::Path;

/// Reads the file (or standard input for `-`) and parses every non-blank,
/// non-`#` line as `count` finite numbers. Errors name the file and line.
pub fn read_numbers(path: &Path, count: usize) -> Result<Vec<Vec<f64>>, String> {
    let name = path.display().to_string();
    let text = if name == "-" {
        let mut s = String::new();
        std::io::stdin()
            .read_to_string(&mut s)
            .map_err(|e| format!("<stdin>: cannot read: {e}"))?;
        s
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("{name}: cannot read: {e}"))?
    };
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let values: Result<Vec<f64>, _> = line.split_whitespace().map(str::parse::<f64>).collect();
        match values {
            Ok(v) if v.len() == count && v.iter().all(|x| x.is_finite()) => rows.push(v),
            _ => {
                return Err(format!(
                    "{name}: line {}: expected {count} finite numbers, found \"{line}\"",
                    i + 1
                ));
            }
        }
    }
    Ok(rows)
}
