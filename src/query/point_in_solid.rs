//! Point-in-polyhedron by parity of a `+x` ray, exact, with the three
//! methods behind one entry point.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Sign, UNDERFLOW, orient2d, orient3d};

use crate::spatial::rounding::{f32_down, f32_up, f64_below};

use super::triangle_records::YzTri;
use super::{Accel, Containment, QueryError};

/// Batches at least this large are classified in grid-cell order.
const SORTED_BATCH: usize = 8192;

/// How to decide inside/outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Method {
    /// Parity of the crossings of a ray along `x` (the seed's method 1),
    /// exact, ties broken by symbolic perturbation: the `+x` ray, or the `−x`
    /// ray when that meets fewer triangles, which has the same parity.
    /// Needs a closed surface.
    #[default]
    Parity,
    /// Inside iff strictly on the inner side of every face (the seed's method
    /// 2). Needs a convex solid; anything else is an error.
    Normals,
    /// The generalized winding number (sum of solid angles over `4π`),
    /// thresholded at ½; defined for open and overlapping input too. On a
    /// closed surface the winding number is the integer signed count of the
    /// `+x` ray's crossings, which is used instead: exact, and right also
    /// within rounding distance of the surface, where the solid-angle sum is
    /// not.
    Winding,
}

/// What the `+x` ray from a point found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum XRay {
    /// The point lies exactly on a triangle.
    OnBoundary,
    /// The signed number of crossings in front of the point: `+1` for each
    /// triangle whose normal has positive `x` (the ray leaves through it),
    /// `−1` for each it enters through. For a closed outward-oriented
    /// surface this is the winding number of the surface around the point.
    Winding(i32),
}

impl Accel {
    /// Classifies `p` by parity of the `+x` ray from it; see
    /// [`Accel::classify_with`].
    ///
    /// # Errors
    ///
    /// As for [`Accel::classify_with`].
    pub fn classify(&self, p: DVec3) -> Result<Containment, QueryError> {
        self.classify_with(p, Method::Parity)
    }

    /// Classifies `p` as inside, outside or on the boundary of the solid.
    ///
    /// **Parity** casts the ray `p + t·(1, 0, 0)`, `t > 0` (or its opposite,
    /// see below). A triangle is
    /// crossed when the projection of `p` onto the `yz` plane is inside the
    /// triangle's projection (three exact `orient2d`) and the triangle is in
    /// front of `p` (one exact `orient3d`). When the projected point lies
    /// exactly on a projected edge or vertex, the tie is broken by Simulation
    /// of Simplicity: `p`'s `(y, z)` is moved symbolically to
    /// `(y + ε, z + ε²)`, so `orient2d(a, b, p) = 0` becomes the sign of
    /// `a.z − b.z`, or of `b.y − a.y` when that is zero. The moved ray passes
    /// through no vertex and along no edge; each crossing is counted exactly
    /// once, a silhouette is crossed 0 or 2 times, and a ray in a face's plane
    /// crosses that face 0 times. If `p` lies on a triangle (exact
    /// `orient3d = 0` and inside the closed triangle) the answer is
    /// [`Containment::OnBoundary`]. The generic case pays only the filtered
    /// predicates; only triangles whose `yz` grid cell holds `p` and whose
    /// `x` extent reaches `p.x` from the ray's side are tested.
    ///
    /// On a closed surface the moved line crosses the triangles an even
    /// number of times in all, so the crossings behind `p` have the parity of
    /// those in front; parity therefore casts `p + t·(−1, 0, 0)` instead
    /// when fewer of the cell's triangles reach `p.x` from `−x`, with the
    /// same perturbation and the same answer, `OnBoundary` included (the
    /// proof is at `XDirection` in the source). The winding method always
    /// counts towards `+x`.
    ///
    /// **Normals** and **Winding** are described at [`Method`],
    /// [`Accel::classify_convex`] and [`Accel::winding_number`].
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate,
    /// [`QueryError::NotClosed`] for parity on an open surface,
    /// [`QueryError::NotConvex`] for normals on a non-convex solid.
    pub fn classify_with(&self, p: DVec3, method: Method) -> Result<Containment, QueryError> {
        if !p.is_finite() {
            return Err(QueryError::NonFinitePoint { index: 0, point: p });
        }
        match method {
            Method::Parity => {
                self.require_closed()?;
                let ray = self.x_ray_towards(p, RayChoice::Fewer);
                Ok(self.containment_from(p, method, ray))
            }
            Method::Normals => self.classify_convex(p),
            Method::Winding => Ok(self.containment_from(p, method, self.x_ray(p))),
        }
    }

