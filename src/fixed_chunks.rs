//! Parallel work over fixed chunks, for results that must not depend on
//! the number of threads.
//!
//! A rayon `sum` or `reduce` of floating-point numbers adds them in an
//! order set by how the work was split, which depends on the thread count
//! and on work stealing; the last bits of the result then change from run
//! to run. Here the input is cut into chunks of a fixed size, each chunk is
//! reduced in order on whichever thread takes it, and the caller combines
//! the chunk results in chunk order: the additions happen in one order
//! whatever the threads, so results are bit-identical.

use std::ops::Range;

use rayon::prelude::*;

/// Items per chunk: large enough that a chunk outweighs the cost of a task.
pub(crate) const CHUNK: usize = 4096;

/// `per_chunk` applied to `0..n` cut into [`CHUNK`]-sized ranges, in
/// parallel; the results in range order.
pub(crate) fn map_chunks<T: Send>(
    n: usize,
    per_chunk: impl Fn(Range<usize>) -> T + Sync + Send,
) -> Vec<T> {
    (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| per_chunk(c * CHUNK..((c + 1) * CHUNK).min(n)))
        .collect()
}

/// The sum of `term(i)` over `0..n`, in parallel, with the same bits for
/// any number of threads.
pub(crate) fn sum(n: usize, term: impl Fn(usize) -> f64 + Sync + Send) -> f64 {
    map_chunks(n, |range| range.map(&term).sum::<f64>())
        .into_iter()
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_do_not_depend_on_the_thread_count() {
        // Terms whose sum rounds differently in different orders.
        let term = |i: usize| 1.0 / (1.0 + i as f64) * if i.is_multiple_of(3) { 1e8 } else { 1e-8 };
        let n = 20 * CHUNK + 17;
        let sequential = (0..n.div_ceil(CHUNK))
            .map(|c| (c * CHUNK..((c + 1) * CHUNK).min(n)).map(term).sum::<f64>())
            .sum::<f64>();
        for threads in [1, 2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let parallel = pool.install(|| sum(n, term));
            assert_eq!(
                parallel.to_bits(),
                sequential.to_bits(),
                "{threads} threads"
            );
        }
        assert_eq!(map_chunks(0, |r| r.len()), Vec::<usize>::new());
        assert_eq!(map_chunks(CHUNK + 1, |r| r.len()), vec![CHUNK, 1]);
    }
}
