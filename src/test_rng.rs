//! The seeded generator of the tests, benchmarks and benchmark drivers:
//! xorshift64 (Marsaglia, "Xorshift RNGs", 2003), as raw 64-bit words or
//! uniform in `[0, 1)`. Reproducible from the seed alone; no statistical
//! quality is claimed. Unit tests reach it as `crate::test_rng`; the
//! integration tests as `crate::common::test_rng` (`tests/common/mod.rs`
//! includes this file once per test crate); benchmarks (`benches/`) and the
//! drivers of `benches/drivers/` include this file by path:
//!
//! ```ignore
//! #[path = "../src/test_rng.rs"]
//! mod test_rng;
//! ```
// Each including target uses only some of the functions.
#![allow(dead_code)]

/// The xorshift64 words started from `seed` (non-zero; a zero seed gives
/// only zeros).
pub(crate) fn bits(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    }
}

/// A uniform `[0, 1)` generator started from `seed` (non-zero): the top 53
/// bits of each word of [`bits`].
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut next = bits(seed);
    move || (next() >> 11) as f64 / (1u64 << 53) as f64
}