    /// What `method` (parity or winding) answers for `p` from the ray cast
    /// from it.
    fn containment_from(&self, p: DVec3, method: Method, ray: XRay) -> Containment {
        let inside = |yes: bool| {
            if yes {
                Containment::Inside
            } else {
                Containment::Outside
            }
        };
        match ray {
            XRay::OnBoundary => Containment::OnBoundary,
            XRay::Winding(w) if method == Method::Parity => inside(w % 2 != 0),
            // Found by the queries fuzz check (fixtures/fuzz/queries/): 2e-69
            // outside a face and 5e-324 above another, the solid-angle sum
            // was near 1. On a closed surface the exact count decides.
            XRay::Winding(w) if self.is_closed() => inside(w > 0),
            XRay::Winding(_) => inside(self.winding_number_unchecked(p) > 0.5),
        }
    }

    /// Classifies every point, in order, on all cores (rayon).
    ///
    /// # Errors
    ///
    /// The first error by index: [`QueryError::NonFinitePoint`] carries the
    /// offending point's index; the method errors as for
    /// [`Accel::classify_with`].
    pub fn classify_batch(
        &self,
        points: &[DVec3],
        method: Method,
    ) -> Result<Vec<Containment>, QueryError> {
        if let Some(index) = points.par_iter().position_first(|p| !p.is_finite()) {
            return Err(QueryError::NonFinitePoint {
                index,
                point: points[index],
            });
        }
        match method {
            Method::Parity => self.require_closed()?,
            Method::Normals => self.convexity().map_err(QueryError::NotConvex)?,
            Method::Winding => {}
        }
        if method == Method::Normals || points.len() < SORTED_BATCH {
            return points
                .par_iter()
                .with_min_len(1024)
                .map(|&p| self.classify_with(p, method))
                .collect();
        }
        // Large batches: grouped by grid cell (see `point_batch`). Parity
        // casts each point's ray whichever way meets fewer triangles (the
        // same answer, see `XDirection`); the winding method needs the `+x`
        // count itself.
        let choice = match method {
            Method::Parity => RayChoice::Fewer,
            _ => RayChoice::Always(XDirection::Plus),
        };
        Ok(self.x_ray_batch(points, choice, |p, ray| {
            self.containment_from(p, method, ray)
        }))
    }

    /// The `+x` ray from `p`: on the boundary, or the signed crossing count.
    pub(super) fn x_ray(&self, p: DVec3) -> XRay {
        self.x_ray_towards(p, RayChoice::Always(XDirection::Plus))
    }

