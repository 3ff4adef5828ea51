//! A solid moved by an orientation-keeping affine map: the same topology,
//! every vertex mapped and rounded once, every face's plane fitted again.

use glam::{DAffine3, DVec3};

use super::{Solid, VertexId};

impl Solid {
    /// Moves every vertex by `map` (rounded to `f64`) in place, keeping
    /// the topology and attributes and fitting each face's plane again to
    /// its moved outer loop, and returns `true`. Returns `false` and
    /// changes nothing when the map mirrors (the faces would face inward:
    /// build the moved solid from its soup with the polygons turned
    /// instead) or a moved position would not be finite.
    #[must_use]
    pub fn move_by(&mut self, map: DAffine3) -> bool {
        let determinant = map.matrix3.determinant();
        if determinant.is_nan() || determinant <= 0.0 {
            return false;
        }
        let finite = self
            .vertices
            .values()
            .all(|vertex| map.transform_point3(vertex.position).is_finite());
        if !finite {
            return false;
        }
        for vertex in self.vertices.values_mut() {
            vertex.position = map.transform_point3(vertex.position);
        }
        let faces: Vec<_> = self.faces.keys().collect();
        for face in faces {
            self.refit_plane(face);
        }
        true
    }

    /// Puts each vertex of `moves` at its new position in place, keeping
    /// the topology and attributes, and fits again the plane of every face
    /// around a moved vertex. The caller proves the moved solid valid
    /// (moving a vertex can fold or cross faces). Vertices not in the solid
    /// are skipped.
    pub fn move_vertices(&mut self, moves: &[(VertexId, DVec3)]) {
        let mut faces = Vec::new();
        for &(v, position) in moves {
            let Some(vertex) = self.vertices.get_mut(v) else {
                continue;
            };
            vertex.position = position;
            faces.extend(self.vertex_faces(v));
        }
        let faces: std::collections::HashSet<_> = faces.into_iter().collect();
        for face in faces {
            self.refit_plane(face);
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;
    use crate::mesh::builders;

    #[test]
    fn a_moved_solid_keeps_its_topology_and_measures() {
        let cube = builders::cuboid(DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)).unwrap();
        let map = DAffine3::from_scale_rotation_translation(
            DVec3::splat(2.0),
            DQuat::from_rotation_z(0.3),
            DVec3::new(5.0, -1.0, 0.5),
        );
        let mut moved = cube.clone();
        assert!(moved.move_by(map));
        assert_eq!(
            (moved.vertex_count(), moved.edge_count(), moved.face_count()),
            (cube.vertex_count(), cube.edge_count(), cube.face_count())
        );
        assert!((moved.volume() - 48.0).abs() < 1e-12);
        for (face, f) in moved.faces() {
            let plane = f.plane.expect("a flat face");
            for v in moved.face_vertices(face) {
                assert!(plane.signed_distance(moved.position(v)).abs() < 1e-12);
            }
        }
        // Mirrors and overflowing maps are refused, the solid left as it
        // was.
        let mut kept = cube.clone();
        assert!(!kept.move_by(DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0))));
        assert!(!kept.move_by(DAffine3::from_scale(DVec3::splat(1e308))));
        assert_eq!(kept.volume(), cube.volume());
        assert_eq!(
            kept.position(kept.vertices().next().unwrap().0),
            cube.position(cube.vertices().next().unwrap().0)
        );
    }
}
