//! Stanford PLY: read in ASCII and in binary of either byte order (faces
//! of any size; properties other than `x y z` and the face's vertex list,
//! and elements other than `vertex` and `face`, are skipped), each face
//! located by its line (ASCII) or its element number and byte offset
//! (binary); written as binary little-endian with `double` coordinates,
//! which keeps every `f64` bit.

use std::path::Path;

use glam::DVec3;
use rayon::prelude::*;

use super::import_error::{ImportError, excerpt};
use super::location::{Location, Sources};
use super::parsed::{ImportOptions, Parsed};
use super::ply_header::{Element, Encoding, Header, Property, Scalar, parse};
use super::text::{as_text, number, reservable};
use crate::mesh::{FaceAttributes, Polygon};

/// What the reader takes from the two elements it knows.
struct Roles {
    /// Index of the `vertex` element, and of its `x`, `y`, `z` properties.
    vertex: usize,
    xyz: [usize; 3],
    /// Index of the `face` element and of its vertex list, if any.
    face: Option<(usize, usize)>,
}

fn roles(path: &Path, header: &Header) -> Result<Roles, ImportError> {
    let find = |name: &str| header.elements.iter().position(|e| e.name == name);
    let vertex = find("vertex").ok_or_else(|| {
        ImportError::malformed(
            path,
            Location::Line(header.lines),
            "the header has no `vertex` element",
        )
    })?;
    let element = &header.elements[vertex];
    let mut xyz = [0; 3];
    for (slot, axis) in xyz.iter_mut().zip(["x", "y", "z"]) {
        *slot = element
            .properties
            .iter()
            .position(|p| matches!(p, Property::Scalar { name, .. } if name == axis))
            .ok_or_else(|| {
                ImportError::malformed(
                    path,
                    Location::Line(element.line),
                    format!("the `vertex` element has no scalar property `{axis}`"),
                )
            })?;
    }
    let face = match find("face") {
        None => None,
        Some(f) => {
            let e = &header.elements[f];
            let list = e
                .properties
                .iter()
                .position(|p| matches!(p, Property::List { name, .. } if name == "vertex_indices" || name == "vertex_index"))
                .ok_or_else(|| {
                    ImportError::malformed(
                        path,
                        Location::Line(e.line),
                        "the `face` element has no list property `vertex_indices`",
                    )
                })?;
            if let Property::List { item, .. } = e.properties[list]
                && !item.is_integer()
            {
                return Err(ImportError::malformed(
                    path,
                    Location::Line(e.line),
                    "the face's vertex indices must be of an integer type",
                ));
            }
            Some((f, list))
        }
    };
    Ok(Roles { vertex, xyz, face })
}

/// Reads a PLY file.
pub(crate) fn read(
    path: &Path,
    bytes: &[u8],
    options: &ImportOptions,
) -> Result<Parsed, ImportError> {
    let header = parse(path, bytes)?;
    let roles = roles(path, &header)?;
    let mut parsed = match header.encoding {
        Encoding::Ascii => read_ascii(path, bytes, &header, &roles, options)?,
        _ => read_binary(path, bytes, &header, &roles, options)?,
    };
    parsed.vertex_numbers = (0..parsed.positions.len()).collect();
    Ok(parsed)
}

/// The checks every face gets: its size, then its indices.
fn face(
    path: &Path,
    at: impl Fn() -> Location,
    indices: &[f64],
    vertices: usize,
) -> Result<(), ImportError> {
    if indices.len() < 3 {
        return Err(ImportError::TooFewCorners {
            path: path.to_path_buf(),
            at: at(),
            count: indices.len(),
        });
    }
    if let Some(&bad) = indices
        .iter()
        .find(|&&i| !(0.0..vertices as f64).contains(&i))
    {
        return Err(ImportError::IndexOutOfRange {
            path: path.to_path_buf(),
            at: at(),
            index: bad as i64,
            available: vertices,
        });
    }
    Ok(())
}

fn too_large(path: &Path, at: Location, count: u64, options: &ImportOptions) -> ImportError {
    ImportError::FaceTooLarge {
        path: path.to_path_buf(),
        at,
        count: count as usize,
        limit: options.max_face_corners,
    }
}

fn non_finite(path: &Path, at: Location, vertex: usize, position: DVec3) -> ImportError {
    ImportError::NonFinite {
        path: path.to_path_buf(),
        at,
        vertex,
        position,
    }
}

