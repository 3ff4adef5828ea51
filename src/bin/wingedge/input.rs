//! Shared input handling for the query subcommands: reading numeric lines
//! from a file or standard input.

/// Reads all of `source` (`-` for standard input) as text; bytes that are
/// not UTF-8 are an error naming the first line that holds one.
pub fn read_source(source: &str) -> Result<String, String> {
    // Bounded reads: endless input (`/dev/zero`, `yes |`) stops at its
    // first NUL byte or at the size limit.
    let bytes = if source == "-" {
        wingedge::io::read_input_from(std::io::stdin().lock())
            .map_err(|e| format!("standard input: cannot read: {e}"))?
    } else {
        wingedge::io::read_input(std::path::Path::new(source))
            .map_err(|e| format!("{source}: cannot read: {e}"))?
    };
    // The text ends at the first invalid UTF-8 or NUL byte (reads stop at
    // a NUL): binary data, named by its line.
    let text_len = wingedge::io::text_len(&bytes);
    let line = 1 + bytes[..text_len].iter().filter(|&&b| b == b'\n').count();
    let binary = format!("{source}:{line}: binary data (not UTF-8 text)");
    if text_len < bytes.len() {
        return Err(binary);
    }
    String::from_utf8(bytes).map_err(|_| binary)
}

/// Parses lines of exactly `N` finite numbers separated by whitespace.
/// Blank lines and lines starting with `#` are skipped. Returns the numbers
/// with their 1-based line numbers, or a message naming the first bad line.
pub fn parse_lines<const N: usize>(
    source: &str,
    text: &str,
) -> Result<Vec<(usize, [f64; N])>, String> {
    let mut out = Vec::new();
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.trim();
        if content.is_empty() || content.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = content.split_whitespace().collect();
        if fields.len() != N {
            return Err(format!(
                "{source}:{line}: expected {N} numbers, found {} fields: '{content}'",
                fields.len()
            ));
        }
        let mut values = [0.0; N];
        for (value, field) in values.iter_mut().zip(&fields) {
            *value = field
                .parse::<f64>()
                .map_err(|_| format!("{source}:{line}: '{field}' is not a number"))?;
            if !value.is_finite() {
                return Err(format!("{source}:{line}: '{field}' is not finite"));
            }
        }
        out.push((line, values));
    }
    Ok(out)
}
