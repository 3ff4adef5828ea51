//! Four `f32` lanes side by side: the arithmetic of the BVH's slab tests,
//! the ordering of a node's children and the leaves' miss filter, written
//! once.
//!
//! On `x86_64` the operations are SSE and SSE2 instructions, one each for
//! the arithmetic (both are part of the `x86_64` baseline, so no feature
//! detection is needed); elsewhere the same operations run lane by lane.
//! Both give the same IEEE results: every arithmetic operation is a single
//! correctly rounded `f32` operation per lane, never fused.

#[cfg(target_arch = "x86_64")]
use std::arch::x86_64 as arch;

/// Four `f32` values.
#[derive(Clone, Copy, Debug)]
pub(super) struct F32x4(
    #[cfg(target_arch = "x86_64")] arch::__m128,
    #[cfg(not(target_arch = "x86_64"))] [f32; 4],
);

/// Four lane conditions, as a bit mask (bit `k` for lane `k`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Mask4(
    #[cfg(target_arch = "x86_64")] arch::__m128,
    #[cfg(not(target_arch = "x86_64"))] [bool; 4],
);

#[cfg(target_arch = "x86_64")]
mod imp {
    // SAFETY (every `unsafe` block below): SSE and SSE2 are enabled on every
    // `x86_64` target, and the loads read exactly the 16 bytes of a
    // `[f32; 4]` or `[u32; 4]` through `loadu` (no alignment needed).
    use super::{F32x4, Mask4, arch};

