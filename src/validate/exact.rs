//! Exact signs of sums that no single predicate covers: the signed volume of
//! a closed shell, and the winding number of a closed shell around a point.
//!
//! The volume sign is filtered first (a rounded sum with a forward error
//! bound) and falls back to exact expansion arithmetic (Shewchuk's
//! `two_sum`/`two_product` and `grow_expansion`) only when the filter cannot
//! decide, so nearly flat shells get the right sign too; coordinates outside
//! the range where expansions are exact (`geom::dyadic`) are summed in
//! exact big-integer arithmetic instead.

use glam::{DVec2, DVec3};

use crate::geom::dyadic::{Dyadic, in_safe_range};
use crate::geom::expansion::{Expansion, two_product};
use crate::geom::{Sign, UNDERFLOW, orient2d, orient3d};

/// Adds `sign · a · b · c` to `sum` exactly.
fn grow_triple_product(sum: &mut Expansion, sign: f64, a: f64, b: f64, c: f64) {
    let (p, e) = two_product(a, b);
    sum.grow_product(sign * p, c);
    sum.grow_product(sign * e, c);
}

/// The filter for [`volume_sign`]: `Σ a·(b × c)` in rounded arithmetic with
/// a forward error bound, accumulated triangle by triangle.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct VolumeFilter {
    sum: f64,
    magnitude: f64,
    count: f64,
    /// `Σ (|cₖ| + 1)` over the last factors of the products (see
    /// [`VolumeFilter::sign`]).
    last_factors: f64,
}

impl VolumeFilter {
    /// Adds one triangle's `a·(b × c)`.
    pub fn add(&mut self, a: DVec3, b: DVec3, c: DVec3) {
        let terms = [
            a.x * b.y * c.z,
            -a.x * b.z * c.y,
            -a.y * b.x * c.z,
            a.y * b.z * c.x,
            a.z * b.x * c.y,
            -a.z * b.y * c.x,
        ];
        for t in terms {
            self.sum += t;
            self.magnitude += t.abs();
        }
        self.count += 1.0;
        // Each corner coordinate of `c` ends two of the six products.
        self.last_factors += 2.0 * (c.x.abs() + c.y.abs() + c.z.abs()) + 6.0;
    }

    /// Adds another filter's sums (triangles of the same shell).
    pub fn merge(&mut self, other: &VolumeFilter) {
        self.sum += other.sum;
        self.magnitude += other.magnitude;
        self.count += other.count;
        self.last_factors += other.last_factors;
    }

    /// The sign when the rounded sum is certain to have it. Each product
    /// carries at most 2 rounding errors and the running sums one per
    /// addition: `|error| ≤ (6n + 8) ε Σ|terms|` (generous). A product
    /// `(a·b)·c` rounded in the subnormal range errs by at most a further
    /// `η(1 + ε)(|c| + 1)` (`η = 2⁻¹⁰⁷⁵`), covered by `UNDERFLOW · Σ(|c| + 1)`;
    /// overflow leaves the sum or the bound non-finite, which decides
    /// nothing.
    pub fn sign(&self) -> Option<Sign> {
        let bound = (6.0 * self.count + 8.0) * f64::EPSILON * self.magnitude
            + UNDERFLOW * self.last_factors;
        (self.sum.is_finite() && bound.is_finite() && self.sum.abs() > bound)
            .then(|| Sign::of(self.sum))
    }
}

/// The six terms of `a·(b × c)`: sign and the axes of `a`, `b`, `c`.
const VOLUME_TERMS: [(f64, [usize; 3]); 6] = [
    (1.0, [0, 1, 2]),
    (-1.0, [0, 2, 1]),
    (-1.0, [1, 0, 2]),
    (1.0, [1, 2, 0]),
    (1.0, [2, 0, 1]),
    (-1.0, [2, 1, 0]),
];

