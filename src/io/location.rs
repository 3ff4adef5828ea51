//! Where something sits in a mesh file: a line of a text format, a byte
//! offset or an element of a binary one, an XML path in a 3MF model, a
//! JSON path in a glTF document; and [`Sources`], which gives every
//! imported polygon its location without storing a string per polygon.

use std::fmt;

/// A place in a mesh file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Location {
    /// A 1-based line of a text file (OBJ, ASCII STL, ASCII PLY, OFF).
    Line(usize),
    /// A byte offset from the start of a binary file.
    Byte(u64),
    /// The `index`-th (0-based) element of a kind (`triangle`, `face`,
    /// `vertex`) of a binary file, which starts at byte `byte`.
    Element {
        /// The kind of element.
        kind: &'static str,
        /// Its 0-based number among the elements of its kind.
        index: usize,
        /// Its first byte.
        byte: u64,
    },
    /// An XML path (3MF) or a JSON path (glTF), with whatever more the
    /// reader could say (the zip entry, the build item, the triangle).
    Path(String),
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Location::Line(line) => write!(f, "line {line}"),
            Location::Byte(byte) => write!(f, "byte {byte}"),
            Location::Element { kind, index, byte } => {
                write!(f, "{kind} {index} (byte {byte})")
            }
            Location::Path(path) => f.write_str(path),
        }
    }
}

/// A file and a place in it, as error messages begin: `FILE:LINE` for a
/// line (as OBJ messages have always been), else `FILE: PLACE`.
pub(crate) struct At<'a>(pub &'a std::path::Path, pub &'a Location);

impl fmt::Display for At<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.1 {
            Location::Line(line) => write!(f, "{}:{line}", self.0.display()),
            other => write!(f, "{}: {other}", self.0.display()),
        }
    }
}

/// The location of every polygon of an import, by runs of polygons that
/// came from one part of the file.
///
/// # Invariants
///
/// Runs are sorted by their first polygon, and the first starts at 0.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sources {
    runs: Vec<Run>,
}

#[derive(Clone, Debug, PartialEq)]
struct Run {
    first: usize,
    kind: RunKind,
}

#[derive(Clone, Debug, PartialEq)]
enum RunKind {
    /// Each polygon's `attributes.line`.
    Lines,
    /// Records of one size: the `k`-th starts at `byte + k × stride`.
    Records {
        kind: &'static str,
        byte: u64,
        stride: u64,
    },
    /// Records of varying size, each with its first byte.
    Offsets { kind: &'static str, bytes: Vec<u64> },
    /// `before` + the polygon's number in the run (from `base`) + `after`.
    Path {
        before: String,
        base: usize,
        after: String,
    },
}

impl Sources {
    /// Every polygon located by its `line` attribute (the text formats).
    #[must_use]
    pub fn lines() -> Sources {
        Sources {
            runs: vec![Run {
                first: 0,
                kind: RunKind::Lines,
            }],
        }
    }

    /// Polygons from `first` on are records of `stride` bytes, the first at
    /// `byte`.
    pub(crate) fn push_records(
        &mut self,
        first: usize,
        kind: &'static str,
        byte: u64,
        stride: u64,
    ) {
        self.push(first, RunKind::Records { kind, byte, stride });
    }

    /// Polygons from `first` on are records starting at `bytes`.
    pub(crate) fn push_offsets(&mut self, first: usize, kind: &'static str, bytes: Vec<u64>) {
        self.push(first, RunKind::Offsets { kind, bytes });
    }

    /// Polygons from `first` on are at `before{k + base}{after}`, `k`
    /// counted from `first`.
    pub(crate) fn push_path(&mut self, first: usize, before: String, base: usize, after: String) {
        self.push(
            first,
            RunKind::Path {
                before,
                base,
                after,
            },
        );
    }

    fn push(&mut self, first: usize, kind: RunKind) {
        debug_assert!(self.runs.last().is_none_or(|r| r.first <= first));
        self.runs.push(Run { first, kind });
    }

    /// Where polygon `polygon` came from, given its `line` attribute.
    #[must_use]
    pub fn locate(&self, polygon: usize, line: Option<usize>) -> Option<Location> {
        let at = self.runs.partition_point(|r| r.first <= polygon);
        let run = self.runs.get(at.checked_sub(1)?)?;
        let k = polygon - run.first;
        Some(match &run.kind {
            RunKind::Lines => Location::Line(line?),
            RunKind::Records { kind, byte, stride } => Location::Element {
                kind,
                index: k,
                byte: byte + stride * k as u64,
            },
            RunKind::Offsets { kind, bytes } => Location::Element {
                kind,
                index: k,
                byte: *bytes.get(k)?,
            },
            RunKind::Path {
                before,
                base,
                after,
            } => Location::Path(format!("{before}{}{after}", k + base)),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_locate_their_polygons() {
        let mut s = Sources::default();
        s.push_records(0, "triangle", 84, 50);
        s.push_path(3, "/model/triangle[".into(), 1, "]".into());
        assert_eq!(
            s.locate(2, None).unwrap().to_string(),
            "triangle 2 (byte 184)"
        );
        assert_eq!(s.locate(4, None).unwrap().to_string(), "/model/triangle[2]");
        assert_eq!(
            Sources::lines().locate(7, Some(12)),
            Some(Location::Line(12))
        );
        let path = std::path::Path::new("m.obj");
        assert_eq!(At(path, &Location::Line(3)).to_string(), "m.obj:3");
        assert_eq!(At(path, &Location::Byte(9)).to_string(), "m.obj: byte 9");
    }
}
