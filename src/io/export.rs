//! Writing a solid (or, for a mesh that is no solid, its soup) in any
//! format, atomically, saying what the format lost: STL and glTF hold
//! `f32`, so every coordinate that rounding changes is counted in the
//! [`ExportReport`], and a coordinate beyond the range of `f32` is refused.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::DVec3;
use slotmap::SecondaryMap;
use thiserror::Error;

use super::format::Format;
use super::{gltf, off, ply, stl, threemf};
use crate::geom::triangulate::triangulate_3d;
use crate::mesh::{PolygonSoup, Solid, VertexId};

/// What writing a file did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExportReport {
    /// The format written.
    pub format: Format,
    /// Vertices written.
    pub vertices: usize,
    /// Faces written (triangles for the formats that hold only triangles).
    pub faces: usize,
    /// Coordinates written (three per vertex).
    pub coordinates: usize,
    /// Coordinates that rounding to the format's `f32` changed (0 for the
    /// formats that keep `f64`).
    pub rounded: usize,
}

impl ExportReport {
    /// The warning to print when the file does not hold the solid's exact
    /// coordinates, naming `path`.
    #[must_use]
    pub fn warning(&self, path: &Path) -> Option<String> {
        (self.rounded > 0).then(|| {
            format!(
                "{}: {} of {} coordinates changed when rounded to f32 ({} holds 32-bit floats; obj, ply, off and 3mf keep every f64 bit)",
                path.display(),
                self.rounded,
                self.coordinates,
                self.format
            )
        })
    }
}

/// Why a file could not be written.
#[derive(Debug, Error)]
pub enum ExportError {
    /// Creating or writing the file failed (the old file is untouched).
    #[error("{}: cannot write: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// A coordinate beyond what the format's numbers hold.
    #[error(
        "vertex {vertex} has the coordinate {}, beyond the range of f32 that {format} holds",
        crate::geom::Readable(*.value)
    )]
    OutOfRange {
        /// The format.
        format: Format,
        /// The vertex (0-based, in the order written).
        vertex: usize,
        /// The coordinate.
        value: f64,
    },
    /// More elements than the format can count.
    #[error("{count} {what} are more than {format} can hold (at most {limit})")]
    TooLarge {
        /// The format.
        format: Format,
        /// What (`triangles`, `vertices`).
        what: &'static str,
        /// How many.
        count: usize,
        /// The format's limit.
        limit: usize,
    },
}

/// Positions and polygons as they will be written.
struct Tables {
    positions: Vec<DVec3>,
    polygons: Vec<Vec<usize>>,
}

impl Tables {
    /// A solid's vertices in table order and its faces: as polygons (a face
    /// with rings as the triangles of its exact triangulation, as OBJ
    /// output does), or all as triangles.
    fn of_solid(solid: &Solid, triangles: bool) -> Tables {
        let mut index: SecondaryMap<VertexId, usize> =
            SecondaryMap::with_capacity(solid.vertex_count());
        let positions = solid
            .vertices()
            .enumerate()
            .map(|(i, (id, v))| {
                index.insert(id, i);
                v.position
            })
            .collect();
        let mut polygons = Vec::with_capacity(solid.face_count());
        for (id, face) in solid.faces() {
            if face.rings.is_empty() && !triangles {
                polygons.push(solid.face_vertices(id).map(|v| index[v]).collect());
            } else if face.rings.is_empty() && solid.face_vertices(id).nth(3).is_none() {
                polygons.push(solid.face_vertices(id).map(|v| index[v]).collect());
            } else if let Ok(ts) = solid.try_triangulate_face(id) {
                polygons.extend(ts.iter().map(|t| t.iter().map(|&v| index[v]).collect()));
            } else {
                // Loops that bound no valid face: each written on its own,
                // so that reading the file back shows the defect.
                for l in solid.face_loops(id) {
                    let corners: Vec<usize> = solid.loop_vertices(l).map(|v| index[v]).collect();
                    push_polygon(&mut polygons, corners, triangles);
                }
            }
        }
        Tables {
            positions,
            polygons,
        }
    }

    /// A soup's positions and polygons (triangulated when asked: exactly
    /// where the polygon allows, else as a fan).
    fn of_soup(soup: &PolygonSoup, triangles: bool) -> Tables {
        let mut polygons = Vec::with_capacity(soup.polygons.len());
        for p in &soup.polygons {
            let corners: Vec<usize> = p.vertices.to_vec();
            if triangles && corners.len() > 3 {
                let points: Vec<DVec3> = corners.iter().map(|&v| soup.positions[v]).collect();
                if let Ok(ts) = triangulate_3d(&points, &[]) {
                    polygons.extend(ts.iter().map(|t| t.iter().map(|&k| corners[k]).collect()));
                    continue;
                }
            }
            push_polygon(&mut polygons, corners, triangles);
        }
        Tables {
            positions: soup.positions.clone(),
            polygons,
        }
    }

    fn triangles(&self) -> Vec<[usize; 3]> {
        self.polygons
            .iter()
            .filter(|p| p.len() == 3)
            .map(|p| [p[0], p[1], p[2]])
            .collect()
    }
}

