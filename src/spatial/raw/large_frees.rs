//! Large arrays given back to the system when they are freed.
//!
//! glibc's allocator maps an allocation of at least its *mmap threshold*
//! (128 KiB to start with) on its own and unmaps it when it is freed. But
//! the threshold is dynamic: each time such an array is freed, the
//! threshold rises to the array's size (up to 32 MiB). After the first
//! large temporary of a run (a file's bytes, a tree's build tables) is
//! freed, later ones of that size are carved out of the heap or a thread's
//! arena instead, and what is freed there mostly stays resident. A run
//! made of stages that each build and drop tables of tens of megabytes
//! (validation: the file, the soup, the checks' context, the
//! self-intersection check's trees, the build's half-edges) then holds
//! the sum of its stages' peaks rather than the largest of them: on two
//! crossing spheres of 180,000 triangles, 112 MB resident for a heap that
//! never held more than 87 MB.
//!
//! Fixing the threshold turns the adjustment off, so every array of
//! 128 KiB or more keeps memory of its own and returns it when freed.

/// The allocations that get memory of their own: 128 KiB and up (glibc's
/// own starting threshold).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const THRESHOLD: libc::c_int = 128 << 10;

/// Makes every allocation of 128 KiB or more memory of its own, given
/// back to the system when it is freed (see the module documentation), for
/// the rest of the process. Where the C library is not glibc, nothing
/// changes. Only where the allocator is placed changes, never what a
/// program computes; the command line calls it first thing.
pub fn return_large_frees_to_the_system() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: `mallopt` only sets a parameter of the allocator, which
    // glibc reads under its own lock; M_MMAP_THRESHOLD accepts any value
    // up to 32 MiB.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, THRESHOLD);
    }
}
