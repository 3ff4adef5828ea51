//! Stage 2: where two triangles meet, decided exactly.
//!
//! For each candidate pair the signs of each triangle's corners against the
//! other's plane (`orient3d`) sort the pair into separate, crossing or
//! coplanar. A crossing pair meets along a segment of the line where the
//! planes meet; its ends are among the points where an edge of one triangle
//! passes through the other (an implicit edge–plane point, or a corner when
//! the edge passes exactly through one) and the corners lying on the other
//! triangle. A coplanar pair's overlap is bounded by pieces of both
//! triangles' edges; its corners are corners inside the other triangle and
//! edge–edge crossings (implicit, in the plane's projection). Both triangles
//! of a pair get every point found and the segments that cut them.

use std::cmp::Ordering;

use glam::{DVec2, DVec3};
use smallvec::SmallVec;

use crate::geom::implicit::{ImplicitPoint, compare_points, kept_axes};
use crate::geom::{Sign, orient2d, orient3d};

use super::points::{CachedPoint, PointView, compare_positions};

/// A point found by a pair: an operand vertex (by its global index) or a
/// constructed point.
#[derive(Clone, Debug)]
pub(crate) enum PointRef {
    /// A corner of one of the two triangles.
    Vertex(u32),
    /// A point made by the intersection.
    New(ImplicitPoint),
}

/// The line a cut runs along besides the cut triangle's own plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Carrier {
    /// Where the two triangles' planes meet (a crossing pair).
    PlanesMeet,
    /// Along edge `k` (corner `k` to corner `k + 1`) of the other triangle
    /// (a coplanar pair).
    OtherEdge(u8),
}

/// A segment cutting one triangle of a pair: its ends (indices into the
/// contact's points) and its line.
pub(crate) type Cut = (u8, u8, Carrier);

/// What one pair of triangles contributes.
#[derive(Clone, Debug, Default)]
pub(crate) struct Contact {
    /// Every point of the pair's intersection that is a corner of the
    /// overlap (distinct).
    pub points: SmallVec<[PointRef; 4]>,
    /// Segments (indices into `points`) that cut the first triangle.
    pub first_cuts: SmallVec<[Cut; 3]>,
    /// Segments that cut the second triangle.
    pub second_cuts: SmallVec<[Cut; 3]>,
    /// For a coplanar pair: whether the two normals point the same way.
    pub coplanar_same: Option<bool>,
    /// Every corner found on the other triangle, also those equal to
    /// another point of `points` (a corner of each triangle at one
    /// position): all of them must be merged into one point.
    pub touched: SmallVec<[u32; 4]>,
}

impl Contact {
    /// The global ids of the contact's points: an operand vertex keeps its
    /// own; a new point is appended to `made` and numbered `base` plus its
    /// place there.
    pub(crate) fn point_ids(&self, base: usize, made: &mut Vec<ImplicitPoint>) -> Vec<u32> {
        self.points
            .iter()
            .map(|r| match r {
                PointRef::Vertex(v) => *v,
                PointRef::New(p) => {
                    made.push(p.clone());
                    (base + made.len() - 1) as u32
                }
            })
            .collect()
    }
}

/// A triangle of one operand with the global indices of its corners.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri {
    pub corners: [DVec3; 3],
    pub ids: [u32; 3],
}

impl Tri {
    fn point(&self, i: usize) -> (DVec3, PointRef) {
        (self.corners[i], PointRef::Vertex(self.ids[i]))
    }
}

/// The contact of triangles `a` and `b`, or `None` when they do not meet.
pub(crate) fn contact(a: &Tri, b: &Tri) -> Option<Contact> {
    let sa = a
        .corners
        .map(|p| orient3d(b.corners[0], b.corners[1], b.corners[2], p));
    if separated(sa) {
        return None;
    }
    let sb = b
        .corners
        .map(|p| orient3d(a.corners[0], a.corners[1], a.corners[2], p));
    if separated(sb) {
        return None;
    }
    if sa == [Sign::Zero; 3] {
        return coplanar(a, b);
    }
    let mut found: SmallVec<[(ImplicitPoint, PointRef); 8]> = SmallVec::new();
    edges_through(a, sa, b, &mut found);
    edges_through(b, sb, a, &mut found);
    let touched = vertices_of(found.iter().map(|f| &f.1));
    let points = distinct(found);
    if points.is_empty() {
        return None;
    }
    let mut contact = Contact {
        points: points.iter().map(|(_, r)| r.clone()).collect(),
        touched,
        ..Contact::default()
    };
    if points.len() >= 2 {
        // The points lie on one line; the lexicographic extremes are the
        // segment's ends.
        let last = (points.len() - 1) as u8;
        contact.first_cuts.push((0, last, Carrier::PlanesMeet));
        contact.second_cuts.push((0, last, Carrier::PlanesMeet));
    }
    Some(contact)
}

