//! STL, binary and ASCII: read (every triangle located by its byte offset
//! or its `facet` line; the corners, which STL repeats for every triangle,
//! are welded afterwards by position) and written (binary, `f32`).
//!
//! A file is binary when its size is exactly what its header's triangle
//! count needs (84 + 50 n bytes); else ASCII when it starts with `solid`
//! and is text; else binary with a count that lies, which is refused
//! before anything is allocated for it.

use std::path::Path;

use glam::DVec3;
use rayon::prelude::*;

use super::import_error::{ImportError, excerpt};
use super::location::{Location, Sources};
use super::parsed::{ImportOptions, Parsed};
use super::text::{as_text, number, numbered_lines};
use crate::mesh::{FaceAttributes, Polygon};

/// Bytes before the first triangle of a binary STL: an 80-byte header and
/// the triangle count.
const HEADER: usize = 84;
/// Bytes per triangle of a binary STL: normal, three corners, attribute.
const RECORD: usize = 50;

/// Reads an STL file, binary or ASCII.
pub(crate) fn read(
    path: &Path,
    bytes: &[u8],
    options: &ImportOptions,
) -> Result<Parsed, ImportError> {
    let declared = bytes
        .get(80..HEADER)
        .map(|c| u64::from(u32::from_le_bytes([c[0], c[1], c[2], c[3]])));
    let needed = declared.map(|n| HEADER as u64 + RECORD as u64 * n);
    if needed == Some(bytes.len() as u64) {
        return read_binary(path, bytes);
    }
    let starts_solid = bytes
        .trim_ascii_start()
        .get(..5)
        .is_some_and(|w| w.eq_ignore_ascii_case(b"solid"));
    if starts_solid && super::read::text_len(bytes) == bytes.len() {
        return read_ascii(path, bytes, options);
    }
    match (declared, needed) {
        (Some(n), Some(needed)) if needed > bytes.len() as u64 => Err(ImportError::Truncated {
            path: path.to_path_buf(),
            at: Location::Byte(80),
            what: format!("the binary header's count of {n} triangles"),
            needed,
            size: bytes.len() as u64,
        }),
        (Some(n), Some(needed)) => Err(ImportError::malformed(
            path,
            Location::Byte(needed),
            format!(
                "{} bytes follow the last of the binary header's {n} triangles (a count that lies, or not an STL file)",
                bytes.len() as u64 - needed
            ),
        )),
        _ => Err(ImportError::Truncated {
            path: path.to_path_buf(),
            at: Location::Byte(0),
            what: "a binary STL header (80 bytes and a triangle count)".into(),
            needed: HEADER as u64,
            size: bytes.len() as u64,
        }),
    }
}

/// A binary STL whose size matches its count: corners as read (`f32`,
/// widened exactly), in parallel.
fn read_binary(path: &Path, bytes: &[u8]) -> Result<Parsed, ImportError> {
    let records = &bytes[HEADER..];
    let n = records.len() / RECORD;
    let f32_at = |r: &[u8], at: usize| {
        f64::from(f32::from_le_bytes([r[at], r[at + 1], r[at + 2], r[at + 3]]))
    };
    let mut positions = vec![DVec3::ZERO; 3 * n];
    positions
        .par_chunks_mut(3 * 4096)
        .zip(records.par_chunks(RECORD * 4096))
        .for_each(|(out, chunk)| {
            for (corners, r) in out.chunks_exact_mut(3).zip(chunk.chunks_exact(RECORD)) {
                for (k, corner) in corners.iter_mut().enumerate() {
                    let at = 12 + 12 * k;
                    *corner = DVec3::new(f32_at(r, at), f32_at(r, at + 4), f32_at(r, at + 8));
                }
            }
        });
    if let Some(corner) = positions.par_iter().position_first(|p| !p.is_finite()) {
        let triangle = corner / 3;
        return Err(ImportError::NonFinite {
            path: path.to_path_buf(),
            at: Location::Element {
                kind: "triangle",
                index: triangle,
                byte: (HEADER + RECORD * triangle) as u64,
            },
            vertex: corner,
            position: positions[corner],
        });
    }
    let polygons = (0..n)
        .into_par_iter()
        .map(|i| Polygon {
            vertices: [3 * i, 3 * i + 1, 3 * i + 2].into_iter().collect(),
            attributes: FaceAttributes {
                source_index: Some(i),
                ..FaceAttributes::default()
            },
        })
        .collect();
    let mut sources = Sources::default();
    sources.push_records(0, "triangle", HEADER as u64, RECORD as u64);
    Ok(Parsed {
        vertex_numbers: (0..positions.len()).collect(),
        positions,
        polygons,
        vertex_lines: Vec::new(),
        sources,
        notes: Vec::new(),
    })
}