/// The exact sign of `Σ a·(b × c)` over the given triangles: six times the
/// signed volume of a closed triangulated surface (positive when outward).
#[must_use]
pub(crate) fn volume_sign(triangles: &[[DVec3; 3]]) -> Sign {
    let mut filter = VolumeFilter::default();
    for &[a, b, c] in triangles {
        filter.add(a, b, c);
    }
    if let Some(sign) = filter.sign() {
        return sign;
    }
    let coordinates = triangles
        .iter()
        .flat_map(|t| t.iter().flat_map(|p| p.to_array()));
    if !coordinates.clone().all(|x| in_safe_range(&[x])) {
        if !coordinates.clone().all(f64::is_finite) {
            // Unspecified for non-finite input (never a panic).
            return Sign::Zero;
        }
        let mut exact = Dyadic::of(0.0);
        for &[a, b, c] in triangles {
            for (sign, [i, j, k]) in VOLUME_TERMS {
                let term = &(&Dyadic::of(a[i]) * &Dyadic::of(b[j])) * &Dyadic::of(c[k]);
                exact = if sign > 0.0 {
                    &exact + &term
                } else {
                    &exact - &term
                };
            }
        }
        return exact.sign();
    }
    let mut exact = Expansion::default();
    for &[a, b, c] in triangles {
        for (sign, [i, j, k]) in VOLUME_TERMS {
            grow_triple_product(&mut exact, sign, a[i], b[j], c[k]);
        }
    }
    exact.sign()
}

/// The side of the `yz`-projected point `p` against the directed edge `ab`,
/// with `p` perturbed by `(ε, ε²)` (Simulation of Simplicity) so that it is
/// never exactly on an edge: consistent for the two faces sharing an edge.
fn perturbed_side(a: DVec2, b: DVec2, p: DVec2) -> Sign {
    let s = orient2d(a, b, p);
    if s != Sign::Zero {
        return s;
    }
    // d/dpx of orient2d(a, b, p) is a.y − b.y; d/dpy is b.x − a.x.
    if a.y != b.y {
        return if a.y > b.y {
            Sign::Positive
        } else {
            Sign::Negative
        };
    }
    if a.x != b.x {
        return if b.x > a.x {
            Sign::Positive
        } else {
            Sign::Negative
        };
    }
    Sign::Zero
}

