//! The unit cube of a grid cell: corners, edges, faces and the 48
//! symmetries (rotations and reflections) that act on them.
//!
//! Corner `c` sits at `(c & 1, (c >> 1) & 1, (c >> 2) & 1)`: bit 0 is x, bit
//! 1 is y, bit 2 is z. Edges are numbered x-edges 0–3, y-edges 4–7, z-edges
//! 8–11, each from its lower corner to its upper one.

/// Each edge's two corners, lower first.
pub(crate) const EDGES: [[u8; 2]; 12] = [
    [0, 1],
    [2, 3],
    [4, 5],
    [6, 7],
    [0, 2],
    [1, 3],
    [4, 6],
    [5, 7],
    [0, 4],
    [1, 5],
    [2, 6],
    [3, 7],
];

/// A corner's coordinates, each 0 or 1.
pub(crate) fn corner_coords(c: u8) -> [i32; 3] {
    [
        i32::from(c & 1),
        i32::from((c >> 1) & 1),
        i32::from((c >> 2) & 1),
    ]
}

/// The axis an edge runs along (0 = x, 1 = y, 2 = z).
pub(crate) fn edge_axis(e: u8) -> usize {
    usize::from(e / 4)
}

/// The edge joining two corners, if they are adjacent.
pub(crate) fn edge_between(a: u8, b: u8) -> Option<u8> {
    let (lo, hi) = (a.min(b), a.max(b));
    EDGES
        .iter()
        .position(|&[x, y]| x == lo && y == hi)
        .map(|e| e as u8)
}

/// A face of the cube: the four corners with coordinate `axis` equal to
/// `side`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct CubeFace {
    /// 0 = x, 1 = y, 2 = z.
    pub(crate) axis: usize,
    /// 0 or 1.
    pub(crate) side: u8,
}

impl CubeFace {
    /// The six faces.
    pub(crate) fn all() -> impl Iterator<Item = CubeFace> {
        (0..3).flat_map(|axis| (0..2).map(move |side| CubeFace { axis, side }))
    }

    /// Whether corner `c` lies on this face.
    #[cfg(test)]
    pub(crate) fn holds_corner(self, c: u8) -> bool {
        (c >> self.axis) & 1 == self.side
    }

    /// Whether edge `e` lies on this face.
    #[cfg(test)]
    pub(crate) fn holds_edge(self, e: u8) -> bool {
        let [a, b] = EDGES[usize::from(e)];
        self.holds_corner(a) && self.holds_corner(b)
    }

    /// The face's corners in cyclic order around it.
    pub(crate) fn cycle(self) -> [u8; 4] {
        let (u, v) = ((self.axis + 1) % 3, (self.axis + 2) % 3);
        let base = self.side << self.axis;
        let (du, dv) = (1u8 << u, 1u8 << v);
        [base, base | du, base | du | dv, base | dv]
    }
}

/// Whether a face of a sign configuration is ambiguous: its four corners
/// alternate inside, outside, inside, outside around it.
pub(crate) fn face_is_ambiguous(config: u8, face: CubeFace) -> bool {
    let inside = face.cycle().map(|c| config >> c & 1 == 1);
    inside[0] == inside[2] && inside[1] == inside[3] && inside[0] != inside[1]
}

/// Whether any face of a configuration is ambiguous.
pub(crate) fn has_ambiguous_face(config: u8) -> bool {
    CubeFace::all().any(|f| face_is_ambiguous(config, f))
}

/// A symmetry of the cube: new coordinate `i` is old coordinate `perm[i]`,
/// mirrored when `flip[i]`. The 6 permutations × 8 flips are the 48
/// rotations and reflections.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Symmetry {
    perm: [usize; 3],
    flip: [bool; 3],
}

impl Symmetry {
    /// All 48 symmetries; the identity first.
    pub(crate) fn all() -> impl Iterator<Item = Symmetry> {
        const PERMS: [[usize; 3]; 6] = [
            [0, 1, 2],
            [1, 2, 0],
            [2, 0, 1],
            [0, 2, 1],
            [2, 1, 0],
            [1, 0, 2],
        ];
        PERMS.into_iter().flat_map(|perm| {
            (0..8u8).map(move |f| Symmetry {
                perm,
                flip: [f & 1 != 0, f & 2 != 0, f & 4 != 0],
            })
        })
    }

    /// The image of a corner.
    pub(crate) fn corner(self, c: u8) -> u8 {
        let old = corner_coords(c);
        (0..3).fold(0u8, |acc, i| {
            let bit = (old[self.perm[i]] != 0) != self.flip[i];
            acc | (u8::from(bit) << i)
        })
    }

    /// The image of an edge.
    pub(crate) fn edge(self, e: u8) -> u8 {
        let [a, b] = EDGES[usize::from(e)];
        // Adjacent corners map to adjacent corners.
        edge_between(self.corner(a), self.corner(b)).unwrap_or(e)
    }

    /// The image of a sign configuration (bit `c` set = corner `c` inside).
    pub(crate) fn config(self, config: u8) -> u8 {
        (0..8u8)
            .filter(|&c| config >> c & 1 == 1)
            .fold(0, |acc, c| acc | 1 << self.corner(c))
    }

    /// Whether the symmetry is a reflection (determinant −1), which turns
    /// counter-clockwise triangles clockwise.
    pub(crate) fn reverses_orientation(self) -> bool {
        let odd_perm = matches!(self.perm, [0, 2, 1] | [2, 1, 0] | [1, 0, 2]);
        let flips = self.flip.iter().filter(|&&f| f).count();
        odd_perm != (flips % 2 == 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_48_symmetries_are_distinct_and_keep_edges_and_faces() {
        let all: Vec<Symmetry> = Symmetry::all().collect();
        assert_eq!(all.len(), 48);
        let images: std::collections::HashSet<[u8; 8]> = all
            .iter()
            .map(|s| core::array::from_fn(|c| s.corner(c as u8)))
            .collect();
        assert_eq!(images.len(), 48);
        for s in &all {
            for &[a, b] in &EDGES {
                assert!(edge_between(s.corner(a), s.corner(b)).is_some());
            }
        }
        assert_eq!(all.iter().filter(|s| s.reverses_orientation()).count(), 24);
    }

    #[test]
    fn faces_hold_four_edges_and_cycle_through_adjacent_corners() {
        for f in CubeFace::all() {
            assert_eq!((0..12).filter(|&e| f.holds_edge(e)).count(), 4);
            let c = f.cycle();
            for i in 0..4 {
                assert!(edge_between(c[i], c[(i + 1) % 4]).is_some());
                assert!(f.holds_corner(c[i]));
            }
        }
        // Corners 0 and 3 are diagonal on the face z = 0.
        assert!(face_is_ambiguous(0b1001, CubeFace { axis: 2, side: 0 }));
        assert!(!has_ambiguous_face(0b1000_0001));
    }
}