/// The vertex indices among `refs`.
fn vertices_of<'r>(refs: impl Iterator<Item = &'r PointRef>) -> SmallVec<[u32; 4]> {
    refs.filter_map(|r| match r {
        PointRef::Vertex(i) => Some(*i),
        PointRef::New(_) => None,
    })
    .collect()
}

/// All three signs strictly equal: the triangle is off the plane.
fn separated(s: [Sign; 3]) -> bool {
    s[0] != Sign::Zero && s[0] == s[1] && s[1] == s[2]
}

/// The points where `t`'s edges pass through `other` (corners on
/// `other`'s plane included), `s` being `t`'s corner signs against it.
fn edges_through(
    t: &Tri,
    s: [Sign; 3],
    other: &Tri,
    found: &mut SmallVec<[(ImplicitPoint, PointRef); 8]>,
) {
    let o = &other.corners;
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] == Sign::Zero {
            if inside_closed(other, t.corners[i]) {
                let (p, r) = t.point(i);
                found.push((ImplicitPoint::Explicit(p), r));
            }
            continue;
        }
        if s[j] == Sign::Zero || s[i] == s[j] {
            continue;
        }
        let (p, q) = (t.corners[i], t.corners[j]);
        let sides = [
            orient3d(p, q, o[0], o[1]),
            orient3d(p, q, o[1], o[2]),
            orient3d(p, q, o[2], o[0]),
        ];
        let positive = sides.contains(&Sign::Positive);
        let negative = sides.contains(&Sign::Negative);
        if positive && negative {
            continue;
        }
        let zeros: SmallVec<[usize; 3]> = (0..3).filter(|&k| sides[k] == Sign::Zero).collect();
        if zeros.len() == 2 {
            // Through a corner of `other`: the corner shared by the two
            // edges (edge k runs from corner k to corner k + 1).
            let corner = if zeros[..] == [0, 1] {
                1
            } else if zeros[..] == [1, 2] {
                2
            } else {
                0
            };
            let (p, r) = other.point(corner);
            found.push((ImplicitPoint::Explicit(p), r));
        } else {
            let point = ImplicitPoint::EdgePlane {
                p,
                q,
                plane: other.corners,
            }
            .simplified();
            found.push((point.clone(), PointRef::New(point)));
        }
    }
}

/// The axis whose projection keeps triangle `t` non-degenerate (exactly),
/// and the triangle's orientation in it.
pub(crate) fn projection(t: &[DVec3; 3]) -> (u8, Sign) {
    let n = (t[1] - t[0]).cross(t[2] - t[0]).abs();
    let mut axes = [0u8, 1, 2];
    axes.sort_by(|&x, &y| n[y as usize].total_cmp(&n[x as usize]));
    for axis in axes {
        let s = orient2d_axis(t[0], t[1], t[2], axis);
        if s != Sign::Zero {
            return (axis, s);
        }
    }
    (axes[0], Sign::Zero)
}

fn flat(p: DVec3, axis: u8) -> DVec2 {
    let (u, v) = kept_axes(axis);
    DVec2::new(p[u], p[v])
}

fn orient2d_axis(a: DVec3, b: DVec3, c: DVec3, axis: u8) -> Sign {
    orient2d(flat(a, axis), flat(b, axis), flat(c, axis))
}

/// Whether `p`, which lies in `t`'s plane, is in the closed triangle.
fn inside_closed(t: &Tri, p: DVec3) -> bool {
    let (axis, facing) = projection(&t.corners);
    let c = &t.corners;
    (0..3).all(|k| {
        let s = orient2d_axis(c[k], c[(k + 1) % 3], p, axis);
        s == Sign::Zero || s == facing
    })
}