/// An ASCII body: one record per non-blank line.
fn read_ascii(
    path: &Path,
    bytes: &[u8],
    header: &Header,
    roles: &Roles,
    options: &ImportOptions,
) -> Result<Parsed, ImportError> {
    let text = as_text(path, &bytes[header.body..], "an ASCII PLY body")
        .map_err(|e| shift_line(e, header.lines))?;
    let mut lines = super::text::numbered_lines(text)
        .map(|(l, t)| (l + header.lines, t))
        .filter(|(_, t)| !t.trim().is_empty());
    let vertex_count = header.elements[roles.vertex].count;
    let mut parsed = Parsed {
        sources: Sources::lines(),
        ..Parsed::default()
    };
    parsed
        .positions
        .reserve(reservable(vertex_count, text.len(), 6));
    let mut values: Vec<f64> = Vec::new();
    for (e, element) in header.elements.iter().enumerate() {
        for k in 0..element.count {
            let Some((line, record)) = lines.next() else {
                return Err(ImportError::malformed(
                    path,
                    Location::Line(header.lines + text.lines().count()),
                    format!(
                        "the file ends after {k} of the {} `{}` records the header declares (line {})",
                        element.count, element.name, element.line
                    ),
                ));
            };
            let mut words = record.split_ascii_whitespace();
            let short = || {
                ImportError::malformed(
                    path,
                    Location::Line(line),
                    format!(
                        "too few values for a `{}` record: `{}`",
                        element.name,
                        excerpt(record.as_bytes())
                    ),
                )
            };
            if e == roles.vertex {
                let mut xyz = [0.0; 3];
                for (p, property) in element.properties.iter().enumerate() {
                    match property {
                        Property::Scalar { .. } => {
                            let word = words.next().ok_or_else(short)?;
                            if let Some(axis) = roles.xyz.iter().position(|&i| i == p) {
                                xyz[axis] = number(path, line, word, "vertex position")?;
                            }
                        }
                        Property::List { .. } => {
                            let n = words.next().ok_or_else(short)?;
                            let n = super::text::count(path, line, n, "a list's length")?;
                            for _ in 0..n {
                                words.next().ok_or_else(short)?;
                            }
                        }
                    }
                }
                let position = DVec3::from_array(xyz);
                if !position.is_finite() {
                    return Err(non_finite(
                        path,
                        Location::Line(line),
                        parsed.positions.len(),
                        position,
                    ));
                }
                parsed.positions.push(position);
                parsed.vertex_lines.push(line);
            } else if roles.face.is_some_and(|(f, _)| f == e) {
                let list = roles.face.map_or(0, |(_, l)| l);
                values.clear();
                for (p, property) in element.properties.iter().enumerate() {
                    match property {
                        Property::Scalar { .. } => {
                            words.next().ok_or_else(short)?;
                        }
                        Property::List { .. } => {
                            let n = words.next().ok_or_else(short)?;
                            let n = super::text::count(path, line, n, "a face's corner count")?;
                            if p == list && n > options.max_face_corners as u64 {
                                return Err(too_large(path, Location::Line(line), n, options));
                            }
                            for _ in 0..n {
                                let word = words.next().ok_or_else(short)?;
                                if p == list {
                                    values.push(number(path, line, word, "vertex index")?);
                                }
                            }
                        }
                    }
                }
                face(
                    path,
                    || Location::Line(line),
                    &values,
                    vertex_count as usize,
                )?;
                parsed.polygons.push(Polygon {
                    vertices: values.iter().map(|&i| i as usize).collect(),
                    attributes: FaceAttributes {
                        source_index: Some(k as usize),
                        line: Some(line),
                        ..FaceAttributes::default()
                    },
                });
            }
        }
    }
    Ok(parsed)
}

/// An error located in the body, moved to the file's line numbers.
fn shift_line(e: ImportError, by: usize) -> ImportError {
    match e {
        ImportError::Malformed {
            path,
            at: Location::Line(l),
            message,
        } => ImportError::Malformed {
            path,
            at: Location::Line(l + by),
            message,
        },
        other => other,
    }
}

