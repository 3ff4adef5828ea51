//! Points made by intersections, kept as the inputs that define them.
//!
//! A boolean's new vertices are where an edge of one solid meets a face of
//! another, where two coplanar edges cross, or — when several solids are
//! combined at once — where three faces' planes meet. Rounding such a point to
//! `f64` moves it off the lines and planes it lies on, and a later sign
//! computed from the rounded point can contradict the construction. So the
//! point is kept as its definition and every predicate on it is evaluated
//! from the definition: in homogeneous coordinates `(X, Y, Z, W)` whose
//! entries are polynomials in input coordinates, by the interval filter and
//! then, if the filter cannot decide, exactly (the indirect predicates of
//! Attene 2020 and Cherchi et al. 2022, written here from their idea).

use glam::DVec3;

use crate::geom::Aabb;
use crate::geom::dyadic::Dyadic;

use super::arithmetic::Arithmetic;
use super::double_double::in_safe_range;
use super::interval::Interval;

/// A point given exactly: explicit coordinates, or the intersection that
/// defines it.
///
/// # Invariants
///
/// The constructions are not degenerate: for [`ImplicitPoint::EdgePlane`]
/// the segment is not parallel to the plane, for [`ImplicitPoint::EdgeEdge`]
/// the two segments are not parallel in the projection, for
/// [`ImplicitPoint::ThreePlanes`] the three normals are independent, so the
/// homogeneous weight `W` is never zero. Callers establish this with exact predicates
/// before they make the point.
#[derive(Clone, Debug, PartialEq)]
pub enum ImplicitPoint {
    /// A point with `f64` coordinates.
    Explicit(DVec3),
    /// The line through `p` and `q` meets the plane through `plane[0..3]`.
    EdgePlane {
        /// One end of the segment.
        p: DVec3,
        /// The other end.
        q: DVec3,
        /// Three points spanning the plane.
        plane: [DVec3; 3],
    },
    /// The line through `p` and `q` meets the line through `r` and `s`, all
    /// four in one plane; the crossing is found in the projection that drops
    /// coordinate `drop_axis`, in which the lines are not parallel.
    EdgeEdge {
        /// One end of the first segment (the point lies on its line).
        p: DVec3,
        /// The other end of the first segment.
        q: DVec3,
        /// One end of the second segment.
        r: DVec3,
        /// The other end of the second segment.
        s: DVec3,
        /// The coordinate the projection drops (0, 1 or 2).
        drop_axis: u8,
    },
    /// The three planes, each through three points, meet in this point.
    ThreePlanes {
        /// Three points spanning each plane (boxed: the other points are
        /// half its size, and most points are not of this kind).
        planes: Box<[[DVec3; 3]; 3]>,
    },
}

/// Homogeneous coordinates: the point `(x / w, y / w, z / w)`, `w ≠ 0`.
#[derive(Clone, Debug)]
pub(crate) struct Homogeneous<T> {
    pub xyz: [T; 3],
    pub w: T,
}

/// Something with exact homogeneous coordinates: an implicit point, or a
/// point made from several (the centroid of a triangle of them).
pub(crate) trait HasHomogeneous {
    /// The coordinates in the arithmetic `T`.
    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T>;

    /// The coordinates as intervals (the filter stage); a point that keeps
    /// them computed returns its copy.
    fn filter(&self) -> Homogeneous<Interval> {
        self.homogeneous()
    }

    /// The exact coordinates (the stage after the filter); a point that
    /// keeps them computed returns its copy.
    fn exact(&self) -> Homogeneous<Dyadic> {
        self.homogeneous()
    }

    /// Whether every coordinate the point is made from is in the
    /// double-double stage's safe range (see
    /// [`in_safe_range`](super::double_double::in_safe_range)), so that
    /// stage may be used on it. `false` unless the point says so.
    fn double_double_safe(&self) -> bool {
        false
    }

    /// Coordinate `axis` when the definition gives it exactly, without
    /// arithmetic (see [`ImplicitPoint::simplified`]); `None` says nothing.
    fn known_coordinate(&self, axis: usize) -> Option<f64> {
        let _ = axis;
        None
    }
}

fn exact<T: Arithmetic>(v: DVec3) -> [T; 3] {
    [T::of(v.x), T::of(v.y), T::of(v.z)]
}

