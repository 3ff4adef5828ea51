//! The leaf interface of a CSG tree: what a primitive tells about a ray and a
//! point.

use std::fmt::Debug;

use glam::DVec3;

use super::{CellRelation, Containment, CrossingPlane, LocalPlane, Stats, TessellateError};
use crate::geom::{Aabb, Ray, Sign};
use crate::query::TileError;

/// Which surface of a primitive a crossing lies on: a face index for a box
/// or a polyhedron, 0 for a sphere, side/base/top for a cylinder. Only
/// [`Primitive::normal`] interprets it.
pub type SurfaceId = u32;

/// One place where a ray crosses a primitive's boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The ray parameter, `t > 0`.
    pub t: f64,
    /// The surface crossed there.
    pub surface: SurfaceId,
}

/// Appends the crossings of a convex solid that the ray's line meets over
/// the parameter interval from `near` to `far` (each with the surface hit
/// there), keeping only `t > 0`, and returns whether the ray's origin is
/// inside (`near ≤ 0 < far`). An interval ending at or behind the origin
/// adds nothing.
pub(crate) fn push_convex_interval(
    crossings: &mut Vec<Crossing>,
    (near, near_surface): (f64, SurfaceId),
    (far, far_surface): (f64, SurfaceId),
) -> bool {
    if far <= 0.0 {
        return false;
    }
    let inside = near <= 0.0;
    if !inside {
        crossings.push(Crossing {
            t: near,
            surface: near_surface,
        });
    }
    crossings.push(Crossing {
        t: far,
        surface: far_surface,
    });
    inside
}

/// A solid that answers rays and points: a leaf of a CSG tree (Roth's
/// primitive solid, one for which a ray–solid intersection algorithm is
/// known; Roth 1982).
///
/// # Contract
///
/// - [`intersect_ray`](Primitive::intersect_ray) returns Roth's `INOUT`
///   — whether the ray's origin is inside — and appends the crossings with
///   `t > 0` in strictly ascending order. "Origin inside" means inside just
///   after the origin along the ray (for an origin in the interior that is
///   the plain answer; for an origin exactly on the boundary it says which
///   way the ray leaves it), so the crossings always alternate starting from
///   that state and a ray never produces a zero-length span.
/// - A ray that lies exactly in a plane of a flat face is decided by the
///   crate-wide symbolic perturbation [`perturbed_side`]: the origin is moved
///   by `ε (1, ε, ε²)`. Every primitive uses the same rule, so two boxes that
///   share a face agree on which of them the grazing ray is in.
/// - [`classify_point`](Primitive::classify_point) is `Inside`, `Outside` or
///   `OnBoundary`; [`boundary_normal`](Primitive::boundary_normal) gives the
///   outward normal at a boundary point on a smooth part of the surface
///   (inside a face, not on an edge or corner), which lets the tree decide
///   points on coincident faces.
/// - [`bounds`](Primitive::bounds) holds the whole solid (infinite for a
///   half-space).
pub trait Primitive: Debug + Send + Sync {
    /// Whether the ray's origin is inside, with the sorted crossings `t > 0`
    /// appended to `crossings`. Ties broken by perturbation are counted in
    /// `stats.tie_breaks`.
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, stats: &mut Stats) -> bool;

    /// Where `p` lies.
    fn classify_point(&self, p: DVec3) -> Containment;

    /// The outward normal at a boundary point `p` when `p` lies on a single
    /// smooth piece of the surface; `None` at edges and corners or when `p`
    /// is not on the boundary. Normals of flat faces are the exact input
    /// normals (so coincident faces compare equal); curved ones are rounded.
    fn boundary_normal(&self, p: DVec3) -> Option<DVec3>;

    /// The plane of the flat piece `surface` of the boundary, in the frame
    /// of the rays this primitive is given, when its crossings are exact
    /// plane crossings: lets a tree compare crossings of different leaves
    /// exactly where their rounded `t` are too close to tell (see
    /// [`CrossingPlane`]). `None` (the default) for curved surfaces and for
    /// primitives that see a rounded image of the ray (a transformed
    /// sphere or cylinder).
    fn crossing_plane(&self, surface: SurfaceId) -> Option<CrossingPlane> {
        let _ = surface;
        None
    }

    /// Appends the planes of the flat pieces of the boundary that pass
    /// through the boundary point `p` (a face: one; an edge: two; a corner:
    /// all of its faces), exactly, and returns `true`; returns `false` when
    /// the primitive cannot list them (the boundary is curved at `p`, or
    /// the primitive does not say: the default). With them, and
    /// [`inside_along`](Primitive::inside_along), a tree decides exactly
    /// the points where surfaces meet at an angle (a corner shared by two
    /// boxes that touch only along a face is outside their intersection);
    /// without them such points are `OnBoundary`.
    fn planes_through(&self, p: DVec3, planes: &mut Vec<LocalPlane>) -> bool {
        let _ = (p, planes);
        false
    }

    /// Whether `p + ε d` is inside for an infinitesimal `ε > 0`, where `p`
    /// is on the boundary and `d` lies in none of the planes of
    /// [`planes_through`](Primitive::planes_through) at `p` (so the answer
    /// is a first-order one). `None` when the primitive cannot tell (the
    /// default).
    fn inside_along(&self, p: DVec3, d: DVec3) -> Option<bool> {
        let _ = (p, d);
        None
    }

    /// The outward normal (not necessarily unit) of `surface` at `p`, for
    /// shading. A rounded construction.
    fn normal(&self, p: DVec3, surface: SurfaceId) -> DVec3;

    /// A box holding the solid.
    fn bounds(&self) -> Aabb;

    /// How the closed box `cell` lies against the solid (see
    /// [`CellRelation`]): `Inside`, `Outside` and `Apart` are certain;
    /// `Meets` is exact for flat primitives and may be conservative for
    /// curved ones.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation;

    /// Builds what [`cell_relation`](Primitive::cell_relation) needs, once
    /// (a polyhedron's exact face tiles). Without it a primitive may answer
    /// `Meets` where it cannot do better.
    ///
    /// # Errors
    ///
    /// [`TileError`] for a face that cannot be tiled.
    fn prepare_cells(&self) -> Result<(), TileError> {
        Ok(())
    }

    /// The solid's volume when it has a closed form (box, sphere, cylinder,
    /// polyhedron by the divergence theorem); `None` otherwise (half-spaces).
    fn exact_volume(&self) -> Option<f64> {
        None
    }

    /// A short name of the kind of primitive (`box`, `sphere`, …).
    fn kind(&self) -> &'static str;

    /// Whether the solid is exactly the polyhedron
    /// [`tessellate`](Primitive::tessellate) returns, whatever the
    /// tolerance and clip (boxes, polyhedra, and those moved by a
    /// transform). A transform moves such a leaf's vertices into the world
    /// once, so the moved leaf stays exact (see
    /// [`Transformed`](super::Transformed)). `false` (the default) for
    /// curved and unbounded solids.
    fn is_polyhedral(&self) -> bool {
        false
    }

    /// The solid as a polyhedron, for boundary evaluation: exact for boxes
    /// and polyhedra, inscribed within `tolerance` (a fraction of the
    /// radius) for curved solids, clipped to hold `clip` for unbounded ones.
    ///
    /// # Errors
    ///
    /// [`TessellateError::Unsupported`] for kinds without a polyhedral
    /// boundary (the default), and the tessellation's own errors.
    fn tessellate(
        &self,
        tolerance: f64,
        clip: &Aabb,
    ) -> Result<crate::mesh::Solid, TessellateError> {
        let _ = (tolerance, clip);
        Err(TessellateError::Unsupported { kind: self.kind() })
    }
}

