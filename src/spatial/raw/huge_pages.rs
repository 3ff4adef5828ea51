//! Large arrays of the spatial structures and their queries on huge pages,
//! where the system offers them.
//!
//! A ray's walk reads a few nodes, packets and triangles scattered over
//! arrays of many megabytes. With 4 KiB pages nearly every one of those
//! reads also misses the processor's address-translation cache and waits
//! for a page-table walk; 2 MiB pages cover the same arrays with a few
//! entries. On Linux, whose transparent huge pages are commonly enabled
//! only for memory that asks for them (`madvise` mode), the accel's large
//! arrays are [`HugeVec`]s: their memory starts on a 2 MiB boundary and
//! spans whole huge pages, and is advised `MADV_HUGEPAGE` before anything
//! is written to it (so it faults in 2 MiB at a time), then collapsed into
//! huge pages once built (`MADV_COLLAPSE`, Linux 6.1 and later: for memory
//! the allocator had already used, which the first advice does not move).
//! Elsewhere, or when the system refuses, nothing changes: the advice is
//! about how memory is backed, never about what it holds.
//!
//! Whole arrays go on huge pages, not only their 2 MiB-aligned middle
//! parts: the few megabytes left on small pages at each end of an array are
//! read as often as the rest, and their misses of the translation cache
//! are a visible share of a walk's waiting on memory.

use std::alloc::{Layout, alloc, dealloc, handle_alloc_error};
use std::mem::MaybeUninit;
use std::ops::{Deref, DerefMut};
use std::ptr::NonNull;

use rayon::prelude::*;

/// The size of a huge page; smaller arrays are left alone.
const HUGE: usize = 2 << 20;

/// Arrays of at least this many bytes get memory of their own on huge
/// pages. Their last huge page is resident in full once touched: up to
/// just under 2 MiB more than the items need per array (at most as much
/// again as the items themselves, since they fill at least half a page).
const HUGE_ARRAY_BYTES: usize = HUGE / 2;

/// A vector of `Copy` items with a capacity fixed when it is made: when
/// that is at least [`HUGE_ARRAY_BYTES`] (on Linux), its memory starts on a
/// 2 MiB boundary and is a whole number of huge pages, advised to be backed
/// by them before anything is written.
///
/// # Invariants
///
/// `ptr` is `layout`'s allocation (dangling when `layout.size()` is 0),
/// with room for `capacity` items; `ptr[..len]` are initialised and
/// `len ≤ capacity`.
pub(crate) struct HugeVec<T: Copy> {
    ptr: NonNull<T>,
    len: usize,
    capacity: usize,
    layout: Layout,
}

// SAFETY: a `HugeVec` owns its items as a `Vec` does.
unsafe impl<T: Copy + Send> Send for HugeVec<T> {}
// SAFETY: shared access hands out only `&[T]`.
unsafe impl<T: Copy + Sync> Sync for HugeVec<T> {}

impl<T: Copy> HugeVec<T> {
    /// An empty vector with room for exactly `capacity` items.
    ///
    /// # Panics
    ///
    /// When `capacity` items do not fit the address space (as
    /// `Vec::with_capacity`); aborts when memory runs out.
    pub(crate) fn with_capacity(capacity: usize) -> HugeVec<T> {
        let bytes = size_of::<T>()
            .checked_mul(capacity)
            .expect("capacity overflow");
        let huge = cfg!(target_os = "linux") && bytes >= HUGE_ARRAY_BYTES;
        let layout = if huge {
            bytes
                .checked_next_multiple_of(HUGE)
                .and_then(|size| Layout::from_size_align(size, HUGE).ok())
        } else {
            Layout::array::<T>(capacity).ok()
        }
        .expect("capacity overflow");
        let ptr = if layout.size() == 0 {
            NonNull::dangling()
        } else {
            // SAFETY: the layout's size is not zero.
            let raw = unsafe { alloc(layout) };
            let Some(ptr) = NonNull::new(raw.cast::<T>()) else {
                handle_alloc_error(layout)
            };
            if huge {
                advise(raw as usize, layout.size(), Advice::HugePages);
            }
            ptr
        };
        HugeVec {
            ptr,
            len: 0,
            capacity,
            layout,
        }
    }

