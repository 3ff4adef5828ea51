//! An affine transform of a primitive.

use std::sync::Arc;

use glam::{DAffine3, DMat3, DVec3};
use thiserror::Error;

use super::tessellate::{DEFAULT_TOLERANCE, mapped};
use super::{
    CellRelation, Containment, Crossing, CrossingPlane, LocalPlane, Polyhedron, Primitive, Stats,
    SurfaceId,
};
use crate::geom::{Aabb, Ray, Readable};
use crate::query::TileError;

/// Why a transform could not be applied.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TransformError {
    /// The linear part has determinant zero (for example a zero scale):
    /// the image of a solid would have no volume.
    #[error("transform is singular (determinant {}) or not finite", Readable(*.determinant))]
    Singular {
        /// The determinant of the linear part.
        determinant: f64,
    },
    /// A polyhedral child moved into the world is no valid closed solid
    /// once its vertices are rounded (a map that squeezes it below `f64`'s
    /// resolution, such as a unit cube moved by 1e17, whose corners all
    /// round to one point): the validator's verdict on the moved solid.
    #[error(
        "the {kind} moved by the transform does not survive rounding its vertices to f64: {reason}"
    )]
    Moved {
        /// The kind of the child.
        kind: &'static str,
        /// What went wrong.
        reason: String,
    },
    /// A curved child whose image is flat along an axis once rounded: the
    /// world coordinates cannot tell its sides apart (a unit sphere moved
    /// by 1e17, where neighbouring `f64` are 16 apart).
    #[error(
        "the {kind} moved by the transform collapses below f64's resolution: its image spans [{}, {}] along {}",
        Readable(*.low),
        Readable(*.high),
        ["x", "y", "z"][*.axis]
    )]
    Collapsed {
        /// The kind of the child.
        kind: &'static str,
        /// The axis along which the image is flat (0, 1, 2 for x, y, z).
        axis: usize,
        /// The image's rounded lowest coordinate along that axis.
        low: f64,
        /// The image's rounded highest coordinate along that axis.
        high: f64,
    },
}

/// A primitive moved by an affine map (translation, rotation, scale, or any
/// invertible linear part).
///
/// A polyhedral child (a box, a polyhedron: [`Primitive::is_polyhedral`])
/// is moved into the world once: its vertices are mapped and rounded to
/// `f64`, and the moved polyhedron answers every question in world
/// coordinates, exactly, like any mesh leaf. It is the same polyhedron
/// boundary evaluation makes of the leaf ([`Primitive::tessellate`]), so
/// ray casting and boundary evaluation see one solid, and its crossings are
/// compared exactly with other flat leaves' (a face it shares with another
/// mesh is crossed once). The price is a copy of the child and its query
/// structure per transformed instance.
///
/// A curved child (sphere, cylinder) is answered in its own frame: rays are
/// mapped into it by the inverse map; an affine map keeps the ray
/// parameter, so the child's `t` values are the answer unchanged. Normals
/// map by the inverse transpose. That mapping is rounded: exactness claims
/// of the child hold in its own frame, not for the mapped input (a
/// translation by a power of two is the notable exact case).
#[derive(Clone, Debug)]
pub struct Transformed {
    child: Arc<dyn Primitive>,
    to_world: DAffine3,
    to_local: DAffine3,
    normal_matrix: DMat3,
    bounds: Aabb,
    /// The polyhedral child moved into the world (vertices rounded once);
    /// `None` for curved children.
    world: Option<Polyhedron>,
}

/// Relative rounding allowance for transformed bounding boxes: each mapped
/// corner coordinate is a sum of three products plus a translation, with a
/// relative error below `4 ε` of the sum of magnitudes; `8 ε` is used so that
/// culling never drops a crossing because of rounding.
const BOUNDS_ROUNDING: f64 = 8.0 * f64::EPSILON;

impl Transformed {
    /// `child` moved by `to_world` (child frame → world frame).
    ///
    /// A leaf must survive its transform, the one rule every query and
    /// command sees (the scene is refused at load, by name): a polyhedral
    /// child's rounded image must pass the validator (the proof boundary
    /// evaluation gives its results), and a curved child's rounded image
    /// must not be flat along any axis.
    ///
    /// # Errors
    ///
    /// [`TransformError::Singular`] when the map is not invertible or not
    /// finite; [`TransformError::Moved`] when a polyhedral child's rounded
    /// image is no valid closed solid; [`TransformError::Collapsed`] when a
    /// curved child's rounded image is flat.
    pub fn try_new(
        child: Arc<dyn Primitive>,
        to_world: DAffine3,
    ) -> Result<Transformed, TransformError> {
        let determinant = to_world.matrix3.determinant();
        if determinant == 0.0 || !determinant.is_finite() || !to_world.translation.is_finite() {
            return Err(TransformError::Singular { determinant });
        }
        let to_local = to_world.inverse();
        let normal_matrix = to_local.matrix3.transpose();
        let world = if child.is_polyhedral() {
            Some(moved_polyhedron(child.as_ref(), to_world)?)
        } else {
            check_not_flat(child.kind(), &to_world, child.bounds())?;
            None
        };
        let bounds = world.as_ref().map_or_else(
            || transform_bounds(&to_world, child.bounds()),
            Primitive::bounds,
        );
        Ok(Transformed {
            child,
            to_world,
            to_local,
            normal_matrix,
            bounds,
            world,
        })
    }

