//! Planes `A x + B y + C z + D = 0` with a unit normal `(A, B, C)`.
//!
//! Planes are *constructions*: their coefficients are rounded floating-point
//! numbers and are documented as such. Decisions about which side of a face a
//! point lies on are never taken from these coefficients but from
//! [`orient3d`](super::orient3d) on the face's own vertices.

use glam::{DAffine3, DMat3, DVec3};
use thiserror::Error;

/// Why a plane could not be fitted.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PlaneError {
    /// The three points are collinear or (some of them) coincident, so they
    /// span no plane.
    #[error(
        "points {}, {} and {} are collinear or coincident and span no plane",
        super::ReadableVec(.points[0]),
        super::ReadableVec(.points[1]),
        super::ReadableVec(.points[2])
    )]
    Collinear {
        /// The offending points.
        points: [DVec3; 3],
    },
    /// A polygon's vertices enclose no area (fewer than three distinct
    /// points, or all collinear).
    #[error("polygon of {vertices} vertices has zero area and spans no plane")]
    ZeroArea {
        /// The number of vertices of the polygon.
        vertices: usize,
    },
    /// An input coordinate is NaN or infinite.
    #[error("non-finite coordinate in plane input")]
    NonFinite,
}

/// An oriented plane `A x + B y + C z + D = 0`.
///
/// # Invariants
///
/// `normal = (A, B, C)` has unit length (up to rounding) and all four
/// coefficients are finite. `f(p) = normal · p + d` is positive on the side the
/// normal points to; for a face of a solid that is the outside.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// `(A, B, C)`: the unit normal.
    pub normal: DVec3,
    /// `D`: minus the signed distance of the plane from the origin along the
    /// normal.
    pub d: f64,
}

/// A plane fitted to a polygon by Newell's method, with the fit's quality.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneFit {
    /// The fitted plane. Its normal follows the polygon's winding
    /// (counter-clockwise seen from the side it points to).
    pub plane: Plane,
    /// The largest distance of a polygon vertex from `plane`. Zero (up to
    /// rounding) for a planar polygon; four or more points need not be
    /// coplanar, and this measures by how much they are not.
    pub max_deviation: f64,
    /// The polygon's vector area `½ Σ pᵢ × pᵢ₊₁`; its length is the area of a
    /// planar polygon.
    pub vector_area: DVec3,
}

impl Plane {
    /// The plane through `point` with the given normal, normalised.
    ///
    /// # Errors
    ///
    /// [`PlaneError::ZeroArea`] when `normal` is zero or too small to
    /// normalise, [`PlaneError::NonFinite`] for non-finite input.
    pub fn try_from_point_normal(point: DVec3, normal: DVec3) -> Result<Plane, PlaneError> {
        if !point.is_finite() || !normal.is_finite() {
            return Err(PlaneError::NonFinite);
        }
        let normal = unit_direction(normal).ok_or(PlaneError::ZeroArea { vertices: 0 })?;
        Ok(Plane {
            normal,
            d: -normal.dot(point),
        })
    }