    impl F32x4 {
        #[inline(always)]
        pub(in super::super) fn splat(x: f32) -> F32x4 {
            F32x4(unsafe { arch::_mm_set1_ps(x) })
        }
        #[inline(always)]
        pub(in super::super) fn load(x: &[f32; 4]) -> F32x4 {
            F32x4(unsafe { arch::_mm_loadu_ps(x.as_ptr()) })
        }
        #[cfg(test)]
        pub(in super::super) fn to_array(self) -> [f32; 4] {
            let mut out = [0.0; 4];
            unsafe { arch::_mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }
        #[inline(always)]
        pub(in super::super) fn add(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_add_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn sub(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_sub_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn mul(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_mul_ps(self.0, o.0) })
        }
        /// Per lane `if self > o { self } else { o }`: `o` when either is
        /// NaN (`maxps` returns its second operand then).
        #[inline(always)]
        pub(in super::super) fn max_or(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_max_ps(self.0, o.0) })
        }
        /// Per lane `if self < o { self } else { o }`.
        #[inline(always)]
        pub(in super::super) fn min_or(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_min_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn gt(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmpgt_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn lt(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmplt_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn le(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmple_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn and_bits(self, bits: [u32; 4]) -> F32x4 {
            F32x4(unsafe { arch::_mm_and_ps(self.0, bits_of(&bits)) })
        }
        #[inline(always)]
        pub(in super::super) fn or_bits(self, bits: [u32; 4]) -> F32x4 {
            F32x4(unsafe { arch::_mm_or_ps(self.0, bits_of(&bits)) })
        }
        #[inline(always)]
        pub(in super::super) fn keep(self, m: Mask4) -> F32x4 {
            F32x4(unsafe { arch::_mm_and_ps(self.0, m.0) })
        }
        /// Five compare-exchanges in three rounds, each a shuffle, a
        /// `min`, a `max` and a shuffle picking the results.
        #[inline(always)]
        pub(in super::super) fn sorted_descending(self) -> F32x4 {
            // `_mm_shuffle_ps::<IMM>(x, y)` is `[x[i0], x[i1], y[i2], y[i3]]`
            // with `iₖ` the 2-bit field `k` of `IMM` (lowest first).
            const SWAP_PAIRS: i32 = 0b10_11_00_01; // [v1, v0, v3, v2]
            const SPREAD: i32 = 0b11_01_10_00; // [x0, x2, y1, y3]
            const SWAP_MIDDLE: i32 = 0b11_01_10_00; // [v0, v2, v1, v3]
            const JOIN: i32 = 0b11_10_01_00; // [x0, x1, y2, y3]
            unsafe {
                let v = self.0;
                // Pairs (0, 1) and (2, 3):
                // [max(v0, v1), max(v2, v3), min(v0, v1), min(v2, v3)].
                let s = arch::_mm_shuffle_ps::<SWAP_PAIRS>(v, v);
                let v =
                    arch::_mm_shuffle_ps::<SPREAD>(arch::_mm_max_ps(v, s), arch::_mm_min_ps(v, s));
                // The two maxima and the two minima: [largest, larger
                // minimum, smaller maximum, smallest].
                let s = arch::_mm_shuffle_ps::<SWAP_PAIRS>(v, v);
                let v =
                    arch::_mm_shuffle_ps::<SPREAD>(arch::_mm_max_ps(v, s), arch::_mm_min_ps(v, s));
                // The middle two.
                let s = arch::_mm_shuffle_ps::<SWAP_MIDDLE>(v, v);
                F32x4(arch::_mm_shuffle_ps::<JOIN>(
                    arch::_mm_max_ps(v, s),
                    arch::_mm_min_ps(v, s),
                ))
            }
        }
        /// The bits of each lane.
        #[inline(always)]
        pub(in super::super) fn to_bits(self) -> [u32; 4] {
            let mut out = [0u32; 4];
            unsafe { arch::_mm_storeu_ps(out.as_mut_ptr().cast::<f32>(), self.0) };
            out
        }
    }

    /// The 16 bytes of `bits` as four `f32` lanes.
    #[inline(always)]
    fn bits_of(bits: &[u32; 4]) -> arch::__m128 {
        unsafe { arch::_mm_loadu_ps(bits.as_ptr().cast::<f32>()) }
    }

    impl Mask4 {
        #[inline(always)]
        pub(in super::super) fn or(self, o: Mask4) -> Mask4 {
            Mask4(unsafe { arch::_mm_or_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(in super::super) fn and(self, o: Mask4) -> Mask4 {
            Mask4(unsafe { arch::_mm_and_ps(self.0, o.0) })
        }
        /// Bit `k` set when lane `k` holds.
        #[inline(always)]
        pub(in super::super) fn bits(self) -> u32 {
            (unsafe { arch::_mm_movemask_ps(self.0) }) as u32
        }
        /// Lanes where `self` holds and `values[k] != v`.
        #[inline(always)]
        pub(in super::super) fn and_not_equal(self, values: &[u32; 4], v: u32) -> Mask4 {
            unsafe {
                let lanes = arch::_mm_loadu_si128(values.as_ptr().cast());
                let equal = arch::_mm_cmpeq_epi32(lanes, arch::_mm_set1_epi32(v as i32));
                Mask4(arch::_mm_andnot_ps(arch::_mm_castsi128_ps(equal), self.0))
            }
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    use super::{F32x4, Mask4};

    impl F32x4 {
        #[inline(always)]
        pub(in super::super) fn splat(x: f32) -> F32x4 {
            F32x4([x; 4])
        }
        #[inline(always)]
        pub(in super::super) fn load(x: &[f32; 4]) -> F32x4 {
            F32x4(*x)
        }
        #[cfg(test)]
        pub(in super::super) fn to_array(self) -> [f32; 4] {
            self.0
        }
        #[inline(always)]
        fn zip(self, o: F32x4, f: impl Fn(f32, f32) -> f32) -> F32x4 {
            F32x4([0, 1, 2, 3].map(|k| f(self.0[k], o.0[k])))
        }
        #[inline(always)]
        fn test(self, o: F32x4, f: impl Fn(f32, f32) -> bool) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| f(self.0[k], o.0[k])))
        }
        #[inline(always)]
        pub(in super::super) fn add(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a + b)
        }
        #[inline(always)]
        pub(in super::super) fn sub(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a - b)
        }
        #[inline(always)]
        pub(in super::super) fn mul(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a * b)
        }
        /// Per lane `if self > o { self } else { o }`.
        #[inline(always)]
        pub(in super::super) fn max_or(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| if a > b { a } else { b })
        }
        /// Per lane `if self < o { self } else { o }`.
        #[inline(always)]
        pub(in super::super) fn min_or(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| if a < b { a } else { b })
        }
        #[inline(always)]
        pub(in super::super) fn gt(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a > b)
        }
        #[inline(always)]
        pub(in super::super) fn lt(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a < b)
        }
        #[inline(always)]
        pub(in super::super) fn le(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a <= b)
        }
        #[inline(always)]
        fn bitwise(self, bits: [u32; 4], f: impl Fn(u32, u32) -> u32) -> F32x4 {
            F32x4([0, 1, 2, 3].map(|k| f32::from_bits(f(self.0[k].to_bits(), bits[k]))))
        }
        /// Per lane, the bits of `self` and of `bits` ANDed.
        #[inline(always)]
        pub(in super::super) fn and_bits(self, bits: [u32; 4]) -> F32x4 {
            self.bitwise(bits, |a, b| a & b)
        }
        /// Per lane, the bits of `self` and of `bits` ORed.
        #[inline(always)]
        pub(in super::super) fn or_bits(self, bits: [u32; 4]) -> F32x4 {
            self.bitwise(bits, |a, b| a | b)
        }
        /// The lanes where `m` holds; `+0.0` in the others.
        #[inline(always)]
        pub(in super::super) fn keep(self, m: Mask4) -> F32x4 {
            self.bitwise(m.0.map(|b| if b { u32::MAX } else { 0 }), |a, b| a & b)
        }
        /// The four values, largest first (no lane may be NaN).
        #[inline(always)]
        pub(in super::super) fn sorted_descending(self) -> F32x4 {
            let mut v = self.0;
            v.sort_by(|a, b| b.total_cmp(a));
            F32x4(v)
        }
        /// The bits of each lane.
        #[inline(always)]
        pub(in super::super) fn to_bits(self) -> [u32; 4] {
            self.0.map(f32::to_bits)
        }
    }

    impl Mask4 {
        #[inline(always)]
        pub(in super::super) fn or(self, o: Mask4) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| self.0[k] | o.0[k]))
        }
        #[inline(always)]
        pub(in super::super) fn and(self, o: Mask4) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| self.0[k] & o.0[k]))
        }
        /// Bit `k` set when lane `k` holds.
        #[inline(always)]
        pub(in super::super) fn bits(self) -> u32 {
            (0..4).map(|k| u32::from(self.0[k]) << k).sum()
        }
        /// Lanes where `self` holds and `values[k] != v`.
        #[inline(always)]
        pub(in super::super) fn and_not_equal(self, values: &[u32; 4], v: u32) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| self.0[k] && values[k] != v))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_follow_scalar_semantics_including_nan() {
        let a = [1.5f32, f32::NAN, -0.0, f32::INFINITY];
        let b = [2.0f32, 3.0, f32::NAN, 1.0];
        let (x, y) = (F32x4::load(&a), F32x4::load(&b));
        let scalar = |f: fn(f32, f32) -> f32| [0, 1, 2, 3].map(|k| f(a[k], b[k]));
        let same = |v: F32x4, w: [f32; 4]| {
            v.to_array()
                .iter()
                .zip(w)
                .all(|(p, q)| p.to_bits() == q.to_bits())
        };
        assert!(same(x.add(y), scalar(|p, q| p + q)));
        assert!(same(x.sub(y), scalar(|p, q| p - q)));
        assert!(same(x.mul(y), scalar(|p, q| p * q)));
        assert!(same(x.max_or(y), scalar(|p, q| if p > q { p } else { q })));
        assert!(same(x.min_or(y), scalar(|p, q| if p < q { p } else { q })));
        assert_eq!(x.gt(y).bits(), 0b1000);
        assert_eq!(x.lt(y).bits(), 0b0001);
        assert_eq!(x.le(y).bits(), 0b0001);
        assert_eq!(x.gt(y).or(x.lt(y)).bits(), 0b1001);
        assert_eq!(x.le(y).and(x.lt(y)).bits(), 0b0001);
        assert_eq!(F32x4::splat(2.0).to_array(), [2.0; 4]);
    }

    #[test]
    fn bitwise_lanes_and_sorting_follow_scalar_semantics() {
        let v = F32x4::load(&[1.5, 0.0, 3.0, f32::MAX]);
        let bits = |v: F32x4| v.to_array().map(f32::to_bits);
        let masks = [0x7fff_fff8, u32::MAX, 0, 0x0f0f_0f0f];
        let ones = [1, 2, 4, 8];
        let raw = [1.5f32, 0.0, 3.0, f32::MAX].map(f32::to_bits);
        assert_eq!(
            bits(v.and_bits(masks)),
            [0, 1, 2, 3].map(|k| raw[k] & masks[k])
        );
        assert_eq!(
            bits(v.or_bits(ones)),
            [0, 1, 2, 3].map(|k| raw[k] | ones[k])
        );
        let entered = v.gt(F32x4::splat(1.0));
        assert_eq!(v.keep(entered).to_array(), [1.5, 0.0, 3.0, f32::MAX]);
        assert_eq!(
            v.keep(v.lt(F32x4::splat(2.0))).to_array(),
            [1.5, 0.0, 0.0, 0.0]
        );
        assert_eq!(
            entered.and_not_equal(&[7, 7, u32::MAX, 9], u32::MAX).bits(),
            0b1001
        );
        assert_eq!(v.to_bits(), raw);
        // Every order of four values, ties and zeros included.
        let values = [0.0f32, 0.5, 0.5, 7.0];
        let mut order = [0usize, 1, 2, 3];
        for _ in 0..24 {
            let lanes = order.map(|k| values[k]);
            assert_eq!(
                F32x4::load(&lanes).sorted_descending().to_array(),
                [7.0, 0.5, 0.5, 0.0]
            );
            for distinct in [[1.0f32, 2.0, 3.0, 4.0], [0.0, 0.0, 0.0, 9.0]] {
                let lanes = order.map(|k| distinct[k]);
                let mut expected = distinct;
                expected.sort_by(|a, b| b.total_cmp(a));
                assert_eq!(F32x4::load(&lanes).sorted_descending().to_array(), expected);
            }
            next_permutation(&mut order);
        }
    }

    /// The next permutation in lexicographic order (wrapping to the first).
    fn next_permutation(p: &mut [usize; 4]) {
        let Some(i) = (0..3).rev().find(|&i| p[i] < p[i + 1]) else {
            p.reverse();
            return;
        };
        let j = (i + 1..4)
            .rev()
            .find(|&j| p[j] > p[i])
            .expect("p[i + 1] > p[i]");
        p.swap(i, j);
        p[i + 1..].reverse();
    }
}
