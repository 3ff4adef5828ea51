//! Compressed rows: values grouped by a dense key by counting sort.

/// For each key in `0..n`, the values paired with it, in the order given:
/// row `k` is `values[offsets[k]..offsets[k + 1]]`. `pairs` is walked
/// twice (once to count, once to place); every key must be below `n`.
pub(crate) fn compressed_rows<V: Copy + Default>(
    n: usize,
    pairs: impl Iterator<Item = (usize, V)> + Clone,
) -> (Vec<usize>, Vec<V>) {
    let mut offsets = vec![0usize; n + 1];
    for (k, _) in pairs.clone() {
        offsets[k + 1] += 1;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut values = vec![V::default(); offsets[n]];
    for (k, v) in pairs {
        values[fill[k]] = v;
        fill[k] += 1;
    }
    (offsets, values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_keep_the_order_given() {
        let pairs = [(2, 'a'), (0, 'b'), (2, 'c'), (0, 'd')];
        let (offsets, values) = compressed_rows(4, pairs.iter().copied());
        assert_eq!(offsets, [0, 2, 2, 4, 4]);
        assert_eq!(values, ['b', 'd', 'a', 'c']);
    }
}