/// A binary body: fixed-size records parsed in parallel, records with
/// lists walked one by one, every read bounds-checked.
fn read_binary(
    path: &Path,
    bytes: &[u8],
    header: &Header,
    roles: &Roles,
    options: &ImportOptions,
) -> Result<Parsed, ImportError> {
    let encoding = header.encoding;
    let vertex_count = header.elements[roles.vertex].count;
    let mut at = header.body;
    let mut parsed = Parsed::default();
    for (e, element) in header.elements.iter().enumerate() {
        let min = element.min_record_bytes() as u64;
        let needed = (at as u64).saturating_add(element.count.saturating_mul(min));
        if needed > bytes.len() as u64 {
            return Err(ImportError::Truncated {
                path: path.to_path_buf(),
                at: Location::Line(element.line),
                what: format!(
                    "the header's {} `{}` records (at least {min} bytes each, from byte {at})",
                    element.count, element.name
                ),
                needed,
                size: bytes.len() as u64,
            });
        }
        let fixed = element
            .properties
            .iter()
            .all(|p| matches!(p, Property::Scalar { .. }));
        if e == roles.vertex && fixed {
            parsed.positions = fixed_vertices(element, roles.xyz, &bytes[at..], encoding);
            if let Some(v) = parsed
                .positions
                .par_iter()
                .position_first(|p| !p.is_finite())
            {
                let byte = (at + v * min as usize) as u64;
                let loc = Location::Element {
                    kind: "vertex",
                    index: v,
                    byte,
                };
                return Err(non_finite(path, loc, v, parsed.positions[v]));
            }
            at += element.count as usize * min as usize;
            continue;
        }
        if fixed && roles.face.is_none_or(|(f, _)| f != e) {
            at += element.count as usize * min as usize;
            continue;
        }
        let is_face = roles.face.is_some_and(|(f, _)| f == e);
        let mut offsets = Vec::new();
        let mut values: Vec<f64> = Vec::new();
        let mut xyz = [0.0; 3];
        for k in 0..element.count as usize {
            let record = at as u64;
            let location = || Location::Element {
                kind: if is_face { "face" } else { "element" },
                index: k,
                byte: record,
            };
            let truncated = |needed: usize| ImportError::Truncated {
                path: path.to_path_buf(),
                at: location(),
                what: format!("`{}` record {k}", element.name),
                needed: needed as u64,
                size: bytes.len() as u64,
            };
            values.clear();
            for (p, property) in element.properties.iter().enumerate() {
                match *property {
                    Property::Scalar { ty, .. } => {
                        let end = at + ty.size();
                        let b = bytes.get(at..end).ok_or_else(|| truncated(end))?;
                        if let Some(axis) = roles.xyz.iter().position(|&i| i == p) {
                            xyz[axis] = ty.read(b, encoding);
                        }
                        at = end;
                    }
                    Property::List { count, item, .. } => {
                        let end = at + count.size();
                        let b = bytes.get(at..end).ok_or_else(|| truncated(end))?;
                        let n = count.read(b, encoding);
                        if n < 0.0 {
                            return Err(ImportError::malformed(
                                path,
                                location(),
                                format!("a list of length {n}"),
                            ));
                        }
                        let listed = is_face && roles.face.is_some_and(|(_, l)| l == p);
                        if listed && n > options.max_face_corners as f64 {
                            return Err(too_large(path, location(), n as u64, options));
                        }
                        at = end;
                        let end = (at as u64).saturating_add(n as u64 * item.size() as u64);
                        if end > bytes.len() as u64 {
                            return Err(truncated(end as usize));
                        }
                        let end = end as usize;
                        if listed {
                            values.extend(
                                bytes[at..end]
                                    .chunks_exact(item.size())
                                    .map(|c| item.read(c, encoding)),
                            );
                        }
                        at = end;
                    }
                }
            }
            if e == roles.vertex {
                let position = DVec3::from_array(xyz);
                if !position.is_finite() {
                    return Err(non_finite(path, location(), k, position));
                }
                parsed.positions.push(position);
            } else if is_face {
                face(path, location, &values, vertex_count as usize)?;
                offsets.push(record);
                parsed.polygons.push(Polygon {
                    vertices: values.iter().map(|&i| i as usize).collect(),
                    attributes: FaceAttributes {
                        source_index: Some(k),
                        ..FaceAttributes::default()
                    },
                });
            }
        }
        if is_face {
            parsed.sources.push_offsets(0, "face", offsets);
        }
    }
    Ok(parsed)
}

/// The positions of a vertex element of fixed-size records, in parallel.
fn fixed_vertices(
    element: &Element,
    xyz: [usize; 3],
    body: &[u8],
    encoding: Encoding,
) -> Vec<DVec3> {
    let mut offset = 0;
    let mut fields = [(0, Scalar::F32); 3];
    for (p, property) in element.properties.iter().enumerate() {
        if let Property::Scalar { ty, .. } = *property {
            if let Some(axis) = xyz.iter().position(|&i| i == p) {
                fields[axis] = (offset, ty);
            }
            offset += ty.size();
        }
    }
    let size = offset.max(1);
    let n = element.count as usize;
    body[..n * offset]
        .par_chunks_exact(size)
        .map(|r| {
            let [x, y, z] = fields.map(|(at, ty)| ty.read(&r[at..], encoding));
            DVec3::new(x, y, z)
        })
        .collect()
}