fn difference<T: Arithmetic>(a: DVec3, b: DVec3) -> [T; 3] {
    let (a, b) = (exact::<T>(a), exact::<T>(b));
    [a[0].minus(&b[0]), a[1].minus(&b[1]), a[2].minus(&b[2])]
}

pub(crate) fn cross<T: Arithmetic>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1].times(&b[2]).minus(&a[2].times(&b[1])),
        a[2].times(&b[0]).minus(&a[0].times(&b[2])),
        a[0].times(&b[1]).minus(&a[1].times(&b[0])),
    ]
}

pub(crate) fn dot<T: Arithmetic>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0].times(&b[0])
        .plus(&a[1].times(&b[1]))
        .plus(&a[2].times(&b[2]))
}

/// `p + (N / D)·(q − p)` in homogeneous form: `(p·D + (q − p)·N, D)`.
fn on_segment<T: Arithmetic>(p: DVec3, q: DVec3, numerator: T, denominator: T) -> Homogeneous<T> {
    let base = exact::<T>(p);
    let step = difference::<T>(q, p);
    let coordinate = |i: usize| base[i].times(&denominator).plus(&step[i].times(&numerator));
    Homogeneous {
        xyz: [coordinate(0), coordinate(1), coordinate(2)],
        w: denominator,
    }
}

/// The two coordinates kept by the projection that drops `axis`, in cyclic
/// order (`y, z` for `x`; `z, x` for `y`; `x, y` for `z`): the orientation
/// of a projected triangle is then the sign of its normal's `axis`
/// component.
#[must_use]
pub(crate) fn kept_axes(axis: u8) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (2, 0),
        _ => (0, 1),
    }
}

impl HasHomogeneous for ImplicitPoint {
    fn known_coordinate(&self, axis: usize) -> Option<f64> {
        let shared = |points: &[DVec3]| {
            points[1..]
                .iter()
                .all(|p| p[axis] == points[0][axis])
                .then_some(points[0][axis])
        };
        match self {
            ImplicitPoint::Explicit(v) => Some(v[axis]),
            ImplicitPoint::EdgePlane { p, q, plane } => shared(&[*p, *q]).or_else(|| shared(plane)),
            ImplicitPoint::EdgeEdge { p, q, r, s, .. } => {
                shared(&[*p, *q]).or_else(|| shared(&[*r, *s]))
            }
            ImplicitPoint::ThreePlanes { planes } => planes.iter().find_map(|plane| shared(plane)),
        }
    }

    fn double_double_safe(&self) -> bool {
        let safe = |points: &[DVec3]| {
            points
                .iter()
                .all(|p| p.to_array().into_iter().all(in_safe_range))
        };
        match self {
            ImplicitPoint::Explicit(v) => safe(&[*v]),
            ImplicitPoint::EdgePlane { p, q, plane } => safe(&[*p, *q]) && safe(plane),
            ImplicitPoint::EdgeEdge { p, q, r, s, .. } => safe(&[*p, *q, *r, *s]),
            ImplicitPoint::ThreePlanes { planes } => planes.iter().all(|plane| safe(plane)),
        }
    }

    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T> {
        match *self {
            ImplicitPoint::Explicit(v) => Homogeneous {
                xyz: exact(v),
                w: T::of(1.0),
            },
            ImplicitPoint::EdgePlane {
                p,
                q,
                plane: [a, b, c],
            } => {
                let normal = cross(&difference::<T>(b, a), &difference::<T>(c, a));
                let numerator = dot(&normal, &difference::<T>(a, p));
                let denominator = dot(&normal, &difference::<T>(q, p));
                on_segment(p, q, numerator, denominator)
            }
            ImplicitPoint::EdgeEdge {
                p,
                q,
                r,
                s,
                drop_axis,
            } => {
                let (u, v) = kept_axes(drop_axis);
                let cross2 = |a: &[T; 3], b: &[T; 3]| a[u].times(&b[v]).minus(&a[v].times(&b[u]));
                let along = difference::<T>(q, p);
                let other = difference::<T>(s, r);
                let numerator = cross2(&difference::<T>(r, p), &other);
                let denominator = cross2(&along, &other);
                on_segment(p, q, numerator, denominator)
            }
            ImplicitPoint::ThreePlanes { ref planes } => {
                // n_k · x = d_k for k = 0, 1, 2, by Cramer's rule:
                // x = (d0 (n1 × n2) + d1 (n2 × n0) + d2 (n0 × n1)) / (n0 · (n1 × n2)).
                let [(n0, d0), (n1, d1), (n2, d2)] = (**planes).map(|[a, b, c]| {
                    let normal = cross(&difference::<T>(b, a), &difference::<T>(c, a));
                    let offset = dot(&normal, &exact::<T>(a));
                    (normal, offset)
                });
                let (c12, c20, c01) = (cross(&n1, &n2), cross(&n2, &n0), cross(&n0, &n1));
                let coordinate = |i: usize| {
                    d0.times(&c12[i])
                        .plus(&d1.times(&c20[i]))
                        .plus(&d2.times(&c01[i]))
                };
                Homogeneous {
                    xyz: [coordinate(0), coordinate(1), coordinate(2)],
                    w: dot(&n0, &c12),
                }
            }
        }
    }
}