    /// The vector of `items`, in order, made on all cores.
    pub(crate) fn from_par_iter<I>(items: I) -> HugeVec<T>
    where
        I: IndexedParallelIterator<Item = T>,
        T: Send,
    {
        let mut v = HugeVec::with_capacity(items.len());
        // An indexed zip pairs slot `i` with item `i`: the slots written are
        // the first `written`, however many items the iterator yields.
        let written = v
            .spare()
            .par_iter_mut()
            .zip(items)
            .with_min_len(1 << 12)
            .map(|(slot, item)| {
                slot.write(item);
            })
            .count();
        v.len = written;
        v
    }

    /// Appends `item`.
    ///
    /// # Panics
    ///
    /// When the vector is full (its capacity is a bound the caller proves).
    pub(crate) fn push(&mut self, item: T) {
        assert!(self.len < self.capacity, "HugeVec is full");
        // SAFETY: `len < capacity`, so the slot lies in the allocation.
        unsafe { self.ptr.as_ptr().add(self.len).write(item) };
        self.len += 1;
    }

    /// The bytes the items occupy, in whole huge pages when the vector has
    /// its own: what it adds to the process's resident memory once written.
    pub(crate) fn memory_bytes(&self) -> usize {
        let bytes = self.len * size_of::<T>();
        if self.layout.align() == HUGE {
            bytes.next_multiple_of(HUGE)
        } else {
            bytes
        }
    }

    /// Asks the system to move the items onto huge pages now, when the
    /// vector has memory of its own (a no-op for pages already there: memory
    /// the allocator mapped afresh faulted in as huge pages; reused memory
    /// may not have). Only the huge pages holding items are asked for.
    pub(crate) fn collapse(&self) {
        if self.layout.align() == HUGE && self.len > 0 {
            let len = self.memory_bytes();
            advise(self.ptr.as_ptr() as usize, len, Advice::Collapse);
        }
    }

    /// The uninitialised slots after the items.
    fn spare(&mut self) -> &mut [MaybeUninit<T>] {
        // SAFETY: the slots `len .. capacity` lie in the allocation and are
        // borrowed mutably through `self`; `MaybeUninit` needs no
        // initialisation.
        unsafe {
            std::slice::from_raw_parts_mut(
                self.ptr.as_ptr().add(self.len).cast::<MaybeUninit<T>>(),
                self.capacity - self.len,
            )
        }
    }
}

impl<T: Copy> Drop for HugeVec<T> {
    fn drop(&mut self) {
        if self.layout.size() != 0 {
            // SAFETY: `ptr` was allocated with `layout` (the invariant); the
            // items are `Copy` and need no drop.
            unsafe { dealloc(self.ptr.as_ptr().cast(), self.layout) };
        }
    }
}

impl<T: Copy> Deref for HugeVec<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        // SAFETY: `ptr[..len]` are initialised (the invariant).
        unsafe { std::slice::from_raw_parts(self.ptr.as_ptr(), self.len) }
    }
}

impl<T: Copy> DerefMut for HugeVec<T> {
    fn deref_mut(&mut self) -> &mut [T] {
        // SAFETY: `ptr[..len]` are initialised (the invariant) and borrowed
        // mutably through `self`.
        unsafe { std::slice::from_raw_parts_mut(self.ptr.as_ptr(), self.len) }
    }
}

impl<T: Copy> Clone for HugeVec<T> {
    fn clone(&self) -> HugeVec<T> {
        let mut v = HugeVec::with_capacity(self.len);
        for &item in self.iter() {
            v.push(item);
        }
        v
    }
}