/// The bytes of a binary little-endian PLY of `polygons`, coordinates as
/// `double`.
pub(crate) fn write(positions: &[DVec3], polygons: &[Vec<usize>]) -> Vec<u8> {
    let wide = polygons.iter().any(|p| p.len() > 255);
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment written by wingedge\nelement vertex {}\nproperty double x\nproperty double y\nproperty double z\nelement face {}\nproperty list {} int vertex_indices\nend_header\n",
        positions.len(),
        polygons.len(),
        if wide { "uint" } else { "uchar" }
    )
    .into_bytes();
    out.reserve(positions.len() * 24 + polygons.len() * 16);
    for p in positions {
        for x in p.to_array() {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    for polygon in polygons {
        if wide {
            out.extend_from_slice(&(polygon.len() as u32).to_le_bytes());
        } else {
            out.push(polygon.len() as u8);
        }
        for &v in polygon {
            out.extend_from_slice(&(v as i32).to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(bytes: &[u8]) -> Result<Parsed, ImportError> {
        read(Path::new("t.ply"), bytes, &ImportOptions::default())
    }

    const ASCII: &str = "ply\nformat ascii 1.0\ncomment a unit square pyramid\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 2\nproperty list uchar int vertex_indices\nproperty int flags\nend_header\n0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n0.1 0.5 1 1\n4 0 3 2 1 7\n3 0 1 4 7\n";

    #[test]
    fn ascii_faces_of_any_size_with_extra_properties() {
        let parsed = parse(ASCII.as_bytes()).unwrap();
        assert_eq!(parsed.positions.len(), 5);
        assert_eq!(parsed.positions[4].x, 0.1);
        assert_eq!(&parsed.polygons[0].vertices[..], &[0, 3, 2, 1]);
        assert_eq!(parsed.polygons[1].attributes.line, Some(19));
        assert_eq!(parsed.vertex_lines[0], 13);
        let e = parse(ASCII.replace("3 0 1 4 7", "3 0 1 5 7").as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.ply:19: vertex index 5 is out of range: 5 vertices are defined"
        );
        let e = parse(ASCII.replace("element face 2", "element face 3").as_bytes()).unwrap_err();
        assert!(
            e.to_string()
                .contains("the file ends after 2 of the 3 `face` records"),
            "{e}"
        );
        let e = parse(ASCII.replace("0.1 0.5", "nan 0.5").as_bytes()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "t.ply:17: vertex 4 has a non-finite coordinate (NaN, 0.5, 1)"
        );
    }

    #[test]
    fn binary_round_trip_keeps_f64_and_refuses_lies() {
        let positions = vec![DVec3::new(0.1, 1e-300, -3.0), DVec3::X, DVec3::Y, DVec3::Z];
        let polygons = vec![vec![0, 2, 1], vec![0, 1, 3], vec![0, 3, 2], vec![1, 2, 3]];
        let bytes = write(&positions, &polygons);
        let parsed = parse(&bytes).unwrap();
        assert_eq!(parsed.positions, positions);
        assert_eq!(parsed.polygons.len(), 4);
        let loc = parsed.sources.locate(1, None).unwrap();
        let body = bytes.len() - 4 * 24 - 4 * 13;
        assert_eq!(
            loc,
            Location::Element {
                kind: "face",
                index: 1,
                byte: (body + 96 + 13) as u64
            }
        );
        let lying = String::from_utf8_lossy(&bytes).replacen(
            "element face 4",
            "element face 4000000000",
            1,
        );
        let header_end = lying.find("end_header\n").unwrap() + 11;
        let mut hostile = lying.as_bytes()[..header_end].to_vec();
        hostile.extend_from_slice(&bytes[bytes.len() - 4 * 24 - 4 * 13..]);
        let e = parse(&hostile).unwrap_err();
        assert!(
            e.to_string().starts_with("t.ply:8: the file ends after"),
            "{e}"
        );
        assert!(e.to_string().contains("4000000000 `face` records"), "{e}");
        let truncated = &bytes[..bytes.len() - 5];
        let e = parse(truncated).unwrap_err();
        assert!(e.to_string().starts_with("t.ply: face 3 (byte "), "{e}");
    }
}