    /// The plane through three points by determinants, done in general: solve `A xᵢ + B yᵢ + C zᵢ + D = 0`
    /// for three points by 3×3 determinants, then scale to a unit normal.
    ///
    /// `A`, `B`, `C` and `D` are the cofactors of the matrix whose rows are
    /// `(xᵢ, yᵢ, zᵢ, 1)`: `A = |y z 1|`, `B = |z x 1|`, `C = |x y 1|`,
    /// `D = -|x y z|`. Unlike the common shortcut (set `D = 1` and solve), this
    /// works for planes through the origin. The points are taken relative to
    /// their centroid first, which leaves `A`, `B`, `C` unchanged and keeps the
    /// determinants accurate far from the origin. The normal points to the side
    /// from which `p1, p2, p3` appear counter-clockwise.
    ///
    /// # Errors
    ///
    /// [`PlaneError::Collinear`] when the points are collinear or coincident
    /// (decided exactly), [`PlaneError::NonFinite`] for non-finite input.
    pub fn try_from_points_determinant(
        p1: DVec3,
        p2: DVec3,
        p3: DVec3,
    ) -> Result<Plane, PlaneError> {
        check_triangle(p1, p2, p3)?;
        let centre = (p1 + p2 + p3) / 3.0;
        let [q1, q2, q3] = [p1 - centre, p2 - centre, p3 - centre];
        let det = |m: DMat3| m.determinant();
        let a = det(DMat3::from_cols_array(&[
            q1.y, q2.y, q3.y, q1.z, q2.z, q3.z, 1.0, 1.0, 1.0,
        ]));
        let b = det(DMat3::from_cols_array(&[
            q1.z, q2.z, q3.z, q1.x, q2.x, q3.x, 1.0, 1.0, 1.0,
        ]));
        let c = det(DMat3::from_cols_array(&[
            q1.x, q2.x, q3.x, q1.y, q2.y, q3.y, 1.0, 1.0, 1.0,
        ]));
        Plane::try_from_point_normal(centre, DVec3::new(a, b, c)).map_err(|_| {
            PlaneError::Collinear {
                points: [p1, p2, p3],
            }
        })
    }

    /// The plane through three points by the cross product: the normal is the cross product of two edge
    /// vectors, `(p1 − p2) × (p2 − p3)`, normalised; `D = −n · p`.
    ///
    /// The normal points to the side from which `p1, p2, p3` appear
    /// counter-clockwise, as for [`Plane::try_from_points_determinant`].
    ///
    /// # Errors
    ///
    /// As for [`Plane::try_from_points_determinant`].
    pub fn try_from_points_cross(p1: DVec3, p2: DVec3, p3: DVec3) -> Result<Plane, PlaneError> {
        check_triangle(p1, p2, p3)?;
        let normal = (p1 - p2).cross(p2 - p3);
        let centre = (p1 + p2 + p3) / 3.0;
        Plane::try_from_point_normal(centre, normal).map_err(|_| PlaneError::Collinear {
            points: [p1, p2, p3],
        })
    }

    /// Newell's method: the best plane through a polygon of any size, with
    /// the largest vertex deviation reported rather than hidden.
    ///
    /// The normal is the polygon's vector area (exact for planar polygons and
    /// a least-squares-like average otherwise); the plane passes through the
    /// vertices' centroid. Coordinates are taken relative to the first vertex
    /// so that a small feature far from the origin keeps its precision.
    ///
    /// # Errors
    ///
    /// [`PlaneError::ZeroArea`] for fewer than three vertices or a polygon with
    /// no area, [`PlaneError::NonFinite`] for non-finite input.
    pub fn try_fit_newell(points: &[DVec3]) -> Result<PlaneFit, PlaneError> {
        if points.iter().any(|p| !p.is_finite()) {
            return Err(PlaneError::NonFinite);
        }
        let zero_area = PlaneError::ZeroArea {
            vertices: points.len(),
        };
        if points.len() < 3 {
            return Err(zero_area);
        }
        let origin = points[0];
        let vector_area = newell_vector_area(points, origin);
        let centroid = points.iter().map(|&p| p - origin).sum::<DVec3>() / points.len() as f64;
        let normal = unit_direction(vector_area).ok_or(zero_area)?;
        let plane = Plane {
            normal,
            d: -normal.dot(centroid + origin),
        };
        let relative = Plane {
            normal,
            d: -normal.dot(centroid),
        };
        let max_deviation = points
            .iter()
            .map(|&p| relative.signed_distance(p - origin).abs())
            .fold(0.0, f64::max);
        Ok(PlaneFit {
            plane,
            max_deviation,
            vector_area,
        })
    }

