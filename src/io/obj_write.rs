//! Writing solids as Wavefront OBJ, polygons kept.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use slotmap::SecondaryMap;

use crate::mesh::{FaceId, Polygon, PolygonSoup, Solid, VertexId};

/// The solid as OBJ text: one `v` line per vertex (shortest decimal that
/// reads back as the same `f64`), then one `f` line per polygon of
/// [`written_soup`], counter-clockwise seen from outside. Faces carrying a
/// group name are preceded by a `g` line when the group changes. The empty
/// solid is a comment saying so, which reads back as the empty solid.
#[must_use]
pub fn to_obj_string(solid: &Solid) -> String {
    let (soup, _) = written_soup(solid);
    let mut out = String::with_capacity(soup.positions.len() * 40 + soup.polygons.len() * 24);
    out.push_str("# written by wingedge\n");
    if soup.polygons.is_empty() && soup.positions.is_empty() {
        out.push_str("# the empty solid: no vertices, no faces\n");
    }
    for p in &soup.positions {
        let _ = writeln!(out, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    let mut group: Option<&str> = None;
    for polygon in &soup.polygons {
        let g = polygon.attributes.group.as_deref();
        if g.is_some() && g != group {
            let _ = writeln!(out, "g {}", g.unwrap_or_default());
            group = g;
        }
        write_polygon(&mut out, polygon.vertices.iter().map(|&v| v + 1));
    }
    out
}

/// Exactly what [`to_obj_string`] writes, as a soup: every vertex of the
/// solid in its order, and the faces as polygons, each with the face it
/// comes from. This is what a proof of a written solid validates.
///
/// OBJ has no faces with holes: a face with rings is written as the
/// triangles of its exact constrained triangulation
/// ([`Solid::try_triangulate_face`]: no sliver of zero area, no flipped
/// triangle), wound like the face. A face whose loops do not bound a valid
/// face (a ring outside or crossing, which validation reports) cannot be
/// triangulated; its loops are then written as polygons of their own, so
/// that reading the file back shows the defect.
#[must_use]
pub fn written_soup(solid: &Solid) -> (PolygonSoup, Vec<FaceId>) {
    let mut index: SecondaryMap<VertexId, usize> =
        SecondaryMap::with_capacity(solid.vertex_count());
    let mut positions = Vec::with_capacity(solid.vertex_count());
    for (i, (id, v)) in solid.vertices().enumerate() {
        index.insert(id, i);
        positions.push(v.position);
    }
    let mut polygons = Vec::with_capacity(solid.face_count());
    let mut faces = Vec::with_capacity(solid.face_count());
    let mut push = |face: FaceId, vertices: &mut dyn Iterator<Item = VertexId>| {
        let mut polygon = Polygon::new(vertices.map(|v| index[v]));
        polygon.attributes = solid.face(face).attributes.clone();
        polygons.push(polygon);
        faces.push(face);
    };
    for (id, face) in solid.faces() {
        if face.rings.is_empty() {
            push(id, &mut solid.face_vertices(id));
        } else if let Ok(triangles) = solid.try_triangulate_face(id) {
            for t in triangles {
                push(id, &mut t.into_iter());
            }
        } else {
            for l in solid.face_loops(id) {
                push(id, &mut solid.loop_vertices(l));
            }
        }
    }
    (
        PolygonSoup {
            positions,
            polygons,
        },
        faces,
    )
}

/// One `f` line with the given 1-based vertex numbers.
fn write_polygon(out: &mut String, vertices: impl Iterator<Item = usize>) {
    out.push('f');
    for v in vertices {
        let _ = write!(out, " {v}");
    }
    out.push('\n');
}

/// Writes the solid to `path` as OBJ, atomically
/// ([`write_atomically`](super::write_atomically)); see [`to_obj_string`].
///
/// # Errors
///
/// Any error from creating or writing the file; `path` is then untouched.
pub fn write_obj(solid: &Solid, path: &Path) -> io::Result<()> {
    let text = to_obj_string(solid);
    super::write_atomically(path, |w| io::Write::write_all(w, text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::to_obj_string;
    use crate::geom::{Sign, orient3d};
    use crate::mesh::builders;

    /// The frame's top and bottom (8 vertices, one ring each) are written as
    /// n + 2h − 2 = 8 triangles each, every one wound like its face (the
    /// outward normal `±z`, decided exactly); the 8 sides stay quads.
    #[test]
    fn faces_with_rings_are_written_as_triangles_wound_like_the_face() {
        let text = to_obj_string(&builders::frame());
        let positions: Vec<DVec3> = text
            .lines()
            .filter_map(|l| l.strip_prefix("v "))
            .map(|l| {
                let c: Vec<f64> = l.split(' ').map(|x| x.parse().unwrap()).collect();
                DVec3::new(c[0], c[1], c[2])
            })
            .collect();
        let faces: Vec<Vec<DVec3>> = text
            .lines()
            .filter_map(|l| l.strip_prefix("f "))
            .map(|l| {
                l.split(' ')
                    .map(|i| positions[i.parse::<usize>().unwrap() - 1])
                    .collect()
            })
            .collect();
        let triangles: Vec<&Vec<DVec3>> = faces.iter().filter(|f| f.len() == 3).collect();
        assert_eq!(triangles.len(), 16);
        assert_eq!(faces.iter().filter(|f| f.len() == 4).count(), 8);
        for t in triangles {
            let z = t[0].z;
            assert!(
                t.iter().all(|p| p.z == z),
                "a triangle of the top or bottom"
            );
            // Seen from outside (above the top, below the bottom) the
            // triangle runs counter-clockwise: a point outside is on its
            // positive side.
            let outside = DVec3::new(0.0, 0.0, if z > 0.5 { 2.0 } else { -1.0 });
            assert_eq!(orient3d(t[0], t[1], t[2], outside), Sign::Positive);
        }
    }
}