    /// The map from the child's frame to the world.
    #[must_use]
    pub fn to_world(&self) -> DAffine3 {
        self.to_world
    }
}

/// The polyhedral `child` with its vertices moved by `to_world` and
/// rounded: the polyhedron boundary evaluation makes of the moved leaf.
fn moved_polyhedron(
    child: &dyn Primitive,
    to_world: DAffine3,
) -> Result<Polyhedron, TransformError> {
    let kind = child.kind();
    let failed = |reason: String| TransformError::Moved { kind, reason };
    // A polyhedral child's tessellation is itself, whatever the tolerance
    // and clip.
    let local = child
        .tessellate(DEFAULT_TOLERANCE, &Aabb::EMPTY)
        .map_err(|e| failed(e.to_string()))?;
    let exact = maps_exactly(&local, &to_world);
    let solid = mapped(local, to_world).map_err(|e| failed(e.to_string()))?;
    // The validator on the exact triangulation of the moved faces: a map
    // that collapses corners onto each other, folds a face or makes faces
    // meet is refused here rather than answered wrongly (a collapsed cube
    // classified its centre outside, with volume 0). The exact image of a
    // valid solid (no coordinate rounded: a translation by integers, a
    // scale by a power of two) is valid, and needs no proof.
    if !exact {
        crate::boolean::prove(&solid).map_err(|e| failed(e.to_string()))?;
    }
    Polyhedron::try_new(solid).map_err(|e| failed(e.to_string()))
}

/// Whether `map` sends every vertex of `solid` to its exact image in
/// `f64`: a linear part without off-diagonal terms, and every product and
/// sum `m x + t` exact (its rounding error, found by an exact
/// multiply-add and a two-sum, zero).
fn maps_exactly(solid: &crate::mesh::Solid, map: &DAffine3) -> bool {
    let m = map.matrix3;
    let diagonal = DVec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z);
    let off_diagonal = [
        m.x_axis.y, m.x_axis.z, m.y_axis.x, m.y_axis.z, m.z_axis.x, m.z_axis.y,
    ];
    if off_diagonal.iter().any(|&v| v != 0.0) {
        return false;
    }
    solid.vertices().all(|(_, vertex)| {
        (0..3).all(|k| {
            let (a, x, t) = (diagonal[k], vertex.position[k], map.translation[k]);
            let product = a * x;
            let sum = product + t;
            // Two-sum (Knuth): the exact error of the rounded sum.
            let back = sum - product;
            let error = (product - (sum - back)) + (t - back);
            a.mul_add(x, -product) == 0.0 && error == 0.0 && sum.is_finite()
        })
    })
}

/// Refuses a curved child whose local box `local`, mapped by `to_world`
/// and rounded (no padding), is flat along an axis.
fn check_not_flat(
    kind: &'static str,
    to_world: &DAffine3,
    local: Aabb,
) -> Result<(), TransformError> {
    if local.is_empty() {
        return Ok(());
    }
    let rows = to_world.matrix3.transpose();
    for axis in 0..3 {
        let row = rows.col(axis);
        let (mut low, mut high) = (0.0, 0.0);
        for k in 0..3 {
            let (a, b) = (row[k] * local.min[k], row[k] * local.max[k]);
            // 0 · ∞ of an unbounded child along an axis the map drops.
            if row[k] != 0.0 {
                low += a.min(b);
                high += a.max(b);
            }
        }
        let (low, high) = (
            to_world.translation[axis] + low,
            to_world.translation[axis] + high,
        );
        if low.is_finite() && high.is_finite() && low >= high {
            return Err(TransformError::Collapsed {
                kind,
                axis,
                low,
                high,
            });
        }
    }
    Ok(())
}