    /// The ray from `p` along the direction `choice` gives: on the boundary,
    /// or the signed number of crossings *in front of* `p` (the `+x`
    /// winding) derived from the crossings that ray meets. Along
    /// [`XDirection::Minus`] that is the negated count of the crossings
    /// behind `p`: equal to the `+x` count on a closed oriented surface, and
    /// of the same parity on every closed one (see [`XDirection`]), so only
    /// parity may use it.
    pub(super) fn x_ray_towards(&self, p: DVec3, choice: RayChoice) -> XRay {
        let Some(p) = self.probe_point(p) else {
            return XRay::Winding(0);
        };
        let g = self.grid();
        let (entries, extent) = g.cell_at(g.cell_index(p.y, p.z));
        // The triangles that can meet the ray. Towards `−x`: those with
        // smallest `x` at most `p.x`, a prefix of the cell's list. Towards
        // `+x`: those with largest `x` at least `p.x`, whose listed `x` is at
        // least `p.x − extent` (see `YzGrid`) and so at least `reach`, a
        // suffix (which may also hold triangles wholly behind `p`; the exact
        // tests reject them); `reach` is the next `f64` below the rounded
        // `p.x − extent`, so not above the exact difference (`−∞` for an
        // infinite extent: every triangle is a candidate). Both are counted
        // rather than searched (no branches), in `f32`: for an `f32` value
        // `v`, `v ≤ p.x` exactly when `v ≤ f32_down(p.x)` (the largest `f32`
        // not above `p.x`), and `v < reach` exactly when `v < f32_up(reach)`.
        let x_down = f32_down(p.x);
        let reach = f32_up(f64_below(p.x - f64::from(extent)));
        let behind = || entries.iter().filter(|e| e.x <= x_down).count();
        let before_ahead = || entries.iter().filter(|e| e.x < reach).count();
        let (direction, candidates) = match choice {
            RayChoice::Always(XDirection::Plus) => (XDirection::Plus, &entries[before_ahead()..]),
            RayChoice::Always(XDirection::Minus) => (XDirection::Minus, &entries[..behind()]),
            RayChoice::Fewer => {
                let (behind, before_ahead) = (behind(), before_ahead());
                if behind < entries.len() - before_ahead {
                    (XDirection::Minus, &entries[..behind])
                } else {
                    (XDirection::Plus, &entries[before_ahead..])
                }
            }
        };
        let q = DVec2::new(p.y, p.z);
        let mut winding = 0i32;
        for e in candidates {
            match triangle_step(&self.tris[e.record as usize], p, q, direction) {
                Step::Miss => {}
                Step::OnBoundary => return XRay::OnBoundary,
                Step::Crossing(w) => winding += w,
            }
        }
        XRay::Winding(winding)
    }

    /// The point a ray from `p` is cast from, or `None` when no ray from `p`
    /// along `±x` meets the solid's boundary in front of `p` (outside the
    /// projected box, or right of the box: winding 0, not on the boundary).
    ///
    /// Left of the box every triangle the line meets is in front of `p`,
    /// wherever `p` is, and `p` is on none: every such point is moved to
    /// one fixed `x` next to the box, so that the exact predicates see
    /// coordinates of the model's magnitude and decide the same (a point at
    /// `x = −1e308` overflows their arithmetic; one at `x = −5e-324` beside
    /// a face at `x = 0` underflows it, and `orient3d` called it on that
    /// face — found by the queries fuzz target once parity could look
    /// along `−x` and see no such face).
    #[inline]
    pub(super) fn probe_point(&self, p: DVec3) -> Option<DVec3> {
        let g = self.grid();
        if !(p.y >= g.y0 && p.y <= g.y1 && p.z >= g.z0 && p.z <= g.z1) || p.x > self.bounds.max.x {
            return None;
        }
        if p.x < self.bounds.min.x {
            let beside = self.bounds.min.x - (1.0 + self.bounds.min.x.abs());
            return Some(DVec3::new(beside, p.y, p.z));
        }
        Some(p)
    }
}

/// Which way along `x` a point's ray is cast.
///
/// Parity may use either way, with the same answer, because of this fact:
/// on a closed surface (every edge shared by two faces) the symbolically
/// moved line `p' + t·(1, 0, 0)`, `t ∈ ℝ` (see [`Accel::classify_with`])
/// crosses the fan triangles an even number of times in all. Proof: the
/// moved point `q' = (y + ε, z + ε²)` lies on no projected edge's line (an
/// edge whose two projected ends differ; such a tie is exactly what the
/// perturbation decides) and on no projected vertex, so the line meets the
/// triangles only in their interiors and crosses each one it meets
/// transversally, once, and a triangle with zero projected area not at all.
/// Summed mod 2, the fan triangles of a face have the face's boundary as
/// their boundary (inner diagonals cancel), so all of them form a 2-cycle
/// mod 2 when every edge has two faces; a 2-cycle in `ℝ³` bounds a finite
/// 3-chain, which the line enters and leaves a total of an even number of
/// times (it starts and ends outside it). With integer coefficients and
/// faces oriented consistently the same argument gives signed crossings
/// summing to 0.
///
/// Let `p` be off the surface. Each crossing of the moved line is strictly
/// in front of `p` or strictly behind it: a crossed triangle's plane is not
/// parallel to `x` (its projection has non-zero area), `p` is not on it
/// (else `p`, projecting into the closed projected triangle and lying in the
/// plane, would be on the triangle), and `ε` is infinitesimal, so the side
/// is the exact `orient3d` of `p` against the plane. Hence
/// `front + behind = total`, even, and the parities of the crossings in
/// front and behind agree (and the signed counts are opposite on an oriented
/// surface). If `p` is on the surface, every triangle holding it has
/// `min x ≤ p.x ≤ max x` and a closed projection holding `(p.y, p.z)`, so
/// either way tests it and answers [`XRay::OnBoundary`]. The perturbation,
/// `q'`, is the same in both directions. So the answer does not depend on
/// the direction, for parity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum XDirection {
    /// Towards `+x`: the triangles in front of `p` count.
    Plus,
    /// Towards `−x`: the triangles behind `p` count (negated).
    Minus,
}