/// A box that surely holds `p` (its interval coordinates, widened by two
/// units in the last place for the division).
pub(crate) fn enclosing_box(p: &impl HasHomogeneous) -> Aabb {
    let filter = p.filter();
    let bound = |i: usize| -> (f64, f64) {
        let (x, w) = (filter.xyz[i], filter.w);
        if w.lo <= 0.0 && w.hi >= 0.0 {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        let q = [x.lo / w.lo, x.lo / w.hi, x.hi / w.lo, x.hi / w.hi];
        let lo = q.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = q.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo.next_down().next_down(), hi.next_up().next_up())
    };
    let (x, y, z) = (bound(0), bound(1), bound(2));
    Aabb {
        min: DVec3::new(x.0, y.0, z.0),
        max: DVec3::new(x.1, y.1, z.1),
    }
}

/// The centroid of three points: strictly inside their triangle when the
/// triangle is not degenerate.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Centroid<P>(pub [P; 3]);

impl<P: HasHomogeneous> HasHomogeneous for Centroid<P> {
    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T> {
        let [a, b, c] = [0, 1, 2].map(|i| self.0[i].homogeneous::<T>());
        centroid_of(a, b, c)
    }

    fn filter(&self) -> Homogeneous<Interval> {
        let [a, b, c] = [0, 1, 2].map(|i| self.0[i].filter());
        centroid_of(a, b, c)
    }

    fn exact(&self) -> Homogeneous<Dyadic> {
        let [a, b, c] = [0, 1, 2].map(|i| self.0[i].exact());
        centroid_of(a, b, c)
    }
}

fn centroid_of<T: Arithmetic>(
    a: Homogeneous<T>,
    b: Homogeneous<T>,
    c: Homogeneous<T>,
) -> Homogeneous<T> {
    // (A/wa + B/wb + C/wc) / 3 = (A·wb·wc + B·wa·wc + C·wa·wb) / (3·wa·wb·wc)
    let bc = b.w.times(&c.w);
    let ac = a.w.times(&c.w);
    let ab = a.w.times(&b.w);
    let coordinate = |i: usize| {
        a.xyz[i]
            .times(&bc)
            .plus(&b.xyz[i].times(&ac))
            .plus(&c.xyz[i].times(&ab))
    };
    Homogeneous {
        xyz: [coordinate(0), coordinate(1), coordinate(2)],
        w: T::of(3.0).times(&a.w).times(&bc),
    }
}

impl ImplicitPoint {
    /// The same point with explicit coordinates when every coordinate is
    /// known exactly from the definition: a segment whose ends share a
    /// coordinate keeps it, and so does a point on a plane (or a line in
    /// the plane's projection) whose defining points share it — an edge of
    /// a cylinder along `z` through the top face of a box is the point
    /// `(x, y, top)` with the edge's own `x` and `y`. Otherwise `self`.
    #[must_use]
    pub fn simplified(self) -> ImplicitPoint {
        if self.explicit().is_some() {
            return self;
        }
        match [0, 1, 2].map(|k| self.known_coordinate(k)) {
            [Some(x), Some(y), Some(z)] => ImplicitPoint::Explicit(DVec3::new(x, y, z)),
            _ => self,
        }
    }

    /// The explicit coordinates, if the point has them.
    #[must_use]
    pub fn explicit(&self) -> Option<DVec3> {
        match *self {
            ImplicitPoint::Explicit(v) => Some(v),
            _ => None,
        }
    }
}
