//! A ray as the BVH's `f32` slab tests see it, and the entries of a ray
//! walk's stack (children keyed by where the ray enters their boxes).

use glam::{BVec4A, DVec3, Vec4};

use crate::geom::Ray;

use super::node::BoxFrame;

/// The low bits of a key that carry `8 | slot` (see `open`).
pub(super) const KEY_SLOT_BITS: u32 = 15;

/// A ray as the `f32` slab tests of the BVH see it: in the tree's
/// [`BoxFrame`], with its parameter rescaled and every constant rounded so
/// that the tests can only err towards entering a box.
///
/// The ray's direction `d'` is already scaled by a power of two so that its
/// largest `|d'ₐ|` is in `[1, 2)` (`query`'s `unit_scaled`). In the frame,
/// the ray is `o' + s · d'` with `o' = (o − centre) · scale` and
/// `s = t · scale`: the same points, with `s` a power-of-two multiple of
/// `t`, so comparisons of `s` are comparisons of `t`.
///
/// # Why the test is conservative
///
/// Per axis, the entry `(near − o')/d'ₐ` is computed from `f32` constants
/// chosen to make it smaller (the origin rounded away from the near plane,
/// `1/d'ₐ` rounded towards zero) and the exit `(far − o')/d'ₐ` from
/// constants making it larger (the origin rounded the other way, `1/d'ₐ`
/// rounded away from zero and grown by `1 + 2⁻²⁰`; the origin is widened by
/// `|f|·2⁻²² + 2⁻¹²⁶` around its `f32` value `f`, the reciprocals shrunk by
/// `1 − 2⁻²²` and grown by `1 + 2⁻¹⁹`, which cover their own roundings).
/// The two `f32` roundings
/// of the subtraction and the product change each by a factor within
/// `(1 ± u)²`, `u = 2⁻²⁴`; as `(1 + u)² < (1 + 2⁻²⁰)(1 − u)²`, a box the
/// exact ray enters at `s₀ ≤ s₁` has computed entry ≤ computed exit, and a
/// computed entry at most `(1 + u)² s₀`. Signs survive rounding, so boxes
/// behind the origin stay behind. A zero direction component gives `1/0 =
/// ±∞` exactly (the slab then holds the origin or not, as the exact test
/// says; `0 · ∞ = NaN` when the origin is on the slab plane leaves the bound
/// unchanged). The limit a box is compared with is the current best `t`
/// grown by the same `2⁻²⁰`, which covers both the entry's rounding and the
/// `f64` rounding of the best `t` itself.
pub(crate) struct RayBox {
    /// The origin in the frame, rounded (per axis) away from the near
    /// planes: used for entries. (Lane 3 of this and the next three
    /// arrays is unused.)
    pub o_near: [f32; 4],
    /// The origin in the frame, rounded towards the near planes: used for
    /// exits.
    pub o_far: [f32; 4],
    /// `1/d'ₐ` rounded towards zero (exactly `±∞` when `d'ₐ = 0`).
    pub inv_near: [f32; 4],
    /// `1/d'ₐ · (1 + 2⁻²⁰)` rounded away from zero.
    pub inv_far: [f32; 4],
    /// Per axis, the row of [`Node8::bounds`](super::Node8::bounds)
    /// holding the near planes (lower bounds when the ray runs up the axis).
    pub near_row: [Row; 3],
    /// Per axis, the row holding the far planes.
    pub far_row: [Row; 3],
    /// `scale`: the factor from `t` to `s`.
    pub(crate) t_to_s: f64,
    /// The octant of the direction: bit `a` set when it runs down axis `a`
    /// (see [`Node8::order`](super::Node8::order)).
    pub octant: usize,
}

/// `2⁻²²`: the relative widening of the origin (see [`RayBox`]).
pub(crate) const ORIGIN_WIDEN: f32 = 1.0 / (1u32 << 22) as f32;
/// `1 − 2⁻²²`: `1/d'ₐ` rounded to `f32` (relative error at most 2⁻²⁴, plus
/// 2⁻⁵³ from `f64`) times this, rounded, is below the exact reciprocal.
pub(crate) const INV_SHRINK: f32 = 1.0 - ORIGIN_WIDEN;
/// `1 + 2⁻¹⁹`: `1/d'ₐ` rounded to `f32` times this, rounded, is at least
/// the exact reciprocal grown by the slab margin `1 + 2⁻²⁰`:
/// `(1 − 2⁻²⁴)² (1 + 2⁻¹⁹) > 1 + 2⁻²⁰`.
pub(crate) const INV_GROW: f32 = 1.0 + 2.0 / (1u32 << 20) as f32;