    /// `A x + B y + C z + D`: the signed distance of `p` from the plane,
    /// positive on the side the normal points to. A rounded construction:
    /// use [`orient3d`](super::orient3d) to decide sides.
    #[must_use]
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        self.normal.dot(p) + self.d
    }

    /// The orthogonal projection of `p` onto the plane.
    #[must_use]
    pub fn project(&self, p: DVec3) -> DVec3 {
        p - self.normal * self.signed_distance(p)
    }

    /// The same plane with the opposite orientation.
    #[must_use]
    pub fn flipped(&self) -> Plane {
        Plane {
            normal: -self.normal,
            d: -self.d,
        }
    }

    /// The image of this plane under the affine map `transform`.
    ///
    /// A point `p` on the plane maps to a point `transform(p)` on the result,
    /// and sides are kept (a point on the positive side maps to the positive
    /// side). Plane coefficients are covariant: they transform by the inverse
    /// transpose of the map, `(A, B, C, D)' = (A, B, C, D) · M⁻¹` in
    /// homogeneous form.
    ///
    /// # Errors
    ///
    /// [`PlaneError::NonFinite`] when `transform` is singular or the result is
    /// not finite.
    pub fn try_transform(&self, transform: &DAffine3) -> Result<Plane, PlaneError> {
        let m = transform.matrix3;
        if m.determinant() == 0.0 || !m.is_finite() || !transform.translation.is_finite() {
            return Err(PlaneError::NonFinite);
        }
        let inverse = m.inverse();
        // Row vector (n, d) times the inverse homogeneous matrix
        // [[M⁻¹, −M⁻¹ t], [0, 1]].
        let normal = inverse.transpose() * self.normal;
        let d = self.d - normal.dot(transform.translation);
        let length = normal.length();
        if length == 0.0 || !length.is_finite() || !d.is_finite() {
            return Err(PlaneError::NonFinite);
        }
        Ok(Plane {
            normal: normal / length,
            d: d / length,
        })
    }
}

/// The vector area `½ Σ (pᵢ − o) × (pᵢ₊₁ − o)` of a closed polygon, computed
/// relative to `origin` (any point; a nearby one keeps precision).
#[must_use]
pub fn newell_vector_area(points: &[DVec3], origin: DVec3) -> DVec3 {
    let n = points.len();
    let mut sum = DVec3::ZERO;
    for i in 0..n {
        let p = points[i] - origin;
        let q = points[(i + 1) % n] - origin;
        sum += p.cross(q);
    }
    sum * 0.5
}

/// `v` scaled to unit length, or `None` when it is zero or not finite. `v`
/// is first scaled exactly by a power of two that brings its largest
/// component near 1, so that the squared length neither underflows
/// (a face of side 1e-90 has a vector area of 1e-180) nor overflows (side
/// 1e100: 1e200): the direction of any non-zero finite vector is found.
#[must_use]
pub fn unit_direction(v: DVec3) -> Option<DVec3> {
    let largest = v.abs().max_element();
    if largest == 0.0 || !largest.is_finite() {
        return None;
    }
    // 2^−e in two exact halves, each a normal power of two.
    let e = largest.log2().floor() as i32;
    let (half, rest) = (-e / 2, -e - (-e / 2));
    (v * 2f64.powi(half) * 2f64.powi(rest)).try_normalize()
}

