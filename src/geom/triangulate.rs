//! Exact constrained Delaunay triangulation of a simple planar polygon with
//! holes.
//!
//! [`triangulate`] takes the outer loop and the holes as 2-D points and
//! returns triangles as indices into the concatenation
//! `outer ++ holes[0] ++ holes[1] ++ …`. Loops may be wound either way;
//! every triangle comes out counter-clockwise (positive [`orient2d`]). The
//! steps:
//!
//! 1. the input is checked (finite, at least three vertices per loop, each
//!    loop simple and bounding an area, every hole strictly inside the outer
//!    loop, holes apart), with a typed error naming the offending loop,
//!    vertices or edges;
//! 2. each hole is joined to the outer loop by a bridge to a visible vertex
//!    (holes taken right to left, from their rightmost vertex, after
//!    Eberly, "Triangulation by Ear Clipping", 2002), which leaves one
//!    weakly simple polygon;
//! 3. ears are clipped from that polygon (Meisters' two-ears theorem, 1975);
//! 4. edges that are not on a loop are flipped until each is locally
//!    Delaunay (Lawson, 1977) — `d` not strictly inside the circle of the
//!    triangle on the other side, by the exact [`incircle`] — which makes
//!    the result the constrained Delaunay triangulation of the loops (Chew,
//!    "Constrained Delaunay triangulations", 1989): of all triangulations
//!    with those edges it maximises the smallest angle, so it has no
//!    avoidable sliver.
//!
//! Every decision is the sign of an exact predicate ([`orient2d`],
//! [`incircle`]); no triangle is ever flipped or of zero area, and a polygon
//! of `n` vertices with `h` holes gives exactly `n + 2h − 2` triangles.
//! The checks and the ear search cost `O(n²)` in the worst case: meant for
//! faces, not for meshing large domains.
//!
//! [`triangulate_3d`] does the same for the loops of a planar face in space,
//! through the face's axis [`Projection`].

use std::fmt;

use glam::{DVec2, DVec3};
use thiserror::Error;

use super::polygon::{
    PolygonLocation, Projection, find_self_intersection, locate_point_in_polygon, segments_touch,
};
use super::{Sign, newell_vector_area, orient2d};

#[cfg(doc)]
use super::incircle;

mod delaunay;
mod ears;

/// A loop of a polygon with holes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ring {
    /// The outer loop.
    Outer,
    /// The hole of this index in the `holes` argument.
    Hole(usize),
}

impl fmt::Display for Ring {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Ring::Outer => write!(f, "the outer loop"),
            Ring::Hole(k) => write!(f, "hole {k}"),
        }
    }
}

/// Why a polygon cannot be triangulated. Vertex indices count in the
/// concatenation `outer ++ holes[0] ++ holes[1] ++ …`; an edge is named by
/// the index of its first vertex (it runs to the next vertex of its loop).
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum TriangulateError {
    /// A loop with fewer than three vertices.
    #[error("{ring} has {count} vertices; a loop needs at least 3")]
    TooFewVertices {
        /// The loop.
        ring: Ring,
        /// How many vertices it has.
        count: usize,
    },
    /// A vertex with a NaN or infinite coordinate.
    #[error("vertex {vertex} of {ring} has a non-finite coordinate")]
    NonFinite {
        /// The loop.
        ring: Ring,
        /// The vertex.
        vertex: usize,
    },
    /// A loop whose vertices all lie on one line (exactly): it bounds no
    /// area.
    #[error("{ring} has all its vertices on one line: it bounds no area")]
    Collinear {
        /// The loop.
        ring: Ring,
    },
    /// Two edges of one loop touch or cross, or two consecutive edges fold
    /// back over each other (a repeated vertex is such a case).
    #[error("{ring} is not simple: its edges from vertices {first} and {second} meet")]
    SelfIntersecting {
        /// The loop.
        ring: Ring,
        /// The first of the two edges.
        first: usize,
        /// The second of the two edges.
        second: usize,
    },
    /// A hole that lies outside the outer loop.
    #[error("hole {hole} lies outside the outer loop")]
    HoleOutside {
        /// The hole.
        hole: usize,
    },
    /// A hole that touches or crosses the outer loop.
    #[error(
        "hole {hole} meets the outer loop: its edge from vertex {hole_edge} touches the outer edge from vertex {outer_edge}"
    )]
    HoleCrossesOuter {
        /// The hole.
        hole: usize,
        /// An edge of the hole that meets the outer loop.
        hole_edge: usize,
        /// The outer edge it meets.
        outer_edge: usize,
    },
    /// Two holes that touch, cross, or lie one inside the other.
    #[error("holes {first} and {second} overlap or touch")]
    HolesOverlap {
        /// The hole of lower index.
        first: usize,
        /// The other hole.
        second: usize,
    },
    /// No bridge or no ear was found. This cannot happen for input that
    /// passed the checks above; it is reported rather than panicking.
    #[error("{ring} could not be joined or clipped: an internal error")]
    Internal {
        /// The loop being processed.
        ring: Ring,
    },
}