/// Which way each point's ray goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum RayChoice {
    /// Every ray the same way.
    Always(XDirection),
    /// Per point, the way along which fewer of its grid cell's triangles can
    /// be met (ties: `+x`). Only for parity (see [`XDirection`]).
    Fewer,
}

/// What one triangle adds to a point's ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Step {
    /// Nothing: not crossed in the ray's direction, `p` not on it.
    Miss,
    /// The point lies exactly on the triangle.
    OnBoundary,
    /// The ray crosses it: the contribution to the `+x` winding.
    Crossing(i32),
}

/// The triangle `t` against the ray from `p` (with `q = (p.y, p.z)`) along
/// `direction`: exact, as described at [`Accel::classify_with`].
#[inline(always)]
pub(super) fn triangle_step(t: &YzTri, p: DVec3, q: DVec2, direction: XDirection) -> Step {
    match cross_x(t, q) {
        Cross::No => Step::Miss,
        Cross::Degenerate => {
            let [a, b, c] = t.corners();
            if orient3d(a, b, c, p) == Sign::Zero && coplanar_point_in_closed_triangle(a, b, c, p) {
                Step::OnBoundary
            } else {
                Step::Miss
            }
        }
        Cross::Closed(perturbed_inside) => {
            let [a, b, c] = t.corners();
            let side = orient3d(a, b, c, p);
            if side == Sign::Zero {
                return Step::OnBoundary;
            }
            if !perturbed_inside {
                return Step::Miss;
            }
            let sigma = Sign::of(f64::from(t.sigma));
            match direction {
                // In front of `p`: `p` is on the triangle's inner side as
                // seen along `+x`.
                XDirection::Plus if side == -sigma => Step::Crossing(i32::from(t.sigma)),
                // Behind `p`: counted with the opposite sign, so that the sum
                // is the `+x` winding on an oriented closed surface.
                XDirection::Minus if side == sigma => Step::Crossing(-i32::from(t.sigma)),
                _ => Step::Miss,
            }
        }
    }
}

/// How the `+x` line through a point meets a triangle's `yz` projection.
enum Cross {
    /// The projected point is outside the closed projected triangle.
    No,
    /// The projection has zero area: only an on-boundary check applies.
    Degenerate,
    /// The projected point is in the closed projected triangle; the flag says
    /// whether the symbolically moved point is inside.
    Closed(bool),
}

/// Shewchuk's `ccwerrboundA`, `(3 + 16ε)ε` with `ε = 2⁻⁵³`: the relative
/// error bound of the rounded 2-D orientation determinant.
const ORIENT2D_BOUND: f64 = (3.0 + 16.0 * HALF_EPSILON) * HALF_EPSILON;
/// Half a unit in the last place of 1.0.
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;
/// [`ORIENT2D_BOUND`] times 2 with a margin for the rounding of the shared
/// bound's own evaluation (see [`cross_x`]).
const SHARED_ORIENT2D_BOUND: f64 = ORIENT2D_BOUND * 2.0 * (1.0 + 64.0 * f64::EPSILON);