/// The side of a flat face's plane a ray lying exactly in that plane is
/// taken to be on: the symbolic perturbation that moves the ray's origin by
/// `ε (1, ε, ε²)` for an infinitesimal `ε > 0` (Simulation of Simplicity).
///
/// The perturbed origin lies on the side of the first non-zero component of
/// the outward `normal`: `Positive` (outside) when that component is
/// positive, `Negative` (inside) otherwise. The rule depends only on the
/// plane's orientation, so coincident faces of touching solids (opposite
/// normals) put the grazing ray in exactly one of them. `Zero` only for a
/// zero normal.
#[must_use]
pub fn perturbed_side(normal: DVec3) -> Sign {
    [normal.x, normal.y, normal.z]
        .into_iter()
        .map(Sign::of)
        .find(|&s| s != Sign::Zero)
        .unwrap_or(Sign::Zero)
}

/// Whether two outward normals point exactly the same way (`Positive`),
/// exactly opposite ways (`Negative`) or neither (`Zero`), decided exactly on
/// the given coordinates.
#[must_use]
pub fn normal_alignment(a: DVec3, b: DVec3) -> Sign {
    use crate::geom::dot_sign;
    if a == DVec3::ZERO || b == DVec3::ZERO {
        return Sign::Zero;
    }
    // a × b = 0 exactly: each component `a_i b_j − a_j b_i` is the exact
    // sign of a two-term dot product.
    let parallel = [(1, 2), (2, 0), (0, 1)].into_iter().all(|(i, j)| {
        dot_sign(DVec3::new(a[i], -a[j], 0.0), DVec3::new(b[j], b[i], 0.0)) == Sign::Zero
    });
    if parallel { dot_sign(a, b) } else { Sign::Zero }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn perturbation_puts_a_grazing_ray_in_one_of_two_touching_solids() {
        // Faces x = 1 of [0,1]³ (normal +x) and of [1,2]×… (normal −x).
        assert_eq!(perturbed_side(DVec3::X), Sign::Positive);
        assert_eq!(perturbed_side(-DVec3::X), Sign::Negative);
        assert_eq!(perturbed_side(DVec3::new(0., -0., 3.)), Sign::Positive);
        assert_eq!(perturbed_side(DVec3::ZERO), Sign::Zero);
    }

    #[test]
    fn alignment_is_exact() {
        assert_eq!(normal_alignment(DVec3::X, DVec3::X * 3.0), Sign::Positive);
        assert_eq!(normal_alignment(DVec3::X, -DVec3::X), Sign::Negative);
        let n = DVec3::new(0.1, 0.2, 0.3);
        assert_eq!(normal_alignment(n, n * 2.0), Sign::Positive);
        assert_eq!(
            normal_alignment(n, DVec3::new(0.1, 0.2, 0.3_f64.next_up())),
            Sign::Zero
        );
    }
}
