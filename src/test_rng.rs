//! The seeded generator of the tests and benchmarks: xorshift64, uniform in
//! `[0, 1)`. Reproducible from the seed alone; no statistical quality is
//! claimed. Unit tests reach it as `crate::test_rng`; integration tests and
//! benchmarks include this file by path.

/// A uniform `[0, 1)` generator started from `seed` (non-zero).
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}
