//! A solid moved by an orientation-keeping affine map: the same topology,
//! every vertex mapped and rounded once, every face's plane fitted again.

use glam::DAffine3;

use super::Solid;

impl Solid {
    /// The solid with every vertex moved by `map` (rounded to `f64`), its
    /// topology and attributes as they are and each face's plane fitted
    /// again to its moved outer loop. `None` when the map mirrors (the
    /// faces would face inward: build the moved solid from its soup with
    /// the polygons turned instead) or a moved position is not finite.
    #[must_use]
    pub fn moved(&self, map: DAffine3) -> Option<Solid> {
        let determinant = map.matrix3.determinant();
        if determinant.is_nan() || determinant <= 0.0 {
            return None;
        }
        let mut moved = self.clone();
        for vertex in moved.vertices.values_mut() {
            vertex.position = map.transform_point3(vertex.position);
            if !vertex.position.is_finite() {
                return None;
            }
        }
        let faces: Vec<_> = moved.faces.keys().collect();
        for face in faces {
            moved.refit_plane(face);
        }
        Some(moved)
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
        let moved = cube.moved(map).unwrap();
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
        // Mirrors and overflowing maps are refused.
        assert!(
            cube.moved(DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)))
                .is_none()
        );
        assert!(
            cube.moved(DAffine3::from_scale(DVec3::splat(1e308)))
                .is_none()
        );
    }
}
