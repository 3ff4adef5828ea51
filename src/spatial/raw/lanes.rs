//! Four `f32` lanes side by side: the arithmetic of the leaves' miss filter
//! and of the portable slab tests (see `spatial::bvh::open_portable`), written once.
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
pub(crate) struct F32x4(
    #[cfg(target_arch = "x86_64")] arch::__m128,
    #[cfg(not(target_arch = "x86_64"))] [f32; 4],
);

/// Four lane conditions, as a bit mask (bit `k` for lane `k`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mask4(
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
        pub(crate) fn splat(x: f32) -> F32x4 {
            F32x4(unsafe { arch::_mm_set1_ps(x) })
        }
        #[inline(always)]
        pub(crate) fn load(x: &[f32; 4]) -> F32x4 {
            F32x4(unsafe { arch::_mm_loadu_ps(x.as_ptr()) })
        }
        #[inline(always)]
        pub(crate) fn to_array(self) -> [f32; 4] {
            let mut out = [0.0; 4];
            unsafe { arch::_mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }
        #[inline(always)]
        pub(crate) fn add(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_add_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn sub(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_sub_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn mul(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_mul_ps(self.0, o.0) })
        }
        /// Per lane `if self > o { self } else { o }`: `o` when either is
        /// NaN (`maxps` returns its second operand then).
        #[inline(always)]
        pub(crate) fn max_or(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_max_ps(self.0, o.0) })
        }
        /// Per lane `if self < o { self } else { o }`.
        #[inline(always)]
        pub(crate) fn min_or(self, o: F32x4) -> F32x4 {
            F32x4(unsafe { arch::_mm_min_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn gt(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmpgt_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn lt(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmplt_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn le(self, o: F32x4) -> Mask4 {
            Mask4(unsafe { arch::_mm_cmple_ps(self.0, o.0) })
        }
    }

    impl Mask4 {
        #[inline(always)]
        pub(crate) fn or(self, o: Mask4) -> Mask4 {
            Mask4(unsafe { arch::_mm_or_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub(crate) fn and(self, o: Mask4) -> Mask4 {
            Mask4(unsafe { arch::_mm_and_ps(self.0, o.0) })
        }
        /// Bit `k` set when lane `k` holds.
        #[inline(always)]
        pub(crate) fn bits(self) -> u32 {
            (unsafe { arch::_mm_movemask_ps(self.0) }) as u32
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
mod imp {
    use super::{F32x4, Mask4};

    impl F32x4 {
        #[inline(always)]
        pub(crate) fn splat(x: f32) -> F32x4 {
            F32x4([x; 4])
        }
        #[inline(always)]
        pub(crate) fn load(x: &[f32; 4]) -> F32x4 {
            F32x4(*x)
        }
        #[inline(always)]
        pub(crate) fn to_array(self) -> [f32; 4] {
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
        pub(crate) fn add(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a + b)
        }
        #[inline(always)]
        pub(crate) fn sub(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a - b)
        }
        #[inline(always)]
        pub(crate) fn mul(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| a * b)
        }
        /// Per lane `if self > o { self } else { o }`.
        #[inline(always)]
        pub(crate) fn max_or(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| if a > b { a } else { b })
        }
        /// Per lane `if self < o { self } else { o }`.
        #[inline(always)]
        pub(crate) fn min_or(self, o: F32x4) -> F32x4 {
            self.zip(o, |a, b| if a < b { a } else { b })
        }
        #[inline(always)]
        pub(crate) fn gt(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a > b)
        }
        #[inline(always)]
        pub(crate) fn lt(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a < b)
        }
        #[inline(always)]
        pub(crate) fn le(self, o: F32x4) -> Mask4 {
            self.test(o, |a, b| a <= b)
        }
    }

    impl Mask4 {
        #[inline(always)]
        pub(crate) fn or(self, o: Mask4) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| self.0[k] | o.0[k]))
        }
        #[inline(always)]
        pub(crate) fn and(self, o: Mask4) -> Mask4 {
            Mask4([0, 1, 2, 3].map(|k| self.0[k] & o.0[k]))
        }
        /// Bit `k` set when lane `k` holds.
        #[inline(always)]
        pub(crate) fn bits(self) -> u32 {
            (0..4).map(|k| u32::from(self.0[k]) << k).sum()
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
}
