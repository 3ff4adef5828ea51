//! The types of the shared bounding-volume hierarchy: the binary nodes the
//! build makes, the eight-wide nodes the walks read, the frame their `f32`
//! boxes are stored in, and the item range of a leaf. Every algorithm over
//! the tree (build, collapse, walks) is in a file of its own that imports
//! these.

use glam::DVec3;

use crate::geom::Aabb;
use crate::spatial::rounding::{f32_down, f32_up, f64_above, f64_below};

/// A node of the binary BVH (before collapsing to [`Node8`]) with
/// conservatively rounded `f32` bounds in the tree's [`BoxFrame`] (32 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Node {
    pub min: [f32; 3],
    pub max: [f32; 3],
    /// Leaf: first triangle; inner node: index of the second child (the
    /// first child follows the node).
    pub first: u32,
    /// Leaf: number of triangles (> 0); inner node: 0.
    pub count: u32,
}

/// Slots of a [`Node8`].
pub(crate) const WIDTH: usize = 8;

/// The bit of [`Node8::child`] that marks a leaf slot (the rest is the index
/// of its leaf: see [`Bvh::leaf`](super::Bvh::leaf)).
pub(crate) const LEAF: u32 = 1 << 31;

/// A BVH node as traversed: the boxes of up to eight children in four cache
/// lines, so that deciding where to descend touches only the parent. Made by
/// collapsing the binary SAH tree: the tree is a third as deep, so a ray
/// waits for a third as many dependent node loads, and opens fewer nodes
/// than with four slots. The eight slab tests run side by side (see
/// `open`). Boxes are in the tree's [`BoxFrame`].
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct Node8 {
    /// The children's boxes by bound then axis then child: `bounds[a]` the
    /// lower bounds along axis `a` (rounded down), `bounds[3 + a]` the upper
    /// ones (rounded up), so that all children are tested in one pass. An
    /// empty slot has lower `+∞` and upper `−∞` (never entered).
    pub bounds: [[f32; WIDTH]; 6],
    /// Per child: [`LEAF`] plus the index of a leaf, or the
    /// index of an inner node; `u32::MAX` for an empty slot.
    pub child: [u32; WIDTH],
    /// Per octant of ray directions (bit `a` set when the direction runs
    /// down axis `a`), the slots in the order the AVX-512 and AVX2 openers
    /// push them: nibble `k` (bits `4k .. 4k + 4`) holds the `k`-th slot in
    /// its low three bits, farthest first along the octant's diagonal (by
    /// the projection of the boxes' centres), and bit 3 set for an empty
    /// slot (never pushed, wherever it stands).
    ///
    /// # Invariants
    ///
    /// The low three bits of each entry's nibbles are a permutation of the
    /// slots, whatever the boxes (infinite or NaN centres included): a slot
    /// missing from the order would never be visited.
    pub order: [u32; WIDTH],
}

impl Node8 {
    pub(crate) const EMPTY: Node8 = Node8 {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [u32::MAX; WIDTH],
        order: [0xFEDC_BA98; WIDTH],
    };
}

/// The coordinates the BVH's `f32` boxes are stored in: `(p − centre) ·
/// scale`, with `centre` the middle of the items' bounding box and `scale`
/// the power of two that brings its largest half-extent into `[½, 1)`.
///
/// Relative to the centre, `f32` boxes stay as tight as the solid is small,
/// wherever it is (a solid 1e8 from the origin culls as well as one at the
/// origin); the power-of-two scale keeps `f32` far from overflow and
/// underflow for solids of any size (1e-12 or 1e12) and is exact.
///
/// # Invariants
///
/// Every stored bound is the exact real `(x − centre) · scale` rounded
/// outward: [`BoxFrame::lower`] never exceeds it, [`BoxFrame::upper`] is
/// never below it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BoxFrame {
    /// The middle of the items' bounding box (any point would be correct).
    pub centre: DVec3,
    /// A power of two.
    pub scale: f64,
}