/// `corners` as one polygon, or as a fan of triangles.
fn push_polygon(polygons: &mut Vec<Vec<usize>>, corners: Vec<usize>, triangles: bool) {
    if !triangles || corners.len() <= 3 {
        polygons.push(corners);
    } else {
        polygons
            .extend((1..corners.len() - 1).map(|i| vec![corners[0], corners[i], corners[i + 1]]));
    }
}

/// The solid in `format`, as bytes, and what was lost.
///
/// # Errors
///
/// [`ExportError::OutOfRange`] for a coordinate beyond `f32` in STL or
/// glTF, [`ExportError::TooLarge`] beyond a format's counts.
pub fn export_bytes(solid: &Solid, format: Format) -> Result<(Vec<u8>, ExportReport), ExportError> {
    if format == Format::Obj {
        let text = super::to_obj_string(solid);
        let report = ExportReport {
            format,
            vertices: solid.vertex_count(),
            faces: solid.face_count(),
            coordinates: 3 * solid.vertex_count(),
            rounded: 0,
        };
        return Ok((text.into_bytes(), report));
    }
    encode(&Tables::of_solid(solid, format.triangles_only()), format)
}

/// Writes the solid to `path` in `format`, atomically
/// ([`write_atomically`](super::write_atomically)); OBJ exactly as
/// [`write_obj`](super::write_obj) writes it.
///
/// # Errors
///
/// As [`export_bytes`], and [`ExportError::Io`] (the old file is then
/// untouched).
pub fn export(solid: &Solid, path: &Path, format: Format) -> Result<ExportReport, ExportError> {
    let (bytes, report) = export_bytes(solid, format)?;
    write(path, &bytes)?;
    Ok(report)
}

/// Writes a soup (a mesh that need not be a solid) to `path` in `format`,
/// atomically: its polygons as they are (OBJ, PLY, OFF), or as triangles.
///
/// # Errors
///
/// As [`export`].
pub fn export_soup(
    soup: &PolygonSoup,
    path: &Path,
    format: Format,
) -> Result<ExportReport, ExportError> {
    let tables = Tables::of_soup(soup, format.triangles_only());
    let (bytes, report) = if format == Format::Obj {
        let mut text = String::from("# written by wingedge\n");
        for p in &tables.positions {
            let _ = writeln!(text, "v {:?} {:?} {:?}", p.x, p.y, p.z);
        }
        for polygon in &tables.polygons {
            text.push('f');
            for v in polygon {
                let _ = write!(text, " {}", v + 1);
            }
            text.push('\n');
        }
        let report = ExportReport {
            format,
            vertices: tables.positions.len(),
            faces: tables.polygons.len(),
            coordinates: 3 * tables.positions.len(),
            rounded: 0,
        };
        (text.into_bytes(), report)
    } else {
        encode(&tables, format)?
    };
    write(path, &bytes)?;
    Ok(report)
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    super::write_atomically(path, |w| std::io::Write::write_all(w, bytes)).map_err(|source| {
        ExportError::Io {
            path: path.to_path_buf(),
            source,
        }
    })
}

/// The bytes of `tables` in `format` (not OBJ).
fn encode(tables: &Tables, format: Format) -> Result<(Vec<u8>, ExportReport), ExportError> {
    let mut report = ExportReport {
        format,
        vertices: tables.positions.len(),
        faces: tables.polygons.len(),
        coordinates: 3 * tables.positions.len(),
        rounded: 0,
    };
    let too_large = |what, count, limit| ExportError::TooLarge {
        format,
        what,
        count,
        limit,
    };
    if tables.positions.len() > i32::MAX as usize {
        return Err(too_large(
            "vertices",
            tables.positions.len(),
            i32::MAX as usize,
        ));
    }
    let bytes = match format {
        Format::Obj => unreachable!("OBJ is written by the OBJ writer"),
        Format::Ply => ply::write(&tables.positions, &tables.polygons),
        Format::Off => off::write(&tables.positions, &tables.polygons),
        Format::ThreeMf => {
            threemf::write(&tables.positions, &tables.triangles()).map_err(|source| {
                ExportError::Io {
                    path: PathBuf::from("(3mf archive)"),
                    source,
                }
            })?
        }
        Format::Stl | Format::Gltf | Format::Glb => {
            let mut rounded = 0;
            let mut narrow = Vec::with_capacity(tables.positions.len());
            for (vertex, p) in tables.positions.iter().enumerate() {
                let mut q = [0f32; 3];
                for (slot, value) in q.iter_mut().zip(p.to_array()) {
                    *slot = value as f32;
                    if !slot.is_finite() {
                        return Err(ExportError::OutOfRange {
                            format,
                            vertex,
                            value,
                        });
                    }
                    rounded += usize::from(f64::from(*slot) != value);
                }
                narrow.push(q);
            }
            report.rounded = rounded;
            let triangles = tables.triangles();
            if triangles.len() > u32::MAX as usize / 3 {
                return Err(too_large(
                    "triangles",
                    triangles.len(),
                    u32::MAX as usize / 3,
                ));
            }
            match format {
                Format::Stl => {
                    let wide: Vec<DVec3> = narrow
                        .iter()
                        .map(|q| DVec3::from_array(q.map(f64::from)))
                        .collect();
                    stl::write(&wide, &triangles)
                }
                Format::Gltf => gltf::write_gltf(&narrow, &triangles),
                _ => gltf::write_glb(&narrow, &triangles),
            }
        }
    };
    Ok((bytes, report))
}