/// The constrained Delaunay triangulation of the polygon bounded by
/// `outer` with the holes `holes`, exactly; see the module documentation.
///
/// Returns triangles `[i, j, k]` of indices into the concatenation
/// `outer ++ holes[0] ++ holes[1] ++ …`, each counter-clockwise (exact
/// [`orient2d`] positive), `n + 2h − 2` of them for `n` vertices in all and
/// `h` holes. Loops may be wound either way. Every loop edge is an edge of
/// some triangle; every other edge is locally Delaunay.
///
/// # Errors
///
/// [`TriangulateError`]: a loop with fewer than three vertices, a
/// non-finite coordinate, a loop with all vertices on one line, a loop that
/// is not simple, a hole outside, touching or crossing the outer loop, two
/// holes touching, crossing or nested.
pub fn triangulate(
    outer: &[DVec2],
    holes: &[&[DVec2]],
) -> Result<Vec<[usize; 3]>, TriangulateError> {
    let rings: Vec<&[DVec2]> = std::iter::once(outer)
        .chain(holes.iter().copied())
        .collect();
    let mut offsets = Vec::with_capacity(rings.len());
    let mut total = 0;
    for ring in &rings {
        offsets.push(total);
        total += ring.len();
    }
    let ring_of = |r: usize| {
        if r == 0 {
            Ring::Outer
        } else {
            Ring::Hole(r - 1)
        }
    };
    let mut counter_clockwise = Vec::with_capacity(rings.len());
    for (r, ring) in rings.iter().enumerate() {
        counter_clockwise.push(check_loop(ring, ring_of(r), offsets[r])?);
    }
    check_holes(&rings, &offsets)?;
    let points: Vec<DVec2> = rings.iter().flat_map(|r| r.iter().copied()).collect();
    // Loops as index lists: the outer one counter-clockwise, holes
    // clockwise, so that the polygon's inside is on the left of every edge.
    let loops: Vec<Vec<usize>> = rings
        .iter()
        .enumerate()
        .map(|(r, ring)| {
            let mut l: Vec<usize> = (offsets[r]..offsets[r] + ring.len()).collect();
            if counter_clockwise[r] != (r == 0) {
                l.reverse();
            }
            l
        })
        .collect();
    let mut triangles = ears::triangulate_loops(&points, &loops)?;
    delaunay::make_delaunay(&points, &loops, &mut triangles);
    Ok(triangles)
}

