//! The generalized winding number (Jacobson et al. 2013): the signed solid
//! angle of the surface seen from a point, over `4π`.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::{Sign, orient3d};

use super::{Accel, QueryError};

/// Coordinates above this magnitude are scaled by [`FAR_SCALE`] before
/// differences are taken.
const FAR: f64 = 1e300;
/// 2⁻⁶⁴: exact, and enough to keep differences of scaled coordinates finite.
const FAR_SCALE: f64 = 1.0 / 18_446_744_073_709_551_616.0;
/// Corner vectors whose largest component lies in this range are used as
/// they are; others are rescaled by a power of two (2^±300: products of three
/// lengths stay far from overflow and underflow).
const UNIT_RANGE: (f64, f64) = (4.909_093_465_297_727e-91, 2.037_035_976_334_486e90);

impl Accel {
    /// The generalized winding number of the surface around `p`:
    /// `Σ Ω(triangle) / 4π` over the fan triangles, each solid angle by Van
    /// Oosterom and Strackee's formula
    /// `tan(Ω/2) = det[a, b, c] / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|)`
    /// with `a, b, c` the corners relative to `p`.
    ///
    /// What it answers:
    /// - on a closed, outward-oriented surface: the integer number of times the
    ///   surface winds around `p` (1 inside a valid solid, 0 outside; 2 inside
    ///   two overlapping shells; −1 inside an inward-oriented shell), up to
    ///   rounding;
    /// - on an open surface (holes) or a soup: a real number that varies
    ///   smoothly away from the surface and jumps by 1 across it; `> ½` is the
    ///   usual "inside" (Jacobson et al.'s threshold), which is what
    ///   [`Method::Winding`](super::Method::Winding) uses;
    /// - exactly on the surface the value is between the two sides and means
    ///   nothing; [`Accel::classify_with`] reports such points as on the
    ///   boundary before looking at the winding number.
    ///
    /// The value is a rounded construction, except that the sign of each
    /// `det[a, b, c]` is taken from the exact `orient3d`, so a point one ulp
    /// off a face still gets that face's ±2π branch right. Cost: every
    /// triangle, `O(n)` per point (no far-field approximation).
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate.
    pub fn winding_number(&self, p: DVec3) -> Result<f64, QueryError> {
        if !p.is_finite() {
            return Err(QueryError::NonFinitePoint { index: 0, point: p });
        }
        Ok(self.winding_number_unchecked(p))
    }

    /// [`Accel::winding_number`] for every point, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first non-finite point, by index.
    pub fn winding_number_batch(&self, points: &[DVec3]) -> Result<Vec<f64>, QueryError> {
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(QueryError::NonFinitePoint {
                index,
                point: points[index],
            });
        }
        Ok(points
            .par_iter()
            .map(|&p| self.winding_number_unchecked(p))
            .collect())
    }

    pub(super) fn winding_number_unchecked(&self, p: DVec3) -> f64 {
        // Powers of two scale exactly, and the solid angle does not change
        // when the corners are scaled alike about `p`. Differences of
        // coordinates near ±`f64::MAX` overflow: such a point or model is
        // scaled down by 2⁻⁶⁴ first. Then each triangle's corner vectors are
        // brought near unit size when the products of three lengths below
        // could overflow or underflow (largest component outside
        // 2^±300), so a point at 1e308 gets a number, not NaN.
        let largest = p
            .abs()
            .max(self.bounds.min.abs())
            .max(self.bounds.max.abs())
            .max_element();
        let pre = if largest > FAR { FAR_SCALE } else { 1.0 };
        let q = p * pre;
        let mut total = 0.0;
        for [ta, tb, tc] in self.tris.iter().map(|t| t.corners()) {
            let (mut a, mut b, mut c) = (ta * pre - q, tb * pre - q, tc * pre - q);
            let size = a.abs().max(b.abs()).max(c.abs()).max_element();
            if size > 0.0 && !(UNIT_RANGE.0..=UNIT_RANGE.1).contains(&size) {
                let s = 2f64.powi((-size.log2().floor() as i32).clamp(-1022, 1022));
                (a, b, c) = (a * s, b * s, c * s);
            }
            let (la, lb, lc) = (a.length(), b.length(), c.length());
            let mut det = a.dot(b.cross(c));
            let exact = orient3d(p, ta, tb, tc);
            if Sign::of(det) != exact {
                det = match exact {
                    Sign::Zero => 0.0,
                    s => f64::from(s.as_i32()) * det.abs().max(f64::MIN_POSITIVE),
                };
            }
            let denom = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
            total += 2.0 * det.atan2(denom);
        }
        total / (4.0 * std::f64::consts::PI)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn winding_number_of_a_cube() {
        let accel = Accel::new(&builders::cube());
        let inside = accel.winding_number(DVec3::new(0.1, 0.2, 0.3)).unwrap();
        let outside = accel.winding_number(DVec3::new(3.0, 0.2, 0.3)).unwrap();
        assert!((inside - 1.0).abs() < 1e-12, "{inside}");
        assert!(outside.abs() < 1e-12, "{outside}");
    }

    #[test]
    fn far_points_get_a_number_not_nan() {
        // Found by the queries fuzz check (fixtures/fuzz/queries/): lengths of corner
        // vectors overflowed for a point at −1.8e308 and the sum was NaN.
        let accel = Accel::new(&builders::cube());
        for p in [
            DVec3::new(-f64::MAX, 1e-156, 0.0),
            DVec3::new(f64::MAX, -f64::MAX, 1e300),
            DVec3::new(-1e200, 0.5, 0.5),
        ] {
            let w = accel.winding_number(p).unwrap();
            assert!(w.abs() < 1e-12, "{p}: {w}");
        }
        // A large model, seen from inside and from much farther away.
        let large = builders::cuboid(DVec3::splat(-1e50), DVec3::splat(1e50)).unwrap();
        let accel = Accel::new(&large);
        let inside = accel.winding_number(DVec3::new(1e49, 2e49, -3e49)).unwrap();
        assert!((inside - 1.0).abs() < 1e-12, "{inside}");
        let outside = accel
            .winding_number(DVec3::new(-f64::MAX, 0.0, 0.0))
            .unwrap();
        assert!(outside.abs() < 1e-12, "{outside}");
    }
}