/// The points sorted exactly and without repeats (each point's filter
/// computed once, not at every comparison).
fn distinct(
    found: SmallVec<[(ImplicitPoint, PointRef); 8]>,
) -> SmallVec<[(ImplicitPoint, PointRef); 8]> {
    let mut cached: SmallVec<[(CachedPoint, PointRef); 8]> = found
        .into_iter()
        .map(|(point, r)| (CachedPoint::new(point), r))
        .collect();
    let order = |x: &CachedPoint, y: &CachedPoint| {
        compare_positions(&PointView::Made(x), &PointView::Made(y))
    };
    cached.sort_by(|x, y| order(&x.0, &y.0));
    cached.dedup_by(|x, y| order(&x.0, &y.0) == Ordering::Equal);
    cached
        .into_iter()
        .map(|(cached, r)| (cached.point, r))
        .collect()
}

/// The contact of two triangles in one plane.
fn coplanar(a: &Tri, b: &Tri) -> Option<Contact> {
    let (axis, a_facing) = projection(&a.corners);
    let b_facing = orient2d_axis(b.corners[0], b.corners[1], b.corners[2], axis);
    // Points by the edge they lie on: edge k of a is 0..3, of b 3..6.
    let mut found: SmallVec<[(ImplicitPoint, PointRef, u8); 12]> = SmallVec::new();
    let corners_in = |t: &Tri, other: &Tri, base: u8, found: &mut SmallVec<_>| {
        let other_base = 3 - base;
        for i in 0..3 {
            if inside_closed(other, t.corners[i]) {
                let (p, r) = t.point(i);
                // A corner lies on both of its edges, and on every edge of
                // the other triangle whose line passes through it.
                let point = ImplicitPoint::Explicit(p);
                found.push((point.clone(), r.clone(), base + i as u8));
                found.push((point.clone(), r.clone(), base + ((i + 2) % 3) as u8));
                for k in 0..3 {
                    let o = &other.corners;
                    if orient2d_axis(o[k], o[(k + 1) % 3], p, axis) == Sign::Zero {
                        found.push((point.clone(), r.clone(), other_base + k as u8));
                    }
                }
            }
        }
    };
    corners_in(a, b, 0, &mut found);
    corners_in(b, a, 3, &mut found);
    for i in 0..3 {
        let (p, q) = (a.corners[i], a.corners[(i + 1) % 3]);
        for k in 0..3 {
            let (r, s) = (b.corners[k], b.corners[(k + 1) % 3]);
            let (pr, qr) = (orient2d_axis(r, s, p, axis), orient2d_axis(r, s, q, axis));
            let (rp, sp) = (orient2d_axis(p, q, r, axis), orient2d_axis(p, q, s, axis));
            let proper = |x: Sign, y: Sign| x != Sign::Zero && y != Sign::Zero && x != y;
            if proper(pr, qr) && proper(rp, sp) {
                let point = ImplicitPoint::EdgeEdge {
                    p,
                    q,
                    r,
                    s,
                    drop_axis: axis,
                }
                .simplified();
                found.push((point.clone(), PointRef::New(point.clone()), i as u8));
                found.push((point.clone(), PointRef::New(point), 3 + k as u8));
            }
        }
    }
    if found.is_empty() {
        return None;
    }
    let touched = vertices_of(found.iter().map(|f| &f.1));
    let mut all: SmallVec<[(ImplicitPoint, PointRef); 8]> = found
        .iter()
        .map(|(p, r, _)| (p.clone(), r.clone()))
        .collect();
    all = distinct(all);
    let index_of = |p: &ImplicitPoint| -> u8 {
        all.iter()
            .position(|(q, _)| compare_points(p, q) == Ordering::Equal)
            .unwrap_or(0) as u8
    };
    let mut contact = Contact {
        points: all.iter().map(|(_, r)| r.clone()).collect(),
        coplanar_same: Some(a_facing == b_facing),
        touched,
        ..Contact::default()
    };
    // Each edge's points in order along it; the extremes bound its piece
    // inside the other triangle (a convex set meets a line in a segment).
    for edge in 0..6u8 {
        let mut on: SmallVec<[u8; 6]> = found
            .iter()
            .filter(|f| f.2 == edge)
            .map(|f| index_of(&f.0))
            .collect();
        on.sort_unstable();
        on.dedup();
        if on.len() >= 2 {
            let (from, to) = (on[0], on[on.len() - 1]);
            // Edges of b cut a; edges of a cut b.
            if edge >= 3 {
                let along = Carrier::OtherEdge(edge - 3);
                contact.first_cuts.push((from, to, along));
            } else {
                let along = Carrier::OtherEdge(edge);
                contact.second_cuts.push((from, to, along));
            }
        }
    }
    Some(contact)
}