/// [`triangulate`] for the loops of a planar face in space: the points are
/// projected onto the axis plane closest to the outer loop's plane
/// ([`Projection::along`] its Newell normal), which is exact for exactly
/// planar loops; of loops that are not planar, the projection is
/// triangulated. Triangles are wound like the outer loop (counter-clockwise
/// around its Newell normal) and index the concatenation as in
/// [`triangulate`].
///
/// # Errors
///
/// Those of [`triangulate`] for the projected loops (a face seen edge-on
/// in every axis plane is [`TriangulateError::Collinear`]); a non-finite
/// coordinate in any of the three axes is [`TriangulateError::NonFinite`].
pub fn triangulate_3d(
    outer: &[DVec3],
    holes: &[&[DVec3]],
) -> Result<Vec<[usize; 3]>, TriangulateError> {
    let mut offset = 0;
    for (r, ring) in std::iter::once(outer)
        .chain(holes.iter().copied())
        .enumerate()
    {
        if let Some(k) = ring.iter().position(|p| !p.is_finite()) {
            let ring = if r == 0 {
                Ring::Outer
            } else {
                Ring::Hole(r - 1)
            };
            return Err(TriangulateError::NonFinite {
                ring,
                vertex: offset + k,
            });
        }
        offset += ring.len();
    }
    let origin = outer.first().copied().unwrap_or(DVec3::ZERO);
    let projection = Projection::along(newell_vector_area(outer, origin));
    let flat = |ring: &[DVec3]| {
        ring.iter()
            .map(|&p| projection.apply(p))
            .collect::<Vec<_>>()
    };
    let outer2 = flat(outer);
    let holes2: Vec<Vec<DVec2>> = holes.iter().map(|h| flat(h)).collect();
    let hole_refs: Vec<&[DVec2]> = holes2.iter().map(Vec::as_slice).collect();
    let mut triangles = triangulate(&outer2, &hole_refs)?;
    if projection.flipped {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    Ok(triangles)
}

/// Checks one loop; returns whether it winds counter-clockwise.
fn check_loop(ring: &[DVec2], which: Ring, offset: usize) -> Result<bool, TriangulateError> {
    if ring.len() < 3 {
        return Err(TriangulateError::TooFewVertices {
            ring: which,
            count: ring.len(),
        });
    }
    if let Some(k) = ring.iter().position(|p| !p.is_finite()) {
        return Err(TriangulateError::NonFinite {
            ring: which,
            vertex: offset + k,
        });
    }
    let first = ring[0];
    let collinear = match ring.iter().find(|&&p| p != first) {
        None => true,
        Some(&other) => ring
            .iter()
            .all(|&p| orient2d(first, other, p) == Sign::Zero),
    };
    if collinear {
        return Err(TriangulateError::Collinear { ring: which });
    }
    if let Some((i, j)) = find_self_intersection(ring) {
        return Err(TriangulateError::SelfIntersecting {
            ring: which,
            first: offset + i,
            second: offset + j,
        });
    }
    // The lexicographically least vertex is convex; a simple loop does not
    // fold there, so the turn is not zero.
    let n = ring.len();
    let least = (0..n)
        .min_by(|&i, &j| {
            (ring[i].x, ring[i].y)
                .partial_cmp(&(ring[j].x, ring[j].y))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .unwrap_or(0);
    match orient2d(
        ring[(least + n - 1) % n],
        ring[least],
        ring[(least + 1) % n],
    ) {
        Sign::Positive => Ok(true),
        Sign::Negative => Ok(false),
        Sign::Zero => Err(TriangulateError::Collinear { ring: which }),
    }
}

/// Checks that every hole lies strictly inside the outer loop and that the
/// holes are pairwise apart (no common point, none inside another).
fn check_holes(rings: &[&[DVec2]], offsets: &[usize]) -> Result<(), TriangulateError> {
    let first_touch = |a: usize, b: usize| {
        let (ra, rb) = (rings[a], rings[b]);
        let edge = |r: &[DVec2], i: usize| (r[i], r[(i + 1) % r.len()]);
        (0..ra.len()).find_map(|i| {
            let (p, q) = edge(ra, i);
            (0..rb.len())
                .find(|&j| {
                    let (u, w) = edge(rb, j);
                    segments_touch(p, q, u, w)
                })
                .map(|j| (offsets[a] + i, offsets[b] + j))
        })
    };
    for a in 1..rings.len() {
        if let Some((hole_edge, outer_edge)) = first_touch(a, 0) {
            return Err(TriangulateError::HoleCrossesOuter {
                hole: a - 1,
                hole_edge,
                outer_edge,
            });
        }
        if locate_point_in_polygon(rings[0], rings[a][0]) != PolygonLocation::Inside {
            return Err(TriangulateError::HoleOutside { hole: a - 1 });
        }
    }
    for a in 1..rings.len() {
        for b in a + 1..rings.len() {
            let nested = || {
                locate_point_in_polygon(rings[a], rings[b][0]) != PolygonLocation::Outside
                    || locate_point_in_polygon(rings[b], rings[a][0]) != PolygonLocation::Outside
            };
            if first_touch(a, b).is_some() || nested() {
                return Err(TriangulateError::HolesOverlap {
                    first: a - 1,
                    second: b - 1,
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests;