/// Where the ASCII reader is in the grammar
/// `solid NAME (facet normal N N N outer loop (vertex X Y Z)+ endloop endfacet)* endsolid NAME`.
#[derive(Clone, Copy, PartialEq)]
enum State {
    /// Before `solid`.
    Outside,
    /// Inside a solid, between facets.
    Solid,
    /// After `facet normal …`.
    Facet,
    /// After `outer loop`, reading vertices.
    Loop,
    /// After `endloop`.
    LoopDone,
}

/// An ASCII STL: one polygon per facet (located by its `facet` line), one
/// vertex per `vertex` line; each `solid`'s name becomes its facets' group.
fn read_ascii(path: &Path, bytes: &[u8], options: &ImportOptions) -> Result<Parsed, ImportError> {
    let text = as_text(path, bytes, "an ASCII STL file")?;
    let mut parsed = Parsed {
        sources: Sources::lines(),
        ..Parsed::default()
    };
    let mut state = State::Outside;
    let mut group: Option<std::sync::Arc<str>> = None;
    let mut facet = Polygon::default();
    let mut last_line = 0;
    for (line, content) in numbered_lines(text) {
        let mut words = content.split_ascii_whitespace();
        let Some(word) = words.next() else { continue };
        last_line = line;
        let keyword = |k: &str| word.eq_ignore_ascii_case(k);
        let unexpected = |expected: &str| {
            ImportError::malformed(
                path,
                Location::Line(line),
                format!(
                    "expected {expected}, found `{}`",
                    excerpt(content.trim().as_bytes())
                ),
            )
        };
        state = match state {
            State::Outside if keyword("solid") => {
                let name = content.trim_start()[5..].trim();
                group = (!name.is_empty()).then(|| name.into());
                State::Solid
            }
            State::Outside => return Err(unexpected("`solid NAME`")),
            State::Solid if keyword("facet") => {
                facet = Polygon {
                    vertices: Default::default(),
                    attributes: FaceAttributes {
                        source_index: Some(parsed.polygons.len()),
                        line: Some(line),
                        group: group.clone(),
                        material: None,
                    },
                };
                State::Facet
            }
            State::Solid if keyword("endsolid") => State::Outside,
            State::Solid => return Err(unexpected("`facet normal NX NY NZ` or `endsolid`")),
            State::Facet if keyword("outer") => State::Loop,
            State::Facet => return Err(unexpected("`outer loop`")),
            State::Loop if keyword("vertex") => {
                let vertex = parsed.positions.len();
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let token = words.next().ok_or_else(|| unexpected("`vertex X Y Z`"))?;
                    *c = number(path, line, token, "vertex position")?;
                }
                let position = DVec3::from_array(xyz);
                if !position.is_finite() {
                    return Err(ImportError::NonFinite {
                        path: path.to_path_buf(),
                        at: Location::Line(line),
                        vertex,
                        position,
                    });
                }
                if facet.vertices.len() >= options.max_face_corners {
                    return Err(ImportError::FaceTooLarge {
                        path: path.to_path_buf(),
                        at: Location::Line(facet.attributes.line.unwrap_or(line)),
                        count: facet.vertices.len() + 1,
                        limit: options.max_face_corners,
                    });
                }
                parsed.positions.push(position);
                parsed.vertex_lines.push(line);
                parsed.vertex_numbers.push(vertex);
                facet.vertices.push(vertex);
                State::Loop
            }
            State::Loop if keyword("endloop") => {
                if facet.vertices.len() < 3 {
                    return Err(ImportError::TooFewCorners {
                        path: path.to_path_buf(),
                        at: Location::Line(facet.attributes.line.unwrap_or(line)),
                        count: facet.vertices.len(),
                    });
                }
                State::LoopDone
            }
            State::Loop => return Err(unexpected("`vertex X Y Z` or `endloop`")),
            State::LoopDone if keyword("endfacet") => {
                parsed.polygons.push(std::mem::take(&mut facet));
                State::Solid
            }
            State::LoopDone => return Err(unexpected("`endfacet`")),
        };
    }
    if matches!(state, State::Facet | State::Loop | State::LoopDone) {
        return Err(ImportError::malformed(
            path,
            Location::Line(last_line),
            "the file ends inside a facet",
        ));
    }
    Ok(parsed)
}