fn check_triangle(p1: DVec3, p2: DVec3, p3: DVec3) -> Result<(), PlaneError> {
    if !(p1.is_finite() && p2.is_finite() && p3.is_finite()) {
        return Err(PlaneError::NonFinite);
    }
    if super::collinear3d(p1, p2, p3) {
        return Err(PlaneError::Collinear {
            points: [p1, p2, p3],
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    /// The common shortcut for the determinant method: fix `D = 1` and solve the 3×3
    /// system `[p₁; p₂; p₃] (A, B, C)ᵀ = −1` by Cramer's rule. Kept here only
    /// to show why it is not used.
    fn d_equals_one_shortcut(p1: DVec3, p2: DVec3, p3: DVec3) -> Option<Plane> {
        let m = DMat3::from_cols(p1, p2, p3).transpose();
        let det = m.determinant();
        if det == 0.0 {
            return None;
        }
        let abc = m.inverse() * DVec3::splat(-1.0);
        let r = abc.length();
        Some(Plane {
            normal: abc / r,
            d: 1.0 / r,
        })
    }

    #[test]
    fn the_d_equals_one_shortcut_fails_for_planes_through_the_origin() {
        let (p1, p2, p3) = (
            DVec3::new(1., 0., 0.),
            DVec3::new(0., 1., 0.),
            DVec3::new(-1., -1., 0.),
        );
        // z = 0 passes through the origin: with D = 1 the system is singular.
        assert!(d_equals_one_shortcut(p1, p2, p3).is_none());
        for plane in [
            Plane::try_from_points_determinant(p1, p2, p3).unwrap(),
            Plane::try_from_points_cross(p1, p2, p3).unwrap(),
        ] {
            assert!(close(plane.normal.z, 1.0, 1e-15), "{plane:?}");
            assert!(close(plane.d, 0.0, 1e-15));
        }
        // Away from the origin the shortcut works and agrees.
        let q = DVec3::new(0., 0., 2.);
        let shortcut = d_equals_one_shortcut(p1 + q, p2 + q, p3 + q).unwrap();
        let general = Plane::try_from_points_determinant(p1 + q, p2 + q, p3 + q).unwrap();
        assert!(close(shortcut.normal.dot(general.normal).abs(), 1.0, 1e-12));
    }

    #[test]
    fn both_three_point_methods_agree_and_follow_the_winding() {
        let p = [
            DVec3::new(1., 2., 3.),
            DVec3::new(4., -1., 2.),
            DVec3::new(0., 5., -2.),
        ];
        let a = Plane::try_from_points_determinant(p[0], p[1], p[2]).unwrap();
        let b = Plane::try_from_points_cross(p[0], p[1], p[2]).unwrap();
        assert!((a.normal - b.normal).length() < 1e-14);
        assert!(close(a.d, b.d, 1e-13));
        let expected = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
        assert!((a.normal - expected).length() < 1e-14);
        for q in p {
            assert!(a.signed_distance(q).abs() < 1e-13);
        }
    }

    #[test]
    fn collinear_and_coincident_points_are_errors_not_nan() {
        let a = DVec3::new(1., 1., 1.);
        let b = DVec3::new(2., 2., 2.);
        let c = DVec3::new(3., 3., 3.);
        assert!(matches!(
            Plane::try_from_points_determinant(a, b, c),
            Err(PlaneError::Collinear { .. })
        ));
        assert!(matches!(
            Plane::try_from_points_cross(a, a, b),
            Err(PlaneError::Collinear { .. })
        ));
        assert!(matches!(
            Plane::try_fit_newell(&[a, b, c]),
            Err(PlaneError::ZeroArea { .. })
        ));
        assert_eq!(
            Plane::try_from_points_cross(a, b, DVec3::new(f64::NAN, 0., 0.)),
            Err(PlaneError::NonFinite)
        );
    }

    #[test]
    fn nearly_collinear_triples_still_give_the_exact_side() {
        // c is one ulp off the line through a and b: not collinear, so a plane
        // exists; its normal is perpendicular to the line.
        let a = DVec3::new(0., 0., 0.);
        let b = DVec3::new(1., 1., 0.);
        let c = DVec3::new(0.5, 0.5 + f64::EPSILON / 2.0, 0.);
        let plane = Plane::try_from_points_cross(a, b, c).unwrap();
        assert!(close(plane.normal.z.abs(), 1.0, 1e-6), "{plane:?}");
        assert!(plane.normal.is_finite());
        assert!(matches!(
            Plane::try_from_points_determinant(a, b, DVec3::new(0.5, 0.5, 0.)),
            Err(PlaneError::Collinear { .. })
        ));
    }

    #[test]
    fn far_from_the_origin_with_unit_features() {
        let o = DVec3::splat(1e9);
        let p = [o, o + DVec3::X, o + DVec3::Y];
        for plane in [
            Plane::try_from_points_determinant(p[0], p[1], p[2]).unwrap(),
            Plane::try_from_points_cross(p[0], p[1], p[2]).unwrap(),
            Plane::try_fit_newell(&[p[0], p[1], o + DVec3::X + DVec3::Y, p[2]])
                .unwrap()
                .plane,
        ] {
            assert!((plane.normal - DVec3::Z).length() < 1e-12, "{plane:?}");
            assert!(close(plane.d, -1e9, 1e-6));
            assert!(close(
                plane.signed_distance(o + DVec3::new(0.3, 0.2, 1.0)),
                1.0,
                1e-6
            ));
        }
    }

    #[test]
    fn tiny_features() {
        let s = 1e-9;
        let p = [
            DVec3::new(0., 0., s),
            DVec3::new(s, 0., 0.),
            DVec3::new(0., s, 0.),
        ];
        let plane = Plane::try_from_points_determinant(p[0], p[1], p[2]).unwrap();
        let expected = DVec3::ONE.normalize();
        assert!((plane.normal - expected).length() < 1e-12);
        assert!(close(
            plane.signed_distance(DVec3::ZERO),
            -s / 3f64.sqrt(),
            1e-20
        ));
        let fit = Plane::try_fit_newell(&p).unwrap();
        assert!((fit.plane.normal - expected).length() < 1e-12);
        assert!(close(
            fit.vector_area.length(),
            3f64.sqrt() / 2.0 * s * s,
            1e-30
        ));
    }

    #[test]
    fn newell_reports_the_deviation_of_a_nearly_coplanar_quad() {
        let h = 1e-6;
        let quad = [
            DVec3::new(0., 0., 0.),
            DVec3::new(1., 0., h),
            DVec3::new(1., 1., 0.),
            DVec3::new(0., 1., h),
        ];
        let fit = Plane::try_fit_newell(&quad).unwrap();
        assert!(close(fit.max_deviation, h / 2.0, 1e-12), "{fit:?}");
        assert!(fit.plane.normal.z > 0.999);
        let flat = [DVec3::ZERO, DVec3::X, DVec3::X + DVec3::Y, DVec3::Y];
        assert!(Plane::try_fit_newell(&flat).unwrap().max_deviation == 0.0);
    }

    #[test]
    fn newell_handles_non_convex_polygons() {
        // An L shape of area 3, counter-clockwise in the xy-plane.
        let l = [
            DVec3::new(0., 0., 5.),
            DVec3::new(2., 0., 5.),
            DVec3::new(2., 1., 5.),
            DVec3::new(1., 1., 5.),
            DVec3::new(1., 2., 5.),
            DVec3::new(0., 2., 5.),
        ];
        let fit = Plane::try_fit_newell(&l).unwrap();
        assert!(close(fit.vector_area.z, 3.0, 1e-15));
        assert!((fit.plane.normal - DVec3::Z).length() < 1e-15);
        assert!(close(fit.plane.d, -5.0, 1e-15));
    }

    #[test]
    fn transforming_a_plane_matches_transforming_its_points() {
        let p = [
            DVec3::new(1., 2., 3.),
            DVec3::new(4., -1., 2.),
            DVec3::new(0., 5., -2.),
        ];
        let plane = Plane::try_from_points_cross(p[0], p[1], p[2]).unwrap();
        let outside = p[0] + plane.normal * 2.0;
        let transforms = [
            DAffine3::from_translation(DVec3::new(5., -3., 2.)),
            DAffine3::from_scale_rotation_translation(
                DVec3::new(2., 0.5, 3.),
                DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0),
                DVec3::new(-1., 7., 0.25),
            ),
            DAffine3::from_mat3(DMat3::from_cols_array(&[
                1., 0.5, 0., 0., 1., 0.3, 0.2, 0., 1.,
            ])),
        ];
        for t in transforms {
            let image = plane.try_transform(&t).unwrap();
            let expected = Plane::try_from_points_cross(
                t.transform_point3(p[0]),
                t.transform_point3(p[1]),
                t.transform_point3(p[2]),
            )
            .unwrap();
            // Shears and non-uniform scales change orientation only through
            // the determinant's sign; these keep it positive.
            assert!(
                (image.normal - expected.normal).length() < 1e-12,
                "{image:?} {expected:?}"
            );
            assert!(close(image.d, expected.d, 1e-11));
            assert!(image.signed_distance(t.transform_point3(outside)) > 0.0);
        }
        assert_eq!(
            plane.try_transform(&DAffine3::from_scale(DVec3::new(1., 0., 1.))),
            Err(PlaneError::NonFinite)
        );
    }
}
