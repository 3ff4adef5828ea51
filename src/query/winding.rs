//! The generalized winding number (Jacobson et al. 2013): the signed solid
//! angle of the surface seen from a point, over `4π`.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::{Sign, orient3d};

use super::{Accel, QueryError};

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
        let mut total = 0.0;
        for [ta, tb, tc] in self.tris.iter().map(|t| t.corners()) {
            let (a, b, c) = (ta - p, tb - p, tc - p);
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
}
