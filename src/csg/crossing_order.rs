//! The order of crossings from different leaves, decided exactly where
//! their rounded parameters cannot tell.
//!
//! A leaf's crossing parameter `t` is a rounded construction. Two leaves
//! that share a tilted face (two meshes, a mesh and a half-space) meet the
//! ray at the same exact `t` but may round it to neighbouring `f64`s, which
//! left a span one ulp long (or a gap) where there is none. So every
//! crossing of a flat piece carries, beside `t`, a certified bound on its
//! rounding (its *spread*: the exact `t` lies within `t ± spread`), and two
//! crossings whose `t ± spread` overlap are compared exactly: `t = N / D`
//! with `N = n · (q − o)` and `D = n · d` for the plane through `q` with
//! normal `n` (for a triangle `n = (b − a) × (c − a)`, `q = a`), evaluated
//! in exact dyadic arithmetic, so equal crossings are taken together and
//! distinct ones in their true order.
//!
//! A transformed box or polyhedron is a polyhedron moved into the world
//! (its vertices rounded once), so its crossings carry their triangle's
//! plane like any mesh's. Crossings of curved surfaces (transformed or
//! not) carry no plane; they are ordered by their rounded `t`.

use std::cmp::Ordering;

use glam::DVec3;

use crate::geom::dyadic::Dyadic;
use crate::geom::implicit::Arithmetic;
use crate::geom::{Ray, Sign};

/// The plane of a flat piece of a leaf's boundary, in the frame of the rays
/// the leaf is given: what makes its crossings' `t` exact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CrossingPlane {
    /// The plane `x[axis] = value` of a box face.
    Axis {
        /// 0, 1 or 2.
        axis: usize,
        /// The coordinate.
        value: f64,
    },
    /// The plane through `point` with normal `normal` (a half-space).
    PointNormal {
        /// A point of the plane.
        point: DVec3,
        /// Its normal, exact as given.
        normal: DVec3,
    },
    /// The plane of a triangle.
    Triangle([DVec3; 3]),
}

impl CrossingPlane {
    /// `(N, D)` with `t = N / D` for the ray, in the arithmetic `T`.
    fn parts<T: Arithmetic>(&self, ray: &Ray) -> (T, T) {
        let o = |k: usize| T::of(ray.origin[k]);
        let d = |k: usize| T::of(ray.direction[k]);
        match *self {
            CrossingPlane::Axis { axis, value } => (T::of(value).minus(&o(axis)), d(axis)),
            CrossingPlane::PointNormal { point, normal } => {
                let n = [0, 1, 2].map(|k| T::of(normal[k]));
                let q = [0, 1, 2].map(|k| T::of(point[k]).minus(&o(k)));
                (dot(&n, &q), dot(&n, &[0, 1, 2].map(d)))
            }
            CrossingPlane::Triangle([a, b, c]) => {
                let e1 = [0, 1, 2].map(|k| T::of(b[k]).minus(&T::of(a[k])));
                let e2 = [0, 1, 2].map(|k| T::of(c[k]).minus(&T::of(a[k])));
                let n = cross(&e1, &e2);
                let q = [0, 1, 2].map(|k| T::of(a[k]).minus(&o(k)));
                (dot(&n, &q), dot(&n, &[0, 1, 2].map(d)))
            }
        }
    }

    /// A bound on `|t − t_exact|` for a leaf's rounded `t` of a crossing
    /// with this plane, as an `f32` rounded up: infinite when it cannot be
    /// bounded cheaply (a ray nearly in the plane, magnitudes near the ends
    /// of the `f64` range), which sends every comparison with it to exact
    /// arithmetic.
    ///
    /// A static forward error bound, a few dozen flops: `t̂ = N̂ / D̂` is
    /// recomputed in `f64`, where each monomial of `N` (a product of three
    /// coordinate differences for a triangle) carries at most `m` roundings,
    /// so `|N̂ − N| ≤ γ_m M` with `M` the sum of the monomials' magnitudes
    /// (likewise `D`); then `|t̂ − t| ≤ (e_N + |t̂| e_D) / (|D̂| − e_D)` plus
    /// the quotient's rounding, and the leaf's `t` is within `|t − t̂|` of
    /// that.
    #[must_use]
    pub fn spread(&self, ray: &Ray, t: f64) -> f32 {
        const U: f64 = f64::EPSILON / 2.0;
        let (o, d) = (ray.origin, ray.direction);
        // N̂, D̂, the magnitudes of their monomials, and the roundings each
        // monomial of N and of D carries.
        let (n_hat, d_hat, n_size, d_size, n_round, d_round) = match *self {
            // One subtraction and one division, each rounded.
            CrossingPlane::Axis { .. } => {
                return up_to_f32(2.0 * f64::EPSILON * t.abs() + f64::MIN_POSITIVE);
            }
            CrossingPlane::PointNormal { point, normal } => {
                let w = point - o;
                (
                    normal.dot(w),
                    normal.dot(d),
                    normal.abs().dot(w.abs()),
                    normal.abs().dot(d.abs()),
                    4.0,
                    3.0,
                )
            }
            CrossingPlane::Triangle([a, b, c]) => {
                let (e1, e2, w) = (b - a, c - a, a - o);
                let n = e1.cross(e2);
                let (p, q) = (e1.abs(), e2.abs());
                let size = DVec3::new(
                    p.y * q.z + p.z * q.y,
                    p.z * q.x + p.x * q.z,
                    p.x * q.y + p.y * q.x,
                );
                (
                    n.dot(w),
                    n.dot(d),
                    size.dot(w.abs()),
                    size.dot(d.abs()),
                    8.0,
                    7.0,
                )
            }
        };
        // Below these magnitudes products may lose bits to underflow; above,
        // they may overflow: no static bound then.
        let sane = |x: f64| x.is_finite() && (x == 0.0 || (1e-280..1e280).contains(&x.abs()));
        if ![n_size, d_size, t].into_iter().all(sane) || d_size == 0.0 {
            return f32::INFINITY;
        }
        // γ_m ≤ (m + 1) u for small m; the sizes were themselves rounded
        // (a few u), covered by the factor 1 + 2⁻⁴⁰.
        let slack = 1.0 + f64::powi(2.0, -40);
        let e_n = (n_round + 1.0) * U * n_size * slack;
        let e_d = (d_round + 1.0) * U * d_size * slack;
        let room = d_hat.abs() - e_d;
        if room <= 0.0 {
            return f32::INFINITY;
        }
        let t_hat = n_hat / d_hat;
        let bound =
            ((e_n + t_hat.abs() * e_d) / room + 2.0 * U * t_hat.abs()) * slack + f64::MIN_POSITIVE;
        up_to_f32((t - t_hat).abs() * slack + bound)
    }
}