impl BoxFrame {
    /// The frame of a solid with bounding box `bounds`.
    pub(crate) fn of(bounds: &Aabb) -> BoxFrame {
        if bounds.is_empty() {
            return BoxFrame {
                centre: DVec3::ZERO,
                scale: 1.0,
            };
        }
        let centre = bounds.center();
        let half = (bounds.max - centre).max(centre - bounds.min).max_element();
        // 2^-e with 2^(e-1) <= half < 2^e; 1 for a single point.
        let scale = if half > 0.0 && half.is_finite() {
            let e = half.log2().floor() as i32 + 1;
            2f64.powi(-e.clamp(-1000, 1000))
        } else {
            1.0
        };
        BoxFrame { centre, scale }
    }

    /// `(x − centre[axis]) · scale`, rounded to `f64`: within half an
    /// `f64` ulp of the exact value (the scaling by a power of two is exact
    /// unless the result is subnormal, where it errs by at most 2⁻¹⁰⁷⁵).
    #[inline]
    #[must_use]
    pub fn in_frame(&self, x: f64, axis: usize) -> f64 {
        (x - self.centre[axis]) * self.scale
    }

    /// An `f32` at most the exact `(x − centre[axis]) · scale`: the rounded
    /// value stepped one `f64` ulp down (covering its rounding), then rounded
    /// down to `f32`.
    #[must_use]
    pub fn lower(&self, x: f64, axis: usize) -> f32 {
        f32_down(f64_below(self.in_frame(x, axis)))
    }

    /// An `f32` at least the exact `(x − centre[axis]) · scale`.
    #[must_use]
    pub fn upper(&self, x: f64, axis: usize) -> f32 {
        f32_up(f64_above(self.in_frame(x, axis)))
    }
}

/// The items of one leaf: positions `first .. first + count` of the tree's
/// item order (see [`Bvh::build`](super::Bvh::build)).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LeafItems {
    /// The leaf's first item position.
    pub first: u32,
    /// Its number of items, `1 ..= LEAF_SIZE`.
    pub count: u32,
}

impl LeafItems {
    /// The positions as a range.
    #[must_use]
    pub fn range(self) -> std::ops::Range<usize> {
        self.first as usize..(self.first + self.count) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_bounds_round_outward() {
        for x in [0.1, -0.1, 1e12 + 0.3, -1e-12, 1e-50, -1e-50, 0.0, 3.0] {
            assert!(f64::from(f32_down(x)) <= x, "{x}");
            assert!(f64::from(f32_up(x)) >= x, "{x}");
        }
    }

    #[test]
    fn frame_bounds_round_outward() {
        // Far from the origin, a tiny solid: `x − centre` is exact here, so
        // the bounds must bracket it, and tightly (f32 relative to the
        // solid's size, not to its distance from the origin).
        let bounds = Aabb::from_points([DVec3::splat(1e8), DVec3::splat(1e8 + 1.0)]);
        let frame = BoxFrame::of(&bounds);
        assert_eq!(frame.scale, 1.0);
        for x in [1e8, 1e8 + 1.0, 1e8 + 2f64.powi(-26), 1e8 + 0.75] {
            let exact = (x - frame.centre.x) * frame.scale;
            let (lo, hi) = (frame.lower(x, 0), frame.upper(x, 0));
            assert!(f64::from(lo) <= exact && exact <= f64::from(hi), "{x}");
            assert!(f64::from(hi) - f64::from(lo) < 1e-6, "{x}: {lo} {hi}");
        }
        // Huge and tiny solids keep the frame's coordinates near 1.
        for size in [1e-300, 1e-12, 1e12, 1e300] {
            let b = Aabb::from_points([DVec3::ZERO, DVec3::splat(size)]);
            let f = BoxFrame::of(&b);
            let top = f.upper(size, 1);
            assert!((0.5..=1.0).contains(&top), "{size}: {top}");
        }
    }
}
