//! Pairing the triangles around an edge that several sheets touch along.
//!
//! Two sheets touching along an edge — the union of two cubes that share
//! an edge — put four triangles on it, two running it each way. Each sheet
//! encloses its own wedge of space around the edge; the builder gives each
//! sheet an edge of its own by pairing every triangle with the neighbour
//! that closes its wedge.
//!
//! Seen along the axis `a → b`, a triangle `(a, b, c)` (running the edge
//! forward) has its outward normal `(b − a) × (c − a)` a quarter-turn
//! counterclockwise (right-handed about the axis) from `c`, so its solid
//! lies on its clockwise side; a triangle running `b → a` has its solid on
//! its counterclockwise side. Sorted counterclockwise, the wedge after a
//! backward triangle is solid, and it must close at the next triangle,
//! which must run forward: the uses alternate, and each backward triangle
//! is paired with the next one. Angles compared exactly
//! ([`sorted_around`]): no two triangles may lie at one angle.

use glam::DVec3;

use crate::geom::around_axis::sorted_around;

/// One use of the edge `a–b`: a triangle's half-edge, whether it runs
/// `a → b`, and the triangle's third corner.
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeUse {
    pub half_edge: usize,
    pub forward: bool,
    pub third: DVec3,
}

/// The twins of the uses of the edge from `a` to `b` (as pairs of
/// half-edges, backward first), or `None` when they cannot be paired: the
/// uses do not alternate in direction around the edge, two lie at one
/// angle, or a third corner is on the edge's line.
pub(super) fn pair_around_edge(
    a: DVec3,
    b: DVec3,
    uses: &[EdgeUse],
) -> Option<Vec<(usize, usize)>> {
    let forward = uses.iter().filter(|u| u.forward).count();
    if uses.len() < 2 || 2 * forward != uses.len() {
        return None;
    }
    let thirds: Vec<DVec3> = uses.iter().map(|u| u.third).collect();
    let sorted: Vec<&EdgeUse> = sorted_around(a, b, &thirds)?
        .into_iter()
        .map(|i| &uses[i])
        .collect();
    let n = sorted.len();
    let mut pairs = Vec::with_capacity(n / 2);
    for (k, &u) in sorted.iter().enumerate() {
        if u.forward {
            continue;
        }
        let next = sorted[(k + 1) % n];
        if !next.forward {
            return None;
        }
        pairs.push((u.half_edge, next.half_edge));
    }
    Some(pairs)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn use_of(half_edge: usize, forward: bool, third: [f64; 3]) -> EdgeUse {
        EdgeUse {
            half_edge,
            forward,
            third: DVec3::from(third),
        }
    }

    /// Two unit cubes sharing the edge x = y = 0 along z: one in the
    /// quadrant x, y ≥ 0, the other in x, y ≤ 0. Each cube's two faces on
    /// the edge are paired with each other.
    #[test]
    fn two_cubes_sharing_an_edge_pair_within_each_cube() {
        let (a, b) = (DVec3::ZERO, DVec3::Z);
        // First cube: its face y = 0 (third corner at x = 1) and its face
        // x = 0 (third corner at y = 1); outward normals −y and −x.
        // (a, b, (1,0,0)): normal z × x = +y — so the face y = 0 with outward
        // −y runs the edge backward, and the face x = 0 forward.
        let uses = [
            use_of(0, false, [1., 0., 0.]),
            use_of(1, true, [0., 1., 0.]),
            use_of(2, false, [-1., 0., 0.]),
            use_of(3, true, [0., -1., 0.]),
        ];
        let mut pairs = pair_around_edge(a, b, &uses).unwrap();
        pairs.sort();
        assert_eq!(pairs, vec![(0, 1), (2, 3)]);
    }

    #[test]
    fn uses_that_do_not_alternate_or_tie_are_refused() {
        let (a, b) = (DVec3::ZERO, DVec3::Z);
        let crossing = [
            use_of(0, false, [1., 0., 0.]),
            use_of(1, false, [0., 1., 0.]),
            use_of(2, true, [-1., 0., 0.]),
            use_of(3, true, [0., -1., 0.]),
        ];
        assert!(pair_around_edge(a, b, &crossing).is_none());
        let folded = [
            use_of(0, false, [1., 0., 0.]),
            use_of(1, true, [2., 0., 0.]),
            use_of(2, false, [-1., 0., 0.]),
            use_of(3, true, [0., -1., 0.]),
        ];
        assert!(pair_around_edge(a, b, &folded).is_none());
        let unbalanced = [
            use_of(0, false, [1., 0., 0.]),
            use_of(1, false, [0., 1., 0.]),
            use_of(2, true, [-1., 0., 0.]),
        ];
        assert!(pair_around_edge(a, b, &unbalanced).is_none());
    }
}
