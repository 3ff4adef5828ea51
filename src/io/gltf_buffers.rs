//! glTF 2.0 binary data: the GLB container, the buffers (the GLB's binary
//! chunk, `data:` URIs, files beside the document) and accessors read with
//! every offset checked, so that a view, an accessor or a count that lies
//! is refused at its JSON path rather than read out of bounds.

use std::borrow::Cow;
use std::path::{Component, Path};

use base64::Engine as _;
use serde_json::Value;

use super::import_error::{ImportError, excerpt};
use super::location::Location;

/// A refusal at a JSON path.
pub(crate) fn refuse(
    path: &Path,
    at: impl Into<String>,
    message: impl Into<String>,
) -> ImportError {
    ImportError::malformed(path, Location::Path(at.into()), message)
}

/// The GLB container's JSON chunk and binary chunk.
pub(crate) fn split_glb<'a>(
    path: &Path,
    bytes: &'a [u8],
) -> Result<(&'a [u8], Option<&'a [u8]>), ImportError> {
    let u32_at = |at: usize| {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize)
    };
    let truncated = |at: u64, what: &str, needed: u64| ImportError::Truncated {
        path: path.to_path_buf(),
        at: Location::Byte(at),
        what: what.to_string(),
        needed,
        size: bytes.len() as u64,
    };
    let version = u32_at(4).ok_or_else(|| truncated(0, "the GLB header", 12))?;
    if version != 2 {
        return Err(ImportError::malformed(
            path,
            Location::Byte(4),
            format!("GLB version {version} (only 2 is read)"),
        ));
    }
    let length = u32_at(8).ok_or_else(|| truncated(0, "the GLB header", 12))?;
    if length > bytes.len() {
        return Err(truncated(8, "the GLB header's length", length as u64));
    }
    let bytes = &bytes[..length];
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    while at < bytes.len() {
        let (Some(size), Some(kind)) = (u32_at(at), u32_at(at + 4)) else {
            return Err(truncated(at as u64, "a chunk header", at as u64 + 8));
        };
        let end = (at + 8).checked_add(size).filter(|&e| e <= bytes.len());
        let Some(end) = end else {
            return Err(truncated(
                at as u64,
                "the chunk's length",
                (at + 8 + size) as u64,
            ));
        };
        match kind {
            0x4E4F_534A if json.is_none() => json = Some(&bytes[at + 8..end]),
            0x004E_4942 if bin.is_none() => bin = Some(&bytes[at + 8..end]),
            _ => {}
        }
        at = end;
    }
    let json = json.ok_or_else(|| {
        ImportError::malformed(path, Location::Byte(12), "the GLB has no JSON chunk")
    })?;
    Ok((json, bin))
}

/// Buffer `index`'s bytes: the GLB chunk, a `data:` URI or a file beside
/// the document (a relative path inside its folder, no `..`).
pub(crate) fn buffer<'a>(
    path: &Path,
    doc: &Value,
    index: usize,
    bin: Option<&'a [u8]>,
) -> Result<Cow<'a, [u8]>, ImportError> {
    let at = format!("buffers[{index}]");
    let b = doc
        .get("buffers")
        .and_then(|b| b.get(index))
        .ok_or_else(|| refuse(path, &at, "no such buffer"))?;
    let length = uint(path, b, "byteLength", &at)?.unwrap_or(0);
    let data: Cow<'a, [u8]> = match b.get("uri") {
        None if index == 0 => Cow::Borrowed(
            bin.ok_or_else(|| refuse(path, &at, "no `uri`, and no GLB binary chunk"))?,
        ),
        None => return Err(refuse(path, &at, "no `uri`")),
        Some(Value::String(uri)) => Cow::Owned(uri_bytes(path, uri, &at)?),
        Some(_) => return Err(refuse(path, format!("{at}.uri"), "not a string")),
    };
    if (data.len() as u64) < length {
        return Err(refuse(
            path,
            &at,
            format!(
                "byteLength is {length}, but the data holds {} bytes",
                data.len()
            ),
        ));
    }
    Ok(data)
}

fn uri_bytes(path: &Path, uri: &str, at: &str) -> Result<Vec<u8>, ImportError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, payload)) = rest.split_once(";base64,") else {
            return Err(refuse(
                path,
                format!("{at}.uri"),
                "a `data:` URI that is not base64",
            ));
        };
        return base64::engine::general_purpose::STANDARD
            .decode(payload)
            .map_err(|e| refuse(path, format!("{at}.uri"), format!("bad base64: {e}")));
    }
    let decoded = percent_decode(uri);
    let relative = Path::new(&decoded);
    let inside = !decoded.contains(':')
        && relative
            .components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if !inside {
        return Err(refuse(
            path,
            format!("{at}.uri"),
            format!(
                "`{}`: only `data:` URIs and relative paths inside the document's folder are read",
                excerpt(uri.as_bytes())
            ),
        ));
    }
    let file = path.parent().unwrap_or(Path::new(".")).join(relative);
    let metadata = std::fs::metadata(&file);
    if !metadata.as_ref().is_ok_and(std::fs::Metadata::is_file) {
        return Err(refuse(
            path,
            format!("{at}.uri"),
            format!("`{}` is not a regular file", file.display()),
        ));
    }
    super::read::read_binary_input(&file).map_err(|e| {
        refuse(
            path,
            format!("{at}.uri"),
            format!("cannot read `{}`: {e}", file.display()),
        )
    })
}

fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && let (Some(h), Some(l)) = (
                bytes.get(i + 1).and_then(|&b| hex(b)),
                bytes.get(i + 2).and_then(|&b| hex(b)),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// A non-negative integer member, if present.
pub(crate) fn uint(
    path: &Path,
    object: &Value,
    key: &str,
    at: &str,
) -> Result<Option<u64>, ImportError> {
    match object.get(key) {
        None => Ok(None),
        Some(v) => v.as_u64().map(Some).ok_or_else(|| {
            refuse(
                path,
                format!("{at}.{key}"),
                format!(
                    "not a non-negative integer: {}",
                    excerpt(v.to_string().as_bytes())
                ),
            )
        }),
    }
}

/// An accessor's elements: `count` runs of `size` bytes, `stride` apart,
/// each checked inside its buffer view and buffer.
pub(crate) struct Elements<'a> {
    pub data: &'a [u8],
    pub count: usize,
    pub stride: usize,
    pub component: u64,
}

/// Resolves accessor `index` of the `kind` (`"VEC3"` or `"SCALAR"`) to its
/// bytes; `buffers` caches each buffer's data.
pub(crate) fn accessor<'b>(
    path: &Path,
    doc: &Value,
    index: usize,
    kind: &str,
    buffers: &'b [Cow<'b, [u8]>],
) -> Result<Elements<'b>, ImportError> {
    let at = format!("accessors[{index}]");
    let a = doc
        .get("accessors")
        .and_then(|a| a.get(index))
        .ok_or_else(|| refuse(path, &at, "no such accessor"))?;
    if a.get("sparse").is_some() {
        return Err(refuse(
            path,
            format!("{at}.sparse"),
            "sparse accessors are not read",
        ));
    }
    if a.get("type").and_then(Value::as_str) != Some(kind) {
        return Err(refuse(
            path,
            format!("{at}.type"),
            format!("expected \"{kind}\""),
        ));
    }
    let component = uint(path, a, "componentType", &at)?.unwrap_or(0);
    let component_size = match (kind, component) {
        ("VEC3", 5126) => 4,
        ("SCALAR", 5121) => 1,
        ("SCALAR", 5123) => 2,
        ("SCALAR", 5125) => 4,
        ("VEC3", _) => {
            return Err(refuse(
                path,
                format!("{at}.componentType"),
                format!("{component}: positions must be floats (5126)"),
            ));
        }
        _ => {
            return Err(refuse(
                path,
                format!("{at}.componentType"),
                format!("{component}: indices must be 5121, 5123 or 5125"),
            ));
        }
    };
    let width = if kind == "VEC3" { 3 } else { 1 };
    let element = component_size * width;
    let count = uint(path, a, "count", &at)?.ok_or_else(|| refuse(path, &at, "no `count`"))?;
    let offset = uint(path, a, "byteOffset", &at)?.unwrap_or(0);
    let Some(view_index) = uint(path, a, "bufferView", &at)? else {
        return Err(refuse(
            path,
            &at,
            "no `bufferView` (an accessor of zeros is not read)",
        ));
    };
    let view_at = format!("bufferViews[{view_index}]");
    let view = doc
        .get("bufferViews")
        .and_then(|v| v.get(view_index as usize))
        .ok_or_else(|| {
            refuse(
                path,
                format!("{at}.bufferView"),
                format!("no such buffer view: {view_index}"),
            )
        })?;
    let buffer = uint(path, view, "buffer", &view_at)?
        .ok_or_else(|| refuse(path, &view_at, "no `buffer`"))? as usize;
    let view_offset = uint(path, view, "byteOffset", &view_at)?.unwrap_or(0);
    let view_length = uint(path, view, "byteLength", &view_at)?
        .ok_or_else(|| refuse(path, &view_at, "no `byteLength`"))?;
    let stride = uint(path, view, "byteStride", &view_at)?
        .unwrap_or(element as u64)
        .max(element as u64);
    let data = buffers.get(buffer).ok_or_else(|| {
        refuse(
            path,
            format!("{view_at}.buffer"),
            format!("no such buffer: {buffer}"),
        )
    })?;
    let view_end = view_offset
        .checked_add(view_length)
        .filter(|&e| e <= data.len() as u64);
    let Some(view_end) = view_end else {
        return Err(refuse(
            path,
            &view_at,
            format!(
                "bytes {view_offset} + {view_length} lie beyond buffer {buffer}'s {} bytes",
                data.len()
            ),
        ));
    };
    let needed = if count == 0 {
        Some(0)
    } else {
        (count - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(element as u64))
            .and_then(|x| x.checked_add(offset))
    };
    let start = view_offset + offset.min(view_length);
    match needed {
        Some(n) if view_offset + n <= view_end => Ok(Elements {
            data: &data[start as usize..view_end as usize],
            count: count as usize,
            stride: stride as usize,
            component,
        }),
        _ => Err(refuse(
            path,
            &at,
            format!(
                "{count} elements of {element} bytes, {stride} apart from byte {offset}, do not fit in {view_at}'s {view_length} bytes (a count that lies)"
            ),
        )),
    }
}

impl Elements<'_> {
    /// Element `k` as `f32` triples.
    pub(crate) fn vec3(&self, k: usize) -> [f32; 3] {
        let b = &self.data[k * self.stride..];
        let f = |i: usize| f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
        [f(0), f(4), f(8)]
    }

    /// Element `k` as an index.
    pub(crate) fn index(&self, k: usize) -> u64 {
        let b = &self.data[k * self.stride..];
        match self.component {
            5121 => u64::from(b[0]),
            5123 => u64::from(u16::from_le_bytes([b[0], b[1]])),
            _ => u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        }
    }
}
