//! OFF (Object File Format): read (the `OFF` keyword, optionally with the
//! `C`, `N`, `ST` prefixes whose extra vertex values are skipped; the
//! counts; one vertex per line; one face per line, `k i1 … ik` and an
//! optional colour), every vertex and face located by its line; written
//! with shortest round-trip decimals, which keep every `f64` bit.

use std::fmt::Write as _;
use std::path::Path;

use glam::DVec3;

use super::import_error::{ImportError, excerpt};
use super::location::{Location, Sources};
use super::parsed::{ImportOptions, Parsed};
use super::text::{as_text, count, number, numbered_lines, reservable};
use crate::mesh::{FaceAttributes, Polygon};

/// Reads an OFF file.
pub(crate) fn read(
    path: &Path,
    bytes: &[u8],
    options: &ImportOptions,
) -> Result<Parsed, ImportError> {
    let text = as_text(path, bytes, "an OFF file")?;
    // Lines with content: comments (`#` to the end of the line) removed.
    let mut lines = numbered_lines(text).filter_map(|(n, l)| {
        let content = l.split('#').next().unwrap_or("").trim();
        (!content.is_empty()).then_some((n, content))
    });
    let bad =
        |line: usize, message: String| ImportError::malformed(path, Location::Line(line), message);
    let Some((first, header)) = lines.next() else {
        return Err(bad(1, "an empty file: expected the keyword `OFF`".into()));
    };
    let mut words: Vec<&str> = header.split_ascii_whitespace().collect();
    let keyword = words[0];
    let prefix = keyword
        .strip_suffix("OFF")
        .filter(|p| p.chars().all(|c| "STCN".contains(c)));
    let Some(prefix) = prefix else {
        return Err(bad(
            first,
            format!(
                "expected the keyword `OFF`, found `{}`",
                excerpt(keyword.as_bytes())
            ),
        ));
    };
    words.remove(0);
    let mut counts_line = first;
    if words.is_empty() {
        let Some((line, counts)) = lines.next() else {
            return Err(bad(
                first,
                "the file ends before the vertex and face counts".into(),
            ));
        };
        counts_line = line;
        words = counts.split_ascii_whitespace().collect();
    }
    if words.len() < 2 {
        return Err(bad(
            counts_line,
            "expected the counts `VERTICES FACES EDGES`".into(),
        ));
    }
    let vertex_count = count(path, counts_line, words[0], "the vertex count")?;
    let face_count = count(path, counts_line, words[1], "the face count")?;
    // Per-vertex values beyond x y z that the prefixes announce are skipped.
    let _ = prefix;
    let mut parsed = Parsed {
        sources: Sources::lines(),
        ..Parsed::default()
    };
    parsed
        .positions
        .reserve(reservable(vertex_count, text.len(), 6));
    parsed
        .polygons
        .reserve(reservable(face_count, text.len(), 8));
    let ends = |what: &str, done: u64, declared: u64| {
        bad(
            text.lines().count().max(1),
            format!(
                "the file ends after {done} of the {declared} {what} the counts (line {counts_line}) declare"
            ),
        )
    };
    for v in 0..vertex_count {
        let Some((line, content)) = lines.next() else {
            return Err(ends("vertices", v, vertex_count));
        };
        let mut xyz = [0.0; 3];
        let mut words = content.split_ascii_whitespace();
        for c in &mut xyz {
            let word = words.next().ok_or_else(|| {
                bad(
                    line,
                    format!(
                        "expected a vertex `X Y Z`, found `{}`",
                        excerpt(content.as_bytes())
                    ),
                )
            })?;
            *c = number(path, line, word, "vertex position")?;
        }
        let position = DVec3::from_array(xyz);
        if !position.is_finite() {
            return Err(ImportError::NonFinite {
                path: path.to_path_buf(),
                at: Location::Line(line),
                vertex: v as usize,
                position,
            });
        }
        parsed.positions.push(position);
        parsed.vertex_lines.push(line);
    }
    let available = parsed.positions.len();
    for f in 0..face_count {
        let Some((line, content)) = lines.next() else {
            return Err(ends("faces", f, face_count));
        };
        let mut words = content.split_ascii_whitespace();
        let k = count(
            path,
            line,
            words.next().unwrap_or(""),
            "a face's corner count",
        )?;
        let at = || Location::Line(line);
        if k < 3 {
            return Err(ImportError::TooFewCorners {
                path: path.to_path_buf(),
                at: at(),
                count: k as usize,
            });
        }
        if k > options.max_face_corners as u64 {
            return Err(ImportError::FaceTooLarge {
                path: path.to_path_buf(),
                at: at(),
                count: usize::try_from(k).unwrap_or(usize::MAX),
                limit: options.max_face_corners,
            });
        }
        let mut vertices = smallvec::SmallVec::with_capacity(k as usize);
        for _ in 0..k {
            let word = words.next().ok_or_else(|| {
                bad(
                    line,
                    format!(
                        "a face of {k} corners lists fewer: `{}`",
                        excerpt(content.as_bytes())
                    ),
                )
            })?;
            let index: i64 = word.parse().map_err(|_| {
                bad(
                    line,
                    format!("cannot read vertex index `{}`", excerpt(word.as_bytes())),
                )
            })?;
            if !(0..available as i64).contains(&index) {
                return Err(ImportError::IndexOutOfRange {
                    path: path.to_path_buf(),
                    at: at(),
                    index,
                    available,
                });
            }
            vertices.push(index as usize);
        }
        parsed.polygons.push(Polygon {
            vertices,
            attributes: FaceAttributes {
                source_index: Some(f as usize),
                line: Some(line),
                ..FaceAttributes::default()
            },
        });
    }
    parsed.vertex_numbers = (0..parsed.positions.len()).collect();
    Ok(parsed)
}