impl RayBox {
    /// The slab-test form of `ray`, whose direction is already scaled so
    /// that its largest component is in `[1, 2)` (so `d' = d`).
    #[inline(always)]
    pub(crate) fn new(ray: &Ray, frame: &BoxFrame) -> RayBox {
        let d = ray.direction;
        debug_assert!((1.0..2.0).contains(&d.abs().max_element()), "{d}");
        // The three axes side by side (lane 3 is unused). `d32` carries the
        // sign of each `dₐ`, −0 included (rounding to `f32` keeps it).
        let d32 = d.as_vec3().extend(1.0);
        // The origin in the frame, rounded to `f32`, widened by
        // `|f|·2⁻²² + 2⁻¹²⁶` either way (see `RayBox`): covers the rounding
        // to `f32` (at most `|f|·2⁻²⁴`, or 2⁻¹⁵⁰ below the normal range),
        // the `f64` rounding of `o` and the rounding of the widening itself.
        // Beyond the `f32` range: no constraint at all. Going down the axis
        // (`d'ₐ` negative, or −0), the ray enters through the upper plane:
        // `(upper − o) · (−|inv|)` is smallest for the smallest origin, so
        // the near origin is `f − m` and the far one `f + m` (the widening
        // takes the sign of `dₐ`: no branch on the signs of random
        // directions, which are not predictable).
        let f = ((ray.origin - frame.centre) * frame.scale)
            .as_vec3()
            .extend(0.0);
        let widen = (f.abs() * ORIGIN_WIDEN + Vec4::splat(f32::MIN_POSITIVE)).copysign(d32);
        let unbounded = Vec4::INFINITY.copysign(d32);
        let finite = f.is_finite_mask();
        let o_near = Vec4::select(finite, f + widen, unbounded);
        let o_far = Vec4::select(finite, f - widen, -unbounded);
        // `1/|dₐ|` rounded to `f32`, shrunk and grown (see the constants);
        // exactly `+∞` for a zero component. Then the sign of `dₐ`.
        let recip = (DVec3::ONE / d.abs()).as_vec3().extend(1.0);
        let zero = d.cmpeq(DVec3::ZERO);
        let zero = BVec4A::new(zero.x, zero.y, zero.z, false);
        let inv_lo = Vec4::select(
            zero,
            Vec4::INFINITY,
            (recip * INV_SHRINK).min(Vec4::splat(f32::MAX)),
        );
        let inv_hi = Vec4::select(zero, Vec4::INFINITY, recip * INV_GROW);
        let down = d32.is_negative_bitmask();
        RayBox {
            o_near: o_near.to_array(),
            o_far: o_far.to_array(),
            inv_near: inv_lo.copysign(d32).to_array(),
            inv_far: inv_hi.copysign(d32).to_array(),
            near_row: [0, 1, 2].map(|a| Row::of(a, down >> a & 1 == 1)),
            far_row: [0, 1, 2].map(|a| Row::of(a, down >> a & 1 == 0)),
            t_to_s: frame.scale,
            octant: (down & 7) as usize,
        }
    }

    /// The limit in `s` for a best crossing at `t` (grown by the margin,
    /// rounded up; `+∞` for none).
    #[inline]
    pub(crate) fn limit(&self, t: f64) -> f32 {
        // `(x as f32) ≥ x (1 − 2⁻²⁴)` for normal `f32`; grown by 2⁻¹⁹ and
        // rounded it is at least `x (1 + 2⁻²⁰)`; `+ 2⁻¹²⁶` covers `x` below
        // the normal range. `+∞` stays `+∞`.
        ((t * self.t_to_s) as f32) * INV_GROW + f32::MIN_POSITIVE
    }
}

/// A row of [`Node8::bounds`](super::Node8::bounds): the lower
/// (`Lower*`) or upper (`Upper*`) bounds of the children along one axis.
/// An enum rather than an index, so that a row is always in range (the
/// slab tests index the rows without a bounds check).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(crate) enum Row {
    /// Lower bounds along `x`.
    LowerX = 0,
    /// Lower bounds along `y`.
    LowerY = 1,
    /// Lower bounds along `z`.
    LowerZ = 2,
    /// Upper bounds along `x`.
    UpperX = 3,
    /// Upper bounds along `y`.
    UpperY = 4,
    /// Upper bounds along `z`.
    UpperZ = 5,
}

impl Row {
    /// The row of the bounds along axis `a` (0, 1 or 2): the upper ones
    /// when `upper`.
    #[inline(always)]
    pub(crate) fn of(a: usize, upper: bool) -> Row {
        match (a, upper) {
            (0, false) => Row::LowerX,
            (1, false) => Row::LowerY,
            (2, false) => Row::LowerZ,
            (0, true) => Row::UpperX,
            (1, true) => Row::UpperY,
            _ => Row::UpperZ,
        }
    }

    /// The row's index into [`Node8::bounds`](super::Node8::bounds).
    #[inline(always)]
    pub(crate) fn index(self) -> usize {
        self as usize
    }
}

/// A child waiting on a traversal's stack: its
/// [`Node8::child`](super::Node8::child) entry and its key (see `open`).
/// `repr(C)`: the AVX2 opener writes entries as
/// pairs of `u32` lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct Deferred {
    /// [`LEAF`] plus a packet index, or an inner node's index.
    pub child: u32,
    /// The child's entry bits with `8 | slot` in the low four bits.
    pub key: u32,
}

impl Deferred {
    /// An unused stack slot.
    pub(crate) const EMPTY: Deferred = Deferred { child: 0, key: 0 };

    /// The child, unless its box is entered beyond the limit whose
    /// [`limit_key`] is `limit_key`: the key without its slot bits, read as
    /// an `f32`, is at most the child's entry (so culling with it stays
    /// conservative).
    #[inline(always)]
    pub(crate) fn reached(self, limit_key: u32) -> Option<u32> {
        (self.key <= limit_key).then_some(self.child)
    }
}

/// The culling limit `limit` (a non-negative `f32` or `+∞`, never NaN) as a
/// key: a [`Deferred`] child is within the limit exactly when its key is at
/// most this, compared as integers.
///
/// A key's bits without the slot bits, `k = key & !15`, are those of a
/// non-negative `f32`, and so is `L = limit.to_bits()`: for such values the
/// bits order as the numbers do, so `f32::from_bits(k) ≤ limit` is `k ≤ L`.
/// As `k` is a multiple of 16, `k ≤ L` holds exactly when `k ≤ L & !15`,
/// that is when `key = k | slot ≤ L | 15`.
#[inline(always)]
pub(crate) fn limit_key(limit: f32) -> u32 {
    debug_assert!(limit >= 0.0, "{limit}");
    limit.to_bits() | KEY_SLOT_BITS
}