/// How the `x` line through `q = (y, z)` meets the triangle's projection.
///
/// First a floating-point filter for the three `orient2d(corner, next corner,
/// q)` at once, evaluated exactly as [`orient2d`] evaluates each (the
/// differences `corner − q`, then `left − right` with `left = Δy₀·Δz₁`,
/// `right = Δz₀·Δy₁`), but with one error bound shared by all three. Why the
/// bound is valid: [`orient2d`] certifies the sign of its rounded `det` when
/// `|det| > B · P`, `B` = [`ORIENT2D_BOUND`] (Shewchuk's `ccwerrboundA`,
/// which also covers the rounding of the differences) and `P = |left| +
/// |right|` evaluated in floating point. With `m` the largest `|Δ|` of the
/// three rounded differences, each rounded product is at most `m²(1 + ε)`,
/// so `P ≤ 2m²(1 + ε)²` and the rounded `B · P` is at most `2Bm²(1 + ε)³`.
/// The bound used here, `(K · m) · m` with `K = 2B(1 + 64ε)`
/// ([`SHARED_ORIENT2D_BOUND`]), is at least `Km²(1 − ε)²`, which exceeds
/// `2Bm²(1 + ε)³`. So a sign this filter certifies is one [`orient2d`] would
/// certify, the exact sign. Roundings in the subnormal range add at most
/// `2η(1 + ε)` (`η = 2⁻¹⁰⁷⁵`) to each determinant's error, covered by
/// [`UNDERFLOW`]; overflow makes the bound or a determinant infinite or NaN,
/// which certifies nothing. Every case the filter leaves open goes to the
/// exact tests of [`cross_x_exact`].
///
/// Multiplying each determinant by the projection's sign `σ = ±1` is exact,
/// so the filter decides [`Cross::No`] when one of them is certainly `−σ`
/// (as [`cross_x_exact`] does on meeting any such sign) and
/// [`Cross::Closed`]`(true)` when all three are certainly `σ` (no tie).
#[inline(always)]
fn cross_x(t: &YzTri, q: DVec2) -> Cross {
    if t.sigma != 0 {
        let (y0, y1, y2) = (t.y[0] - q.x, t.y[1] - q.x, t.y[2] - q.x);
        let (z0, z1, z2) = (t.z[0] - q.y, t.z[1] - q.y, t.z[2] - q.y);
        let sigma = f64::from(t.sigma);
        let d0 = sigma * (y0 * z1 - z0 * y1);
        let d1 = sigma * (y1 * z2 - z1 * y2);
        let d2 = sigma * (y2 * z0 - z2 * y0);
        let m = y0
            .abs()
            .max(y1.abs())
            .max(y2.abs())
            .max(z0.abs())
            .max(z1.abs())
            .max(z2.abs());
        let bound = SHARED_ORIENT2D_BOUND * m * m + UNDERFLOW;
        if (d0 < -bound) | (d1 < -bound) | (d2 < -bound) {
            return Cross::No;
        }
        if (d0 > bound) & (d1 > bound) & (d2 > bound) {
            return Cross::Closed(true);
        }
    }
    cross_x_exact(t, q)
}

/// [`cross_x`] by three [`orient2d`] and the perturbation of ties.
#[inline(never)]
fn cross_x_exact(t: &YzTri, q: DVec2) -> Cross {
    if t.sigma == 0 {
        let (ymin, ymax) = (
            t.y[0].min(t.y[1]).min(t.y[2]),
            t.y[0].max(t.y[1]).max(t.y[2]),
        );
        let (zmin, zmax) = (
            t.z[0].min(t.z[1]).min(t.z[2]),
            t.z[0].max(t.z[1]).max(t.z[2]),
        );
        return if q.x >= ymin && q.x <= ymax && q.y >= zmin && q.y <= zmax {
            Cross::Degenerate
        } else {
            Cross::No
        };
    }
    let sigma = Sign::of(f64::from(t.sigma));
    let a = DVec2::new(t.y[0], t.z[0]);
    let b = DVec2::new(t.y[1], t.z[1]);
    let c = DVec2::new(t.y[2], t.z[2]);
    let s0 = orient2d(a, b, q);
    if s0 == -sigma {
        return Cross::No;
    }
    let s1 = orient2d(b, c, q);
    if s1 == -sigma {
        return Cross::No;
    }
    let s2 = orient2d(c, a, q);
    if s2 == -sigma {
        return Cross::No;
    }
    if s0 != Sign::Zero && s1 != Sign::Zero && s2 != Sign::Zero {
        return Cross::Closed(true);
    }
    let inside = [(s0, a, b), (s1, b, c), (s2, c, a)]
        .iter()
        .all(|&(s, u, v)| s != Sign::Zero || perturbed_orient(u, v) == sigma);
    Cross::Closed(inside)
}

