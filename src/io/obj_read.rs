//! Reading Wavefront OBJ into a polygon soup (tobj underneath, polygons kept).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use thiserror::Error;

use crate::mesh::{FaceAttributes, Polygon, PolygonSoup};

/// Why an OBJ file could not be read.
#[derive(Debug, Error)]
pub enum ObjError {
    /// The file could not be opened or read.
    #[error("{}: cannot read: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file is not valid OBJ.
    #[error("{}: {message}", .path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
}

/// Reads every object and group of an OBJ file into one soup, polygons kept
/// as polygons; group names are carried onto the polygons' attributes.
///
/// # Errors
///
/// [`ObjError::Io`] when the file cannot be read, [`ObjError::Parse`] when
/// tobj rejects it.
pub fn read_obj(path: &Path) -> Result<PolygonSoup, ObjError> {
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let file = std::fs::File::open(path).map_err(|source| ObjError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let mut reader = std::io::BufReader::new(file);
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ObjError::Parse {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let mut soup = PolygonSoup::default();
    for model in models {
        let mesh = &model.mesh;
        let base = soup.positions.len();
        soup.positions.extend(
            mesh.positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2])),
        );
        let group: Arc<str> = Arc::from(model.name.as_str());
        let mut start = 0usize;
        let arities: Vec<usize> = if mesh.face_arities.is_empty() {
            vec![3; mesh.indices.len() / 3]
        } else {
            mesh.face_arities.iter().map(|&a| a as usize).collect()
        };
        for arity in arities {
            let vertices = mesh.indices[start..start + arity]
                .iter()
                .map(|&i| base + i as usize)
                .collect();
            start += arity;
            soup.polygons.push(Polygon {
                vertices,
                attributes: FaceAttributes {
                    group: Some(group.clone()),
                    ..FaceAttributes::default()
                },
            });
        }
    }
    Ok(soup)
}
