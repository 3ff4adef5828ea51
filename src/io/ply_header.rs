//! The header of a PLY file: its encoding, and its elements with their
//! properties, each located by its header line.

use std::path::Path;

use super::import_error::{ImportError, excerpt};
use super::location::Location;
use super::text::count;

/// The most header bytes read before `end_header` must have come.
const MAX_HEADER_BYTES: usize = 1 << 20;

/// How the body is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    LittleEndian,
    BigEndian,
}

/// A scalar type of a property.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(word: &str) -> Option<Scalar> {
        Some(match word {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Its size in a binary body.
    pub(crate) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    pub(crate) fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The value at the start of `b` (at least [`Scalar::size`] bytes),
    /// exactly as `f64` (every type here widens exactly).
    #[inline]
    pub(crate) fn read(self, b: &[u8], encoding: Encoding) -> f64 {
        macro_rules! get {
            ($t:ty, $n:expr) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(&b[..$n]);
                if encoding == Encoding::BigEndian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }
            }};
        }
        match self {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(get!(i16, 2)),
            Scalar::U16 => f64::from(get!(u16, 2)),
            Scalar::I32 => f64::from(get!(i32, 4)),
            Scalar::U32 => f64::from(get!(u32, 4)),
            Scalar::F32 => f64::from(get!(f32, 4)),
            Scalar::F64 => get!(f64, 8),
        }
    }
}

/// A property of an element.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Property {
    Scalar {
        name: String,
        ty: Scalar,
    },
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

/// An element of the header.
#[derive(Clone, Debug)]
pub(crate) struct Element {
    pub name: String,
    pub count: u64,
    pub properties: Vec<Property>,
    /// Its `element` line.
    pub line: usize,
}

impl Element {
    /// The fewest bytes one record takes in a binary body (lists empty).
    pub(crate) fn min_record_bytes(&self) -> usize {
        self.properties
            .iter()
            .map(|p| match p {
                Property::Scalar { ty, .. } => ty.size(),
                Property::List { count, .. } => count.size(),
            })
            .sum()
    }
}

/// A parsed header: the encoding, the elements, the byte where the body
/// starts and the number of header lines.
#[derive(Clone, Debug)]
pub(crate) struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    pub body: usize,
    pub lines: usize,
}

/// Reads the header, up to and including its `end_header` line.
pub(crate) fn parse(path: &Path, bytes: &[u8]) -> Result<Header, ImportError> {
    let bad =
        |line: usize, message: String| ImportError::malformed(path, Location::Line(line), message);
    let window = &bytes[..bytes.len().min(MAX_HEADER_BYTES)];
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut start = 0;
    let mut line = 0;
    loop {
        line += 1;
        let Some(end) = memchr::memchr(b'\n', &window[start..]).map(|i| start + i) else {
            return Err(if bytes.len() > MAX_HEADER_BYTES {
                bad(
                    line,
                    format!("no `end_header` within the first {MAX_HEADER_BYTES} bytes"),
                )
            } else {
                bad(
                    line,
                    "the file ends inside the header (no `end_header` line)".into(),
                )
            });
        };
        let raw = &window[start..end];
        start = end + 1;
        let Ok(text) = std::str::from_utf8(raw) else {
            return Err(bad(
                line,
                "binary data in the header (not UTF-8 text)".into(),
            ));
        };
        let text = text.trim_end_matches('\r');
        let words: Vec<&str> = text.split_ascii_whitespace().collect();
        let quoted = || excerpt(text.as_bytes());
        if line == 1 {
            if text.trim() != "ply" {
                return Err(bad(
                    1,
                    format!(
                        "not a PLY file: the first line must be `ply`, found `{}`",
                        quoted()
                    ),
                ));
            }
            continue;
        }
        match words.as_slice() {
            [] => {}
            ["comment" | "obj_info", ..] => {}
            ["format", kind, version] => {
                if *version != "1.0" {
                    return Err(bad(line, format!("unknown PLY version `{}`", quoted())));
                }
                encoding = Some(match *kind {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::LittleEndian,
                    "binary_big_endian" => Encoding::BigEndian,
                    _ => return Err(bad(line, format!("unknown PLY format `{}`", quoted()))),
                });
            }
            ["element", name, n] => elements.push(Element {
                name: (*name).to_string(),
                count: count(path, line, n, "the element count")?,
                properties: Vec::new(),
                line,
            }),
            ["property", "list", count_type, item_type, name] => {
                let (Some(c), Some(i)) = (Scalar::parse(count_type), Scalar::parse(item_type))
                else {
                    return Err(bad(
                        line,
                        format!("unknown property type in `{}`", quoted()),
                    ));
                };
                if !c.is_integer() {
                    return Err(bad(
                        line,
                        format!("a list's count must be an integer type: `{}`", quoted()),
                    ));
                }
                let element = elements
                    .last_mut()
                    .ok_or_else(|| bad(line, "a property before any `element` line".into()))?;
                element.properties.push(Property::List {
                    name: (*name).to_string(),
                    count: c,
                    item: i,
                });
            }
            ["property", ty, name] => {
                let ty = Scalar::parse(ty)
                    .ok_or_else(|| bad(line, format!("unknown property type in `{}`", quoted())))?;
                let element = elements
                    .last_mut()
                    .ok_or_else(|| bad(line, "a property before any `element` line".into()))?;
                element.properties.push(Property::Scalar {
                    name: (*name).to_string(),
                    ty,
                });
            }
            ["end_header"] => break,
            _ => return Err(bad(line, format!("cannot read header line `{}`", quoted()))),
        }
    }
    let encoding = encoding.ok_or_else(|| bad(2, "no `format` line in the header".into()))?;
    Ok(Header {
        encoding,
        elements,
        body: start,
        lines: line,
    })
}
