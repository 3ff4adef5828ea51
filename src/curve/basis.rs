//! B-spline basis functions by the Cox–de Boor recursion (de Boor 1972,
//! Cox 1972).
//!
//! With knots `t_i` and order `k` (degree `k − 1`):
//!
//! ```text
//! N_{i,1}(t) = 1 if t_i ≤ t < t_{i+1}, else 0
//! N_{i,k}(t) = (t − t_i) / (t_{i+k−1} − t_i) · N_{i,k−1}(t)
//!            + (t_{i+k} − t) / (t_{i+k} − t_{i+1}) · N_{i+1,k−1}(t)
//! ```
//!
//! A term whose denominator is zero (a repeated knot) is taken as zero: the
//! `N` it multiplies is zero on the empty interval, so the convention is
//! `0/0 = 0`.

use super::{CurveError, KnotVector};

/// `N_{i,k}(t)`, the B-spline basis function of order `k` (degree `k − 1`)
/// starting at knot `i` (0-based), by the Cox–de Boor recursion.
///
/// The intervals are half-open, `[t_i, t_{i+1})`, so every basis function is
/// zero at the last knot; curve evaluation takes the left limit there.
///
/// # Errors
///
/// [`CurveError::BasisIndex`] when `k = 0` or knot `i + k` does not exist.
pub fn basis(knots: &KnotVector, i: usize, order: usize, t: f64) -> Result<f64, CurveError> {
    let values = knots.values();
    let bad = CurveError::BasisIndex {
        index: i,
        order,
        knots: values.len(),
    };
    if order == 0 {
        return Err(bad);
    }
    match i.checked_add(order) {
        Some(last) if last < values.len() => {}
        _ => return Err(bad),
    }
    // Order 1 for i..i+k, then each pass raises the order by one in place.
    let mut n: Vec<f64> = (i..i + order)
        .map(|j| {
            if values[j] <= t && t < values[j + 1] {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    for k in 2..=order {
        for j in 0..=order - k {
            let at = i + j;
            let left = ratio(t - values[at], values[at + k - 1] - values[at]) * n[j];
            let right = ratio(values[at + k] - t, values[at + k] - values[at + 1]) * n[j + 1];
            n[j] = left + right;
        }
    }
    Ok(n[0])
}

/// `numerator / denominator`, or 0 when the denominator is zero (two equal
/// knots: the Cox–de Boor `0/0 = 0` convention).
pub(crate) fn ratio(numerator: f64, denominator: f64) -> f64 {
    if denominator == 0.0 {
        0.0
    } else {
        numerator / denominator
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_hat_functions() {
        let k = KnotVector::try_new(vec![0., 1., 2., 3.], 1).unwrap();
        assert_eq!(basis(&k, 0, 2, 0.5).unwrap(), 0.5);
        assert_eq!(basis(&k, 0, 2, 1.0).unwrap(), 1.0);
        assert_eq!(basis(&k, 0, 2, 1.5).unwrap(), 0.5);
        assert_eq!(basis(&k, 0, 2, 2.0).unwrap(), 0.0);
        assert_eq!(basis(&k, 2, 1, 2.5).unwrap(), 1.0);
        assert!(matches!(
            basis(&k, 2, 2, 0.0),
            Err(CurveError::BasisIndex { index: 2, .. })
        ));
        assert!(basis(&k, 0, 0, 0.0).is_err());
        assert!(basis(&k, usize::MAX, 2, 0.0).is_err());
    }

    #[test]
    fn repeated_knots_give_zero_not_nan() {
        let k = KnotVector::try_new(vec![0., 0., 0., 1., 1., 1.], 2).unwrap();
        for t in [0.0, 0.25, 0.5, 0.999] {
            let sum: f64 = (0..3).map(|i| basis(&k, i, 3, t).unwrap()).sum();
            assert!((sum - 1.0).abs() < 1e-15, "{t}: {sum}");
            assert!(!basis(&k, 2, 1, t).unwrap().is_nan());
        }
    }
}