/// The bytes of a binary STL of `triangles` (corners as `f32`, already
/// checked finite by the caller) with each triangle's unit normal.
pub(crate) fn write(positions: &[DVec3], triangles: &[[usize; 3]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER + RECORD * triangles.len());
    let mut header = [b' '; 80];
    let title = b"binary STL written by wingedge";
    header[..title.len()].copy_from_slice(title);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for t in triangles {
        let [a, b, c] = t.map(|i| positions[i]);
        let normal = (b - a).cross(c - a).normalize_or_zero();
        for v in [normal, a, b, c] {
            for x in v.to_array() {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<Parsed, ImportError> {
        read(Path::new("t.stl"), bytes, &ImportOptions::default())
    }

    fn tetrahedron() -> (Vec<DVec3>, Vec<[usize; 3]>) {
        let p = vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        (p, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    }

    #[test]
    fn binary_reads_back_what_was_written() {
        let (p, t) = tetrahedron();
        let bytes = write(&p, &t);
        assert_eq!(bytes.len(), 84 + 4 * 50);
        let parsed = parse(&bytes).unwrap();
        assert_eq!(parsed.polygons.len(), 4);
        assert_eq!(parsed.positions.len(), 12);
        assert_eq!(parsed.positions[3..6], [p[0], p[1], p[3]]);
        assert_eq!(
            parsed.sources.locate(2, None).unwrap().to_string(),
            "triangle 2 (byte 184)"
        );
    }

    #[test]
    fn counts_that_lie_are_refused_before_allocating() {
        let (p, t) = tetrahedron();
        let mut bytes = write(&p, &t);
        bytes[80..84].copy_from_slice(&1_000_000_000u32.to_le_bytes());
        let e = parse(&bytes).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.stl: byte 80: the file ends after 284 bytes, but the binary header's count of 1000000000 triangles needs 50000000084 bytes (truncated, or a count that lies)"
        );
        bytes[80..84].copy_from_slice(&3u32.to_le_bytes());
        let e = parse(&bytes).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.stl: byte 234: 50 bytes follow the last of the binary header's 3 triangles (a count that lies, or not an STL file)"
        );
        let e = parse(b"abc").unwrap_err();
        assert!(e.to_string().contains("needs 84 bytes"), "{e}");
    }

    #[test]
    fn ascii_facets_are_polygons_located_by_line() {
        let text = "solid cube\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0.1 1 0\n  endloop\n endfacet\nendsolid cube\n";
        let parsed = parse(text.as_bytes()).unwrap();
        assert_eq!(parsed.polygons[0].attributes.line, Some(2));
        assert_eq!(parsed.polygons[0].attributes.group.as_deref(), Some("cube"));
        assert_eq!(parsed.vertex_lines, [4, 5, 6]);
        assert_eq!(parsed.positions[2].x, 0.1, "ASCII keeps f64");
        let e = parse(text.replace("0.1 1 0", "nan 1 0").as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.stl:6: vertex 2 has a non-finite coordinate (NaN, 1, 0)"
        );
        let e = parse(
            text.replace("outer loop", "outer lop\n")
                .replace("  outer", "outer")
                .as_bytes(),
        );
        assert!(e.is_ok(), "only the keyword's first word is read");
        let e = parse(text.replace("   vertex 0.1 1 0\n", "").as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.stl:2: a face needs at least 3 corners, this one has 2"
        );
        let e = parse(b"solid x\n facet normal 0 0 1\n  vertex 1 2 3\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.stl:3: expected `outer loop`, found `vertex 1 2 3`"
        );
        let e = parse(b"solid x\n facet normal 0 0 1\n").unwrap_err();
        assert_eq!(e.to_string(), "t.stl:2: the file ends inside a facet");
    }
}