/// The world box of a local box under `m`, padded for rounding; infinite
/// wherever an infinite local extent can reach.
pub(crate) fn transform_bounds(m: &DAffine3, local: Aabb) -> Aabb {
    if local.is_empty() {
        return Aabb::EMPTY;
    }
    let mut out = Aabb::EMPTY;
    let rows = m.matrix3.transpose();
    for axis in 0..3 {
        let row = rows.col(axis);
        let (mut lo, mut hi, mut magnitude) = (m.translation[axis], m.translation[axis], 0.0);
        for k in 0..3 {
            let coefficient = row[k];
            if coefficient == 0.0 {
                continue;
            }
            let (a, b) = (coefficient * local.min[k], coefficient * local.max[k]);
            lo += a.min(b);
            hi += a.max(b);
            magnitude += a.abs().max(b.abs());
        }
        let pad = BOUNDS_ROUNDING * (magnitude + m.translation[axis].abs());
        out.min[axis] = lo - pad;
        out.max[axis] = hi + pad;
    }
    out
}

impl Primitive for Transformed {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, stats: &mut Stats) -> bool {
        if let Some(world) = &self.world {
            return world.intersect_ray(ray, crossings, stats);
        }
        let local = Ray::new(
            self.to_local.transform_point3(ray.origin),
            self.to_local.transform_vector3(ray.direction),
        );
        self.child.intersect_ray(&local, crossings, stats)
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        if let Some(world) = &self.world {
            return world.classify_point(p);
        }
        self.child.classify_point(self.to_local.transform_point3(p))
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        if let Some(world) = &self.world {
            return world.boundary_normal(p);
        }
        self.child
            .boundary_normal(self.to_local.transform_point3(p))
            .map(|n| self.normal_matrix * n)
    }

    fn crossing_plane(&self, surface: SurfaceId) -> Option<CrossingPlane> {
        self.world.as_ref()?.crossing_plane(surface)
    }

    fn planes_through(&self, p: DVec3, planes: &mut Vec<LocalPlane>) -> bool {
        self.world
            .as_ref()
            .is_some_and(|world| world.planes_through(p, planes))
    }

    fn inside_along(&self, p: DVec3, d: DVec3) -> Option<bool> {
        self.world.as_ref()?.inside_along(p, d)
    }

    fn normal(&self, p: DVec3, surface: SurfaceId) -> DVec3 {
        if let Some(world) = &self.world {
            return world.normal(p, surface);
        }
        self.normal_matrix
            * self
                .child
                .normal(self.to_local.transform_point3(p), surface)
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// A polyhedral child's answer is exact (the moved polyhedron's); a
    /// curved child's is its answer for the box holding the cell's image in
    /// the child's frame (padded for rounding): certain answers stay
    /// certain, and `Meets` may be conservative unless the map keeps axes.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        if let Some(world) = &self.world {
            return world.cell_relation(cell);
        }
        self.child
            .cell_relation(&transform_bounds(&self.to_local, *cell))
    }

    fn prepare_cells(&self) -> Result<(), TileError> {
        match &self.world {
            Some(world) => world.prepare_cells(),
            None => self.child.prepare_cells(),
        }
    }

    fn exact_volume(&self) -> Option<f64> {
        if let Some(world) = &self.world {
            return world.exact_volume();
        }
        Some(self.child.exact_volume()? * self.to_world.matrix3.determinant().abs())
    }

    fn kind(&self) -> &'static str {
        self.child.kind()
    }

    fn is_polyhedral(&self) -> bool {
        self.world.is_some()
    }

    fn tessellate(
        &self,
        tolerance: f64,
        clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        if let Some(world) = &self.world {
            return Ok(world.solid().clone());
        }
        // The clip box is in world coordinates; the child's is its image
        // under the inverse map (the box of the mapped corners).
        let local = Aabb::from_points((0..8).map(|i| {
            let pick = |bit: usize, a: f64, b: f64| if i & bit == 0 { a } else { b };
            self.to_local.transform_point3(glam::DVec3::new(
                pick(1, clip.min.x, clip.max.x),
                pick(2, clip.min.y, clip.max.y),
                pick(4, clip.min.z, clip.max.z),
            ))
        }));
        let child = self.child.tessellate(tolerance, &local)?;
        mapped(child, self.to_world)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csg::{AxisBox, Sphere};

    #[test]
    fn a_scaled_and_moved_sphere_keeps_ray_parameters() {
        let s: Arc<dyn Primitive> = Arc::new(Sphere::try_new(DVec3::ZERO, 1.0).unwrap());
        let m = DAffine3::from_scale_rotation_translation(
            DVec3::new(2., 1., 1.),
            glam::DQuat::IDENTITY,
            DVec3::new(10., 0., 0.),
        );
        let t = Transformed::try_new(s, m).unwrap();
        let mut out = Vec::new();
        let ray = Ray::new(DVec3::new(0., 0., 0.), DVec3::X);
        assert!(!t.intersect_ray(&ray, &mut out, &mut Stats::default()));
        let ts: Vec<f64> = out.iter().map(|c| c.t).collect();
        assert_eq!(ts, [8.0, 12.0]);
        assert_eq!(
            t.classify_point(DVec3::new(11.5, 0., 0.)),
            Containment::Inside
        );
        let n = t.normal(DVec3::new(12., 0., 0.), 0);
        assert!(n.x > 0.0 && n.y == 0.0);
        assert!((t.exact_volume().unwrap() - 8.0 / 3.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!(t.bounds().contains(DVec3::new(12., 1., 1.)));
    }

    /// A curved child moved so far that its rounded image is flat is
    /// refused by name; a small one near the origin is not.
    #[test]
    fn a_curved_child_that_collapses_is_refused() {
        let s: Arc<dyn Primitive> = Arc::new(Sphere::try_new(DVec3::ZERO, 1.0).unwrap());
        let far = DAffine3::from_translation(DVec3::new(0.0, 1e17, 0.0));
        let e = Transformed::try_new(s.clone(), far).unwrap_err();
        assert_eq!(
            e,
            TransformError::Collapsed {
                kind: "sphere",
                axis: 1,
                low: 1e17,
                high: 1e17
            }
        );
        assert!(
            e.to_string().contains("collapses below f64's resolution"),
            "{e}"
        );
        assert!(e.to_string().contains("along y"), "{e}");
        let tiny = DAffine3::from_scale(DVec3::splat(1e-100));
        assert!(Transformed::try_new(s, tiny).is_ok());
    }

    #[test]
    fn rotated_box_bounds_and_singular_maps() {
        let b: Arc<dyn Primitive> = Arc::new(AxisBox::try_new(DVec3::ZERO, DVec3::ONE).unwrap());
        let r = DAffine3::from_rotation_z(std::f64::consts::FRAC_PI_4);
        let t = Transformed::try_new(b.clone(), r).unwrap();
        let bounds = t.bounds();
        assert!((bounds.max.y - 2f64.sqrt()).abs() < 1e-12);
        assert!((bounds.min.x + 0.5f64.sqrt()).abs() < 1e-12);
        assert!(Transformed::try_new(b, DAffine3::from_scale(DVec3::new(1., 0., 1.))).is_err());
    }

    #[test]
    fn a_moved_mesh_is_exact_in_the_world_or_refused() {
        let cube = crate::mesh::builders::cuboid(DVec3::ZERO, DVec3::splat(2.0)).unwrap();
        let mesh: Arc<dyn Primitive> = Arc::new(Polyhedron::try_new(cube).unwrap());
        let turn = DAffine3::from_rotation_translation(
            glam::DQuat::from_rotation_z(0.5),
            DVec3::new(0.25, 0.0, 0.0),
        );
        let moved = Transformed::try_new(mesh.clone(), turn).unwrap();
        assert!(moved.is_polyhedral());
        // Its crossings carry their triangle's plane in world coordinates:
        // the moved corners, rounded once.
        let mut crossings = Vec::new();
        let ray = Ray::new(DVec3::new(0.5, 1.0, -5.0), DVec3::Z);
        assert!(!moved.intersect_ray(&ray, &mut crossings, &mut Stats::default()));
        assert_eq!(crossings.len(), 2);
        let Some(CrossingPlane::Triangle(corners)) = moved.crossing_plane(crossings[0].surface)
        else {
            panic!("a flat crossing")
        };
        assert!(corners.iter().all(|c| c.z == 0.0));
        assert_eq!(
            moved.tessellate(1e-3, &Aabb::EMPTY).unwrap().vertex_count(),
            8
        );
        // A cube moved by 1e17 rounds all its corners to one point (the
        // neighbouring f64 there are 16 apart): refused by name, not a leaf
        // that answers "outside" with volume 0.
        let far = DAffine3::from_translation(DVec3::splat(1e17));
        let e = Transformed::try_new(mesh.clone(), far).unwrap_err();
        assert!(
            matches!(e, TransformError::Moved { kind: "mesh", .. }),
            "{e}"
        );
        assert!(e.to_string().contains("does not survive rounding"), "{e}");
        // By 1e15 (neighbours 0.125 apart) it survives, exactly.
        let near = DAffine3::from_translation(DVec3::splat(1e15));
        let moved = Transformed::try_new(mesh.clone(), near).unwrap();
        assert_eq!(moved.exact_volume(), Some(8.0));
        // A map under which a corner leaves the range of f64 (determinant 1,
        // but x = 2 is sent to 2e308) is refused by name.
        let squeeze = DAffine3::from_scale(DVec3::new(1e308, 1.0, 1e-308));
        assert!(matches!(
            Transformed::try_new(mesh, squeeze),
            Err(TransformError::Moved { kind: "mesh", .. })
        ));
    }
}
