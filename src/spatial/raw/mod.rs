//! The low-level memory and lane code the spatial structures and their
//! queries share, and the `unsafe` it needs, each with its safety argument:
//!
//! - [`huge_pages`]: vectors whose memory is aligned to and advised onto
//!   2 MiB pages (raw allocation, `madvise`);
//! - [`lanes`]: four `f32` lanes as SSE registers (intrinsics);
//! - [`prefetch`]: requests for memory ahead of its use (a hint that never
//!   faults);
//! - [`large_frees`]: large arrays given back to the system when freed
//!   (`mallopt`).
//!
//! The AVX2 and AVX-512 node openers (`spatial::bvh::open_avx2`,
//! `spatial::bvh::open_avx512`, and `spatial::bvh::open_widest`, which
//! calls them where the processor has them) hold the only other `unsafe`
//! code of the crate: their intrinsics are the node test itself.

pub(crate) mod huge_pages;
pub(crate) mod lanes;
pub(crate) mod large_frees;
pub(crate) mod prefetch;