/// The winding number of a closed triangulated surface around each point `p`, counted
/// along the ray `p + t·x̂`, `t > 0`: `1` inside an outward shell, `-1`
/// inside an inward one, `0` outside. Exact, with ties of the ray against
/// edges and vertices broken by symbolic perturbation of `p` by `(0, ε, ε²)`.
/// `None` when `p` lies on a face the ray crosses; a point on a face parallel
/// to the ray is counted as the perturbed point. One answer per point of
/// `points`, in one pass over the triangles (each triangle's box made once
/// for all of them).
#[must_use]
pub(crate) fn winding_numbers(triangles: &[[DVec3; 3]], points: &[DVec3]) -> Vec<Option<i64>> {
    let yz = |v: DVec3| DVec2::new(v.y, v.z);
    let mut windings: Vec<Option<i64>> = vec![Some(0); points.len()];
    for &[a, b, c] in triangles {
        // Cheap rejection on the projected box.
        let (lo_y, hi_y) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        let (lo_z, hi_z) = (a.z.min(b.z).min(c.z), a.z.max(b.z).max(c.z));
        let hi_x = a.x.max(b.x).max(c.x);
        for (p, winding) in points.iter().zip(&mut windings) {
            if p.y < lo_y || p.y > hi_y || p.z < lo_z || p.z > hi_z || p.x > hi_x {
                continue;
            }
            let Some(w) = winding else {
                continue;
            };
            let (a2, b2, c2, q) = (yz(a), yz(b), yz(c), yz(*p));
            let s = perturbed_side(a2, b2, q);
            if s == Sign::Zero || perturbed_side(b2, c2, q) != s || perturbed_side(c2, a2, q) != s {
                continue;
            }
            // s is the sign of the triangle's normal along x. The crossing
            // is ahead of p when p is behind the plane as seen along the
            // normal.
            match orient3d(a, b, c, *p) {
                Sign::Zero => *winding = None,
                side if side == -s => *w += s.as_i32() as i64,
                _ => {}
            }
        }
    }
    windings
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(offset: DVec3, scale: f64, outward: bool) -> Vec<[DVec3; 3]> {
        let solid = crate::mesh::builders::cube();
        let mut out = Vec::new();
        for (f, _) in solid.faces() {
            let v: Vec<DVec3> = solid
                .face_vertices(f)
                .map(|v| solid.position(v) * scale + offset)
                .collect();
            for i in 1..v.len() - 1 {
                out.push(if outward {
                    [v[0], v[i], v[i + 1]]
                } else {
                    [v[0], v[i + 1], v[i]]
                });
            }
        }
        out
    }

    #[test]
    fn volume_sign_and_winding() {
        let c = cube(DVec3::new(1e8, 0., 0.), 1.0, true);
        assert_eq!(volume_sign(&c), Sign::Positive);
        assert_eq!(volume_sign(&cube(DVec3::ZERO, 1.0, false)), Sign::Negative);
        let c = cube(DVec3::ZERO, 1.0, true);
        let points = [
            DVec3::ZERO,
            // On a face the ray crosses: on the surface.
            DVec3::new(-1., 0.5, 0.25),
            // On a face parallel to the ray: the perturbed point (y + ε) is in.
            DVec3::new(0., -1., 0.),
            // Rays through edges and vertices: perturbation keeps the count
            // exact.
            DVec3::new(-5., 1., 1.),
            DVec3::new(-5., 0., 0.),
            DVec3::new(0.5, 0., 0.),
            DVec3::new(5., 0., 0.),
        ];
        assert_eq!(
            winding_numbers(&c, &points),
            [Some(1), None, Some(1), Some(0), Some(0), Some(1), Some(0)]
        );
        let inward = cube(DVec3::ZERO, 1.0, false);
        assert_eq!(
            winding_numbers(&inward, &[DVec3::new(0.25, 0.5, -0.5)]),
            [Some(-1)]
        );
    }

    #[test]
    fn volume_sign_over_the_whole_range() {
        // Cubes whose triple products underflow (2^-400: 2^-1200 per term)
        // or overflow (2^400), one far from its size (2^250 at 2^300: the
        // rounded sum cancels to nothing), and a flat shell at 2^-1000
        // (exact zero).
        let scale = |k: i32| 2f64.powi(k);
        for (offset, size) in [
            (DVec3::ZERO, scale(-400)),
            (DVec3::splat(scale(-399)), scale(-400)),
            (DVec3::ZERO, scale(400)),
            (DVec3::new(scale(300), 0., 0.), scale(250)),
        ] {
            for outward in [true, false] {
                let want = if outward {
                    Sign::Positive
                } else {
                    Sign::Negative
                };
                let c = cube(offset, size, outward);
                assert_eq!(volume_sign(&c), want, "{offset} {size:e} {outward}");
            }
        }
        let p = |x: f64, y: f64| DVec3::new(x, y, 0.0) * scale(-1000);
        let flat = [
            [p(0., 0.), p(1., 0.), p(0., 1.)],
            [p(0., 0.), p(0., 1.), p(1., 0.)],
        ];
        assert_eq!(volume_sign(&flat), Sign::Zero);
    }

    #[test]
    fn exact_fallback_for_a_flat_shell() {
        // A doubly covered triangle encloses nothing: the sum is exactly 0.
        let t = [
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.7, 0.9, 0.3),
            DVec3::new(0.4, 2.2, 1.3),
        ];
        let flat = vec![t, [t[0], t[2], t[1]]];
        assert_eq!(volume_sign(&flat), Sign::Zero);
        let mut e = Expansion::default();
        e.grow(1e100);
        e.grow(1.0);
        e.grow(-1e100);
        assert_eq!(e.sign(), Sign::Positive);
    }
}
