//! The base cases of marching cubes (Lorensen & Cline 1987): one
//! representative sign configuration per class of the cube's 48 symmetries,
//! with the surface's boundary loops.
//!
//! An edge is written as its two corners (corner `c` at
//! `(c & 1, c >> 1 & 1, c >> 2 & 1)`). Each loop lists, in order, the edges
//! the surface crosses; consecutive edges share a cube face, and the segment
//! between them is where the surface meets that face. The first edge of a
//! loop is the apex of its fan triangulation, chosen so that no diagonal of
//! the fan lies in a cube face. Orientation is not written here: the table
//! generator orients each loop so its normal points at the outside corners.
//!
//! **The ambiguity rule.** On a face whose corners alternate inside,
//! outside, inside, outside, the two inside corners are *separated*: each
//! is cut off by its own segment. The rule reads only the face's four signs,
//! so the two cells sharing the face apply it identically and their
//! segments on it agree. Cases 0–13 (at most four inside corners) follow it
//! as drawn by Lorensen and Cline. Complementing a configuration swaps
//! inside and outside, so on an ambiguous face the complement of a separated
//! pair is a *joined* pair: cases 3, 6 and 7 therefore cannot be
//! complemented and have their complements 3c, 6c and 7c below, where the
//! outside corners are joined across the face. The other cases have no
//! ambiguous face and are complemented by reversing their loops.

/// A base case: the inside corners of its representative configuration and
/// the loops of its surface.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BaseCase {
    /// Its name: Lorensen and Cline's number, `c` for a complement.
    pub(crate) name: &'static str,
    /// The corners with `F ≥ ½`.
    pub(crate) inside: &'static [u8],
    /// The surface's loops, each a cycle of crossed edges (corner pairs).
    pub(crate) loops: &'static [&'static [[u8; 2]]],
}

/// The base cases: 0–13 and the complements 3c, 6c, 7c.
pub(crate) const BASE_CASES: [BaseCase; 17] = [
    BaseCase {
        name: "0",
        inside: &[],
        loops: &[],
    },
    // One corner.
    BaseCase {
        name: "1",
        inside: &[0],
        loops: &[&[[0, 1], [0, 2], [0, 4]]],
    },
    // Two corners on an edge.
    BaseCase {
        name: "2",
        inside: &[0, 1],
        loops: &[&[[0, 2], [1, 3], [1, 5], [0, 4]]],
    },
    // Two corners diagonal on a face (ambiguous face z = 0: separated).
    BaseCase {
        name: "3",
        inside: &[0, 3],
        loops: &[&[[0, 1], [0, 2], [0, 4]], &[[1, 3], [2, 3], [3, 7]]],
    },
    // Two corners diagonal through the cube.
    BaseCase {
        name: "4",
        inside: &[0, 7],
        loops: &[&[[0, 1], [0, 2], [0, 4]], &[[3, 7], [5, 7], [6, 7]]],
    },
    // Three corners on a face.
    BaseCase {
        name: "5",
        inside: &[0, 1, 2],
        loops: &[&[[0, 4], [1, 5], [1, 3], [2, 3], [2, 6]]],
    },
    // An edge and a corner diagonal to it on a face (ambiguous face x = 0).
    BaseCase {
        name: "6",
        inside: &[0, 1, 6],
        loops: &[&[[0, 2], [1, 3], [1, 5], [0, 4]], &[[2, 6], [4, 6], [6, 7]]],
    },
    // Three corners pairwise diagonal on faces.
    BaseCase {
        name: "7",
        inside: &[1, 2, 4],
        loops: &[
            &[[0, 1], [1, 3], [1, 5]],
            &[[0, 2], [2, 3], [2, 6]],
            &[[0, 4], [4, 5], [4, 6]],
        ],
    },
    // Four corners on a face.
    BaseCase {
        name: "8",
        inside: &[0, 1, 2, 3],
        loops: &[&[[0, 4], [1, 5], [3, 7], [2, 6]]],
    },
    // A corner and its three neighbours.
    BaseCase {
        name: "9",
        inside: &[0, 1, 2, 4],
        loops: &[&[[1, 3], [2, 3], [2, 6], [4, 6], [4, 5], [1, 5]]],
    },
    // Two opposite edges (ambiguous faces x = 0 and x = 1).
    BaseCase {
        name: "10",
        inside: &[0, 1, 6, 7],
        loops: &[
            &[[0, 2], [1, 3], [1, 5], [0, 4]],
            &[[2, 6], [3, 7], [5, 7], [4, 6]],
        ],
    },
    // A path of three edges along the three axes (cases 11 and 14 of
    // Lorensen and Cline are mirror images: one class here).
    BaseCase {
        name: "11",
        inside: &[0, 1, 3, 7],
        loops: &[&[[0, 2], [2, 3], [6, 7], [5, 7], [1, 5], [0, 4]]],
    },
    // Three corners on a face and the corner diagonally opposite their
    // middle one (ambiguous faces x = 1 and y = 1).
    BaseCase {
        name: "12",
        inside: &[0, 1, 2, 7],
        loops: &[
            &[[0, 4], [1, 5], [1, 3], [2, 3], [2, 6]],
            &[[3, 7], [5, 7], [6, 7]],
        ],
    },
    // Four corners, no two adjacent (every face ambiguous).
    BaseCase {
        name: "13",
        inside: &[0, 3, 5, 6],
        loops: &[
            &[[0, 1], [0, 2], [0, 4]],
            &[[1, 3], [2, 3], [3, 7]],
            &[[1, 5], [4, 5], [5, 7]],
            &[[2, 6], [4, 6], [6, 7]],
        ],
    },
    // The complement of 3: outside corners 0 and 3 joined across z = 0.
    BaseCase {
        name: "3c",
        inside: &[1, 2, 4, 5, 6, 7],
        loops: &[&[[3, 7], [2, 3], [0, 2], [0, 4], [0, 1], [1, 3]]],
    },
    // The complement of 6: outside corners 0 and 6 joined across x = 0.
    BaseCase {
        name: "6c",
        inside: &[2, 3, 4, 5, 7],
        loops: &[&[[6, 7], [2, 6], [0, 2], [1, 3], [1, 5], [0, 4], [4, 6]]],
    },
    // The complement of 7: the outside corners joined across three faces;
    // inside corner 0 is cut off on its own.
    BaseCase {
        name: "7c",
        inside: &[0, 3, 5, 6, 7],
        loops: &[
            &[[0, 1], [0, 2], [0, 4]],
            &[[1, 3], [1, 5], [4, 5], [4, 6], [2, 6], [2, 3]],
        ],
    },
];
