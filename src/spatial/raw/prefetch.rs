//! Requests for memory ahead of its use: a hint to the processor that
//! changes no answer.

/// Asks the processor to start loading the cache lines of `items` (a hint:
/// no effect on any answer; nothing on targets without the instruction).
#[inline(always)]
pub(crate) fn prefetch<T>(items: &[T]) {
    let bytes = std::mem::size_of_val(items);
    if bytes > 0 {
        let start = items.as_ptr().cast::<u8>();
        prefetch_bytes(start, bytes - 1);
    }
}

/// Asks the processor to start loading the cache lines of the bytes
/// `start ..= start + last` (a hint: the address is never dereferenced, and
/// may be anything).
#[inline(always)]
pub(crate) fn prefetch_bytes(start: *const u8, last: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = start.cast::<i8>();
        let mut offset = 0;
        while offset < last {
            // SAFETY: SSE is part of the x86_64 baseline, and a prefetch
            // is a hint that never faults, whatever the address.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) };
            offset += 64;
        }
        // The last line, when the bytes straddle one more boundary.
        // SAFETY: as above.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(last)) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (start, last);
}