/// OFF text of `polygons`: shortest round-trip decimals.
pub(crate) fn write(positions: &[DVec3], polygons: &[Vec<usize>]) -> Vec<u8> {
    let mut out = String::with_capacity(positions.len() * 40 + polygons.len() * 24);
    let _ = writeln!(
        out,
        "OFF\n# written by wingedge\n{} {} 0",
        positions.len(),
        polygons.len()
    );
    for p in positions {
        let _ = writeln!(out, "{:?} {:?} {:?}", p.x, p.y, p.z);
    }
    for polygon in polygons {
        let _ = write!(out, "{}", polygon.len());
        for v in polygon {
            let _ = write!(out, " {v}");
        }
        out.push('\n');
    }
    out.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Parsed, ImportError> {
        read(
            Path::new("t.off"),
            text.as_bytes(),
            &ImportOptions::default(),
        )
    }

    #[test]
    fn reads_counts_vertices_and_faces_by_line() {
        let text = "OFF\n# a tetrahedron\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 0.1\n3 0 2 1\n3 0 1 3\n3 0 3 2 255 0 0\n3 1 2 3\n";
        let parsed = parse(text).unwrap();
        assert_eq!(parsed.positions[3].z, 0.1);
        assert_eq!(parsed.polygons[2].attributes.line, Some(10));
        assert_eq!(parsed.vertex_lines, [4, 5, 6, 7]);
        let e = parse(&text.replace("3 1 2 3", "3 1 2 4")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.off:11: vertex index 4 is out of range: 4 vertices are defined"
        );
        let e = parse(&text.replace("4 4 6", "4 5 6")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.off:11: the file ends after 4 of the 5 faces the counts (line 3) declare"
        );
        let e = parse(&text.replace("0 0 0.1", "0 0 inf")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.off:7: vertex 3 has a non-finite coordinate (0, 0, inf)"
        );
        let e = parse("PLY\n").unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.off:1: expected the keyword `OFF`, found `PLY`"
        );
        let e = parse("OFF 4000000000 1 0\n0 0 0\n").unwrap_err();
        assert!(
            e.to_string()
                .contains("ends after 1 of the 4000000000 vertices"),
            "{e}"
        );
    }
}