impl<T: Copy + std::fmt::Debug> std::fmt::Debug for HugeVec<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Asks the system to move the 2 MiB-aligned part of `items` onto huge
/// pages now (for arrays that are not [`HugeVec`]s; a no-op for parts
/// already there; ignored where unsupported).
pub(crate) fn collapse_into_huge_pages<T>(items: &[T]) {
    for_aligned_part(
        items.as_ptr() as usize,
        std::mem::size_of_val(items),
        |at, len| {
            advise(at, len, Advice::HugePages);
            advise(at, len, Advice::Collapse);
        },
    );
}

/// Calls `f` with the 2 MiB-aligned part of the `len` bytes at `start`,
/// if there is one.
fn for_aligned_part(start: usize, len: usize, f: impl FnOnce(usize, usize)) {
    let (lo, hi) = (start.next_multiple_of(HUGE), (start + len) / HUGE * HUGE);
    if hi > lo {
        f(lo, hi - lo);
    }
}

/// The advices given.
#[derive(Clone, Copy)]
enum Advice {
    /// `MADV_HUGEPAGE`: back the range with huge pages from now on.
    HugePages,
    /// `MADV_COLLAPSE`: move what the range holds onto huge pages now.
    Collapse,
}

#[cfg(target_os = "linux")]
fn advise(start: usize, len: usize, advice: Advice) {
    /// `MADV_COLLAPSE` of the Linux user API (not in every libc binding).
    const MADV_COLLAPSE: libc::c_int = 25;
    let advice = match advice {
        Advice::HugePages => libc::MADV_HUGEPAGE,
        Advice::Collapse => MADV_COLLAPSE,
    };
    // SAFETY: `start .. start + len` is page-aligned and lies inside a live
    // allocation of the caller; both advices change how the range is
    // backed, never what it holds. A refusal (an old kernel, huge pages
    // disabled) leaves the range as it was, so the result is not needed.
    unsafe { libc::madvise(start as *mut libc::c_void, len, advice) };
}

#[cfg(not(target_os = "linux"))]
fn advise(_: usize, _: usize, _: Advice) {}

#[cfg(test)]
mod tests {
    use super::*;

    /// Items survive every way of making, growing, cloning and advising a
    /// vector, small and huge (past several huge pages, not a multiple of
    /// one), and a huge one's memory starts on a huge-page boundary.
    #[test]
    fn huge_vectors_hold_their_items() {
        for n in [0usize, 1, 1000, HUGE_ARRAY_BYTES / 8, 3_000_000] {
            let item = |i: usize| i as u64 * 7 + 3;
            let made = HugeVec::from_par_iter((0..n).into_par_iter().map(item));
            let mut pushed = HugeVec::with_capacity(n);
            for i in 0..n {
                pushed.push(item(i));
            }
            made.collapse();
            let cloned = made.clone();
            for v in [&made, &pushed, &cloned] {
                assert_eq!(v.len(), n);
                assert!(v.iter().enumerate().all(|(i, &x)| x == item(i)));
            }
            let bytes = n * 8;
            if cfg!(target_os = "linux") && bytes >= HUGE_ARRAY_BYTES {
                assert_eq!(made.as_ptr() as usize % HUGE, 0);
                assert_eq!(made.memory_bytes(), bytes.next_multiple_of(HUGE));
            } else {
                assert_eq!(made.memory_bytes(), bytes);
            }
        }
    }

    #[test]
    #[should_panic(expected = "HugeVec is full")]
    fn a_full_vector_refuses_more() {
        let mut v = HugeVec::with_capacity(1);
        v.push(1u8);
        v.push(2u8);
    }

    #[test]
    fn collapsing_changes_no_contents() {
        let v: Vec<u64> = (0..3_000_000).map(|i| i * 7 + 3).collect();
        collapse_into_huge_pages(&v);
        assert!(v.iter().enumerate().all(|(i, &x)| x == i as u64 * 7 + 3));
    }
}