/// `orient2d(u, v, q')` for `q' = q + (ε, ε²)` when `orient2d(u, v, q) = 0`:
/// the sign of `u.y − v.y`, or of `v.x − u.x` when that is zero (2-D names:
/// `x` is the 3-D `y`, `y` the 3-D `z`).
#[inline]
fn perturbed_orient(u: DVec2, v: DVec2) -> Sign {
    crate::geom::count_tie_break();
    match Sign::of(u.y - v.y) {
        Sign::Zero => Sign::of(v.x - u.x),
        s => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn cube_centre_faces_edges_vertices() {
        let accel = Accel::new(&builders::cube());
        let c = |x, y, z| accel.classify(DVec3::new(x, y, z)).unwrap();
        assert_eq!(c(0.0, 0.0, 0.0), Containment::Inside);
        assert_eq!(c(2.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(-2.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(1.0, 0.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(0.0, 1.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(1.0, 1.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(1.0, 1.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(0.0, 0.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(-0.5, 1.0, -1.0), Containment::OnBoundary);
        // Rays along faces and edges from inside and outside.
        assert_eq!(c(0.0, 1.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(-3.0, 1.0, 1.0), Containment::Outside);
        assert_eq!(c(-3.0, 1.0, 0.0), Containment::Outside);
        assert_eq!(c(-3.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(0.5, 0.0, 0.0), Containment::Inside);
    }

    /// Points that stress both ray directions: random points in and around
    /// the box, points next to both ends of it in `x`, every vertex and edge
    /// midpoint (on the boundary, or on the `x` line through one), the
    /// vertices moved along `x` to both sides (rays through vertices), and
    /// points just inside and outside the box's `x` ends on those lines.
    fn stress_points(solid: &crate::mesh::Solid, seed: u64) -> Vec<DVec3> {
        let accel = Accel::new(solid);
        let (min, max) = (accel.bounds().min, accel.bounds().max);
        let size = max - min;
        let mut u = crate::test_rng::uniform(seed);
        let mut points: Vec<DVec3> = (0..3000)
            .map(|_| min - size * 0.1 + DVec3::new(u(), u(), u()) * size * 1.2)
            .collect();
        for _ in 0..500 {
            let (y, z) = (min.y + u() * size.y, min.z + u() * size.z);
            for x in [min.x, max.x, min.x + 1e-9 * size.x, max.x - 1e-9 * size.x] {
                points.push(DVec3::new(x, y, z));
            }
        }
        let corners: Vec<DVec3> = solid.vertices().map(|(_, v)| v.position).collect();
        for (k, &v) in corners.iter().enumerate() {
            let w = corners[(k * 7 + 3) % corners.len()];
            for p in [v, (v + w) * 0.5] {
                points.push(p);
                for x in [
                    min.x - 1.0,
                    max.x + 1.0,
                    min.x,
                    max.x,
                    (min.x + max.x) * 0.5,
                ] {
                    points.push(DVec3::new(x, p.y, p.z));
                }
            }
        }
        points
    }

    fn closed_solids() -> Vec<crate::mesh::Solid> {
        vec![
            builders::cube(),
            builders::l_prism(),
            builders::icosahedron(),
            builders::dodecahedron(),
            builders::sphere(9),
        ]
    }

    #[test]
    fn minus_x_rays_answer_as_plus_x_rays_on_closed_solids() {
        for (k, solid) in closed_solids().iter().enumerate() {
            let accel = Accel::new(solid);
            for p in stress_points(solid, 11 + k as u64) {
                let plus = accel.x_ray_towards(p, RayChoice::Always(XDirection::Plus));
                let minus = accel.x_ray_towards(p, RayChoice::Always(XDirection::Minus));
                let fewer = accel.x_ray_towards(p, RayChoice::Fewer);
                // Oriented closed solids: even the signed counts agree.
                assert_eq!(plus, minus, "solid {k}, {p}");
                assert_eq!(plus, fewer, "solid {k}, {p}");
            }
        }
    }

    #[test]
    fn boundary_points_are_found_from_either_side() {
        let accel = Accel::new(&builders::cube());
        let mut points = Vec::new();
        for a in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            for b in [-1.0, -0.25, 0.0, 0.75, 1.0] {
                for side in [-1.0, 1.0] {
                    points.push(DVec3::new(side, a, b));
                    points.push(DVec3::new(a, side, b));
                    points.push(DVec3::new(a, b, side));
                }
            }
        }
        for p in points {
            for choice in [
                RayChoice::Always(XDirection::Plus),
                RayChoice::Always(XDirection::Minus),
                RayChoice::Fewer,
            ] {
                assert_eq!(accel.x_ray_towards(p, choice), XRay::OnBoundary, "{p}");
            }
        }
    }

    #[test]
    fn cell_prefix_and_suffix_hold_every_triangle_a_ray_can_meet() {
        let solid = builders::sphere(24);
        let accel = Accel::new(&solid);
        let g = accel.grid();
        let mut u = crate::test_rng::uniform(5);
        for _ in 0..4000 {
            let b = accel.bounds();
            let p = b.min + DVec3::new(u(), u(), u()) * (b.max - b.min);
            let (entries, extent) = g.cell_at(g.cell_index(p.y, p.z));
            let reach = f32_up(f64_below(p.x - f64::from(extent)));
            for (i, e) in entries.iter().enumerate() {
                let t = &accel.tris[e.record as usize];
                assert!(f64::from(e.x) <= t.x[0].min(t.x[1]).min(t.x[2]));
                if i > 0 {
                    assert!(entries[i - 1].x <= e.x);
                }
                // Every triangle reaching `p.x` from `+x` is in the suffix.
                if t.x[0].max(t.x[1]).max(t.x[2]) >= p.x {
                    assert!(e.x >= reach, "{p}");
                }
            }
        }
    }

    #[test]
    fn large_batches_match_single_queries_for_every_method() {
        // Above the grouped-batch threshold, on a closed solid and on an open
        // one (a sphere missing one face), where the winding method must not
        // take a parity shortcut.
        let closed = builders::sphere(24);
        let mut soup = builders::sphere_soup(24);
        soup.polygons.pop();
        let open = crate::mesh::Solid::try_from_soup(&soup).unwrap();
        for (solid, methods) in [
            (&closed, &[Method::Parity, Method::Winding][..]),
            (&open, &[Method::Winding][..]),
        ] {
            let accel = Accel::new(solid);
            let mut points = stress_points(solid, 3);
            while points.len() < SORTED_BATCH + 100 {
                let more = stress_points(solid, points.len() as u64);
                points.extend(more);
            }
            for &method in methods {
                let batch = accel.classify_batch(&points, method).unwrap();
                for (p, got) in points.iter().zip(&batch) {
                    assert_eq!(
                        accel.classify_with(*p, method).unwrap(),
                        *got,
                        "{p} {method:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn far_points_are_outside_by_every_method() {
        // Points far left of the box on lines through the solid: the exact
        // predicates would overflow on their coordinates (the no-panic
        // audit, after the queries fuzz check's far points).
        for solid in [builders::cube(), builders::l_prism()] {
            let accel = Accel::new(&solid);
            for x in [-f64::MAX, -1e300, -1e154, f64::MAX] {
                let p = DVec3::new(x, 0.5, 0.5);
                for method in [Method::Parity, Method::Winding, Method::Normals] {
                    match accel.classify_with(p, method) {
                        Ok(c) => assert_eq!(c, Containment::Outside, "{p} {method:?}"),
                        Err(e) => assert!(matches!(e, QueryError::NotConvex(_)), "{e}"),
                    }
                }
            }
        }
    }
}