/// `x` as an `f32` no smaller than `x`.
fn up_to_f32(x: f64) -> f32 {
    if x.is_nan() {
        return f32::INFINITY;
    }
    let f = x as f32;
    if f64::from(f) < x { f.next_up() } else { f }
}

fn dot<T: Arithmetic>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0].times(&b[0])
        .plus(&a[1].times(&b[1]))
        .plus(&a[2].times(&b[2]))
}

fn cross<T: Arithmetic>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1].times(&b[2]).minus(&a[2].times(&b[1])),
        a[2].times(&b[0]).minus(&a[0].times(&b[2])),
        a[0].times(&b[1]).minus(&a[1].times(&b[0])),
    ]
}

/// The exact order of the crossings of `ray` with two planes; `None` when
/// the ray is parallel to either (no crossing parameter).
#[must_use]
pub fn compare_exactly(a: &CrossingPlane, b: &CrossingPlane, ray: &Ray) -> Option<Ordering> {
    let (na, da) = a.parts::<Dyadic>(ray);
    let (nb, db) = b.parts::<Dyadic>(ray);
    let (sa, sb) = (da.sign(), db.sign());
    if sa == Sign::Zero || sb == Sign::Zero {
        return None;
    }
    // na / da − nb / db has the sign of (na·db − nb·da) · da · db.
    let difference = (&(&na * &db) - &(&nb * &da)).sign();
    let sign = if sa == sb {
        difference
    } else {
        difference.reversed()
    };
    Some(sign.ordering())
}

/// Whether `t₁ ± s₁` and `t₂ ± s₂` are certainly apart, and which way:
/// the gap, rounded, must exceed the spreads with room for that rounding.
#[must_use]
#[inline(always)]
pub(crate) fn certain_order(t1: f64, s1: f32, t2: f64, s2: f32) -> Option<Ordering> {
    let allowance = (f64::from(s1) + f64::from(s2)) * (1.0 + 4.0 * f64::EPSILON);
    let gap = t1 - t2;
    if gap > allowance {
        Some(Ordering::Greater)
    } else if -gap > allowance {
        Some(Ordering::Less)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_tilted_planes_give_equal_crossings_and_ulps_are_ordered() {
        let tri = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.7, 0.4, 0.1),
            DVec3::new(0.3, 1.9, 0.7),
        ];
        // The same plane from another corner order.
        let same = CrossingPlane::Triangle([tri[1], tri[2], tri[0]]);
        let ray = Ray::new(DVec3::new(-3.0, -2.5, -1.25), DVec3::new(1.0, 0.7, 0.6));
        let a = CrossingPlane::Triangle(tri);
        assert_eq!(compare_exactly(&a, &same, &ray), Some(Ordering::Equal));
        // A plane one ulp over along z is crossed later or earlier, never
        // equally.
        let lifted = CrossingPlane::Triangle(tri.map(|p| DVec3::new(p.x, p.y, p.z.next_up())));
        assert_ne!(compare_exactly(&a, &lifted, &ray), Some(Ordering::Equal));
        // The spread bounds the rounded t: the exact t (a dyadic quotient,
        // rounded) is within it, and it is small.
        let (n, d) = a.parts::<Dyadic>(&ray);
        let exact = n.quotient_to_f64(&d);
        let t = exact.next_up().next_up();
        let s = a.spread(&ray, t);
        assert!(
            f64::from(s) >= (t - exact).abs() && f64::from(s) < 1e-12 * t.abs(),
            "{s} {t}"
        );
        let p = CrossingPlane::PointNormal {
            point: tri[0],
            normal: DVec3::new(0.3, -0.2, 0.9),
        };
        let (n, d) = p.parts::<Dyadic>(&ray);
        let exact = n.quotient_to_f64(&d);
        let s = p.spread(&ray, exact);
        assert!(s > 0.0 && f64::from(s) < 1e-12 * exact.abs(), "{s} {exact}");
        // A parallel ray has no crossing to compare.
        let flat = CrossingPlane::Axis {
            axis: 2,
            value: 1.0,
        };
        let along = Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(compare_exactly(&flat, &a, &along), None);
    }

    #[test]
    fn certain_order_needs_a_gap_beyond_the_spreads() {
        assert_eq!(certain_order(1.0, 0.0, 2.0, 0.0), Some(Ordering::Less));
        assert_eq!(certain_order(1.0, 0.6, 2.0, 0.6), None);
        assert_eq!(certain_order(2.0, 0.4, 1.0, 0.4), Some(Ordering::Greater));
        assert_eq!(certain_order(1.0, f32::INFINITY, 9.0, 0.0), None);
        assert!(f64::from(up_to_f32(0.1)) >= 0.1);
    }
}
