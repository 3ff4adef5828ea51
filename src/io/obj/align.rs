//! Aligning tobj's output with the line pass: positions placed at their
//! original vertex numbers (tobj renumbers them per object and drops the
//! ones no face uses).

use std::path::Path;

use glam::DVec3;

use super::error::ObjError;
use super::scan::Scan;

/// Places the positions tobj read at their original vertex numbers;
/// unreferenced vertices (which tobj drops) are read from their own lines.
pub(super) fn align_positions(
    path: &Path,
    bytes: &[u8],
    scan: &Scan,
    models: &[tobj::Model],
) -> Result<Vec<DVec3>, ObjError> {
    let mismatch = |what: &str| ObjError::Parse {
        path: path.to_path_buf(),
        line: None,
        message: format!("internal: tobj and the line pass disagree ({what})"),
    };
    let vertex_count = scan.vertex_lines.len();
    let mut positions = vec![DVec3::NAN; vertex_count];
    let mut set = vec![false; vertex_count];
    let mut faces = scan.faces.iter();
    let mut local_to_original: Vec<usize> = Vec::new();
    for model in models {
        let mesh = &model.mesh;
        local_to_original.clear();
        local_to_original.resize(mesh.positions.len() / 3, usize::MAX);
        let mut cursor = 0usize;
        let face_count = if mesh.face_arities.is_empty() {
            mesh.indices.len() / 3
        } else {
            mesh.face_arities.len()
        };
        for k in 0..face_count {
            let arity = mesh.face_arities.get(k).map_or(3, |&a| a as usize);
            let record = faces.next().ok_or_else(|| mismatch("face count"))?;
            if record.len != arity {
                return Err(mismatch("face size"));
            }
            let originals = &scan.corners[record.start..record.start + arity];
            let locals = mesh
                .indices
                .get(cursor..cursor + arity)
                .ok_or_else(|| mismatch("index count"))?;
            cursor += arity;
            for (&local, &original) in locals.iter().zip(originals) {
                let local = local as usize;
                let slot = local_to_original
                    .get_mut(local)
                    .ok_or_else(|| mismatch("local index"))?;
                if *slot == usize::MAX {
                    *slot = original;
                    let p = &mesh.positions[3 * local..3 * local + 3];
                    positions[original] = DVec3::new(p[0], p[1], p[2]);
                    set[original] = true;
                } else if *slot != original {
                    return Err(mismatch("vertex identity"));
                }
            }
        }
    }
    if faces.next().is_some() {
        return Err(mismatch("face count"));
    }
    for (i, done) in set.iter().enumerate() {
        if !done {
            positions[i] =
                read_vertex_line(bytes, scan.vertex_offsets[i]).ok_or_else(|| ObjError::Parse {
                    path: path.to_path_buf(),
                    line: Some(scan.vertex_lines[i] as usize),
                    message: "cannot read vertex position".to_string(),
                })?;
        }
        if !positions[i].is_finite() {
            return Err(ObjError::NonFinite {
                path: path.to_path_buf(),
                line: scan.vertex_lines[i] as usize,
                vertex: i + 1,
                position: positions[i],
            });
        }
    }
    Ok(positions)
}

/// The position on a `v` line, as tobj reads it (`x y z [w]`, or
/// `x y z r g b`).
fn read_vertex_line(bytes: &[u8], offset: usize) -> Option<DVec3> {
    let end = bytes[offset..]
        .iter()
        .position(|&b| b == b'\n')
        .map_or(bytes.len(), |i| offset + i);
    let text = std::str::from_utf8(&bytes[offset..end]).ok()?;
    let values: Vec<&str> = text.split_whitespace().skip(1).collect();
    let number = |i: usize| values.get(i).and_then(|v| v.parse::<f64>().ok());
    let p = DVec3::new(number(0)?, number(1)?, number(2)?);
    match values.len() {
        4 => Some(p / number(3)?),
        _ => Some(p),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::io::obj::fixture::{TET, read};

    #[test]
    fn unreferenced_vertices_are_kept() {
        let import = read(&format!("{TET}v 5 5 5 2\n")).unwrap();
        assert_eq!(import.soup.positions.len(), 5);
        assert_eq!(import.soup.positions[4], DVec3::splat(2.5));
        assert_eq!(import.vertex_lines[4], 9);
    }
}
