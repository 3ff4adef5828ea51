//! Knot vectors: non-decreasing parameter values that split a B-spline's
//! domain into polynomial spans.

use super::CurveError;

/// A validated knot vector `t_0 ≤ t_1 ≤ … ≤ t_{m−1}` for curves of one
/// degree `p`, serving `n = m − p − 1` control points.
///
/// # Invariants
///
/// - every knot is finite and the sequence never decreases;
/// - `m ≥ 2 (p + 1)`, so that there are at least `p + 1` control points;
/// - no value is repeated more than `p + 1` times;
/// - the domain `[t_p, t_n]` has positive length.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    values: Vec<f64>,
    degree: usize,
}

/// Which one-sided limit to take at a knot, where a curve may switch from
/// one polynomial piece to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Approach {
    /// From below: the piece that ends at the parameter.
    FromBelow,
    /// From above: the piece that starts at the parameter (the usual
    /// convention, `t_i ≤ t < t_{i+1}`).
    FromAbove,
}

impl KnotVector {
    /// Validates `values` as knots for curves of degree `degree`.
    ///
    /// # Errors
    ///
    /// [`CurveError::NonFiniteKnot`], [`CurveError::DecreasingKnots`],
    /// [`CurveError::TooFewKnots`], [`CurveError::KnotMultiplicity`],
    /// [`CurveError::EmptyDomain`].
    pub fn try_new(values: Vec<f64>, degree: usize) -> Result<KnotVector, CurveError> {
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(CurveError::NonFiniteKnot { index, value });
        }
        if let Some(index) = (1..values.len()).find(|&i| values[i] < values[i - 1]) {
            return Err(CurveError::DecreasingKnots {
                index,
                previous: values[index - 1],
                next: values[index],
            });
        }
        let needed = degree
            .checked_add(1)
            .and_then(|o| o.checked_mul(2))
            .unwrap_or(usize::MAX);
        if values.len() < needed {
            return Err(CurveError::TooFewKnots {
                count: values.len(),
                degree,
                needed,
            });
        }
        let mut start = 0;
        while start < values.len() {
            let run = values[start..]
                .iter()
                .take_while(|&&v| v == values[start])
                .count();
            if run > degree + 1 {
                return Err(CurveError::KnotMultiplicity {
                    index: start,
                    value: values[start],
                    multiplicity: run,
                    degree,
                });
            }
            start += run;
        }
        let n = values.len() - degree - 1;
        if values[degree] >= values[n] {
            return Err(CurveError::EmptyDomain {
                start: values[degree],
                end: values[n],
            });
        }
        Ok(KnotVector { values, degree })
    }

    /// The uniform knot vector `0, 1, …, n + p` for `n` control points of
    /// degree `p`: every basis function is a shifted copy of one, and the
    /// domain is `[p, n]`.
    ///
    /// # Errors
    ///
    /// [`CurveError::TooFewKnots`] when `n < p + 1`.
    pub fn try_uniform(control_points: usize, degree: usize) -> Result<KnotVector, CurveError> {
        let count = control_points.saturating_add(degree).saturating_add(1);
        if control_points < degree.saturating_add(1) {
            return Err(CurveError::TooFewKnots {
                count,
                degree,
                needed: degree.saturating_add(1).saturating_mul(2),
            });
        }
        KnotVector::try_new((0..count).map(|i| i as f64).collect(), degree)
    }

    /// The open uniform (clamped) knot vector for `n` control points of
    /// degree `p`: `p + 1` zeros, `1, 2, …, n − p − 1`, then `p + 1` copies
    /// of `n − p`. The curve starts at the first control point and ends at
    /// the last.
    ///
    /// # Errors
    ///
    /// [`CurveError::TooFewKnots`] when `n < p + 1`.
    pub fn try_open_uniform(
        control_points: usize,
        degree: usize,
    ) -> Result<KnotVector, CurveError> {
        if control_points < degree.saturating_add(1) {
            return Err(CurveError::TooFewKnots {
                count: control_points.saturating_add(degree).saturating_add(1),
                degree,
                needed: degree.saturating_add(1).saturating_mul(2),
            });
        }
        let last = (control_points - degree) as f64;
        let mut values = vec![0.0; degree + 1];
        values.extend((1..control_points - degree).map(|i| i as f64));
        values.extend(std::iter::repeat_n(last, degree + 1));
        KnotVector::try_new(values, degree)
    }

    /// The degree `p` the knots serve.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots.
    #[must_use]
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The number of control points the knots serve, `m − p − 1`.
    #[must_use]
    pub fn control_point_count(&self) -> usize {
        self.values.len() - self.degree - 1
    }

    /// The parameter domain `[t_p, t_n]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (
            self.values[self.degree],
            self.values[self.control_point_count()],
        )
    }

    /// Whether `t` lies in the domain (false for NaN).
    #[must_use]
    pub fn contains(&self, t: f64) -> bool {
        let (start, end) = self.domain();
        start <= t && t <= end
    }

    /// `Ok(())` when `t` lies in the domain.
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] otherwise (NaN included).
    pub fn check_parameter(&self, t: f64) -> Result<(), CurveError> {
        if self.contains(t) {
            Ok(())
        } else {
            let (start, end) = self.domain();
            Err(CurveError::ParameterOutOfDomain { t, start, end })
        }
    }

    /// How many knots equal `value`.
    #[must_use]
    pub fn multiplicity(&self, value: f64) -> usize {
        self.values.iter().filter(|&&v| v == value).count()
    }

    /// The span `s` (with `p ≤ s < n` and `t_s < t_{s+1}`) whose polynomial
    /// piece gives the curve at `t` from the given side. From above it is
    /// the `s` with `t_s ≤ t < t_{s+1}`, except at the end of the domain,
    /// where the last non-empty span is used; from below it is the `s` with
    /// `t_s < t ≤ t_{s+1}`, except at the start of the domain.
    ///
    /// `t` must lie in the domain (see [`KnotVector::contains`]); outside it
    /// the nearest end span is returned.
    #[must_use]
    pub fn span(&self, t: f64, approach: Approach) -> usize {
        let p = self.degree;
        let last = self.control_point_count() - 1;
        let v = &self.values;
        match approach {
            Approach::FromAbove => {
                let after = v.partition_point(|&k| k <= t);
                let mut s = after.saturating_sub(1).clamp(p, last);
                while s > p && v[s] >= v[s + 1] {
                    s -= 1;
                }
                s
            }
            Approach::FromBelow => {
                let after = v.partition_point(|&k| k < t);
                let mut s = after.saturating_sub(1).clamp(p, last);
                while s < last && v[s] >= v[s + 1] {
                    s += 1;
                }
                s
            }
        }
    }

    /// The distinct knot values inside the domain, its ends included, in
    /// increasing order: the breakpoints between polynomial pieces.
    #[must_use]
    pub fn breakpoints(&self) -> Vec<f64> {
        let (start, end) = self.domain();
        let mut points: Vec<f64> = self
            .values
            .iter()
            .copied()
            .filter(|&v| start <= v && v <= end)
            .collect();
        points.dedup();
        points
    }

    /// The knots with `u` inserted once (kept sorted; same degree). The
    /// caller checks that `u` is in the domain and that its multiplicity
    /// stays at most `p + 1`.
    pub(crate) fn inserted(&self, u: f64) -> KnotVector {
        let at = self.values.partition_point(|&k| k <= u);
        let mut values = self.values.clone();
        values.insert(at, u);
        KnotVector {
            values,
            degree: self.degree,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_knot_vectors_are_named() {
        assert_eq!(
            KnotVector::try_new(vec![0., 0., 1., 0.5, 2., 2.], 1),
            Err(CurveError::DecreasingKnots {
                index: 3,
                previous: 1.0,
                next: 0.5
            })
        );
        assert!(matches!(
            KnotVector::try_new(vec![0., 1., 2., 3., 4.], 2),
            Err(CurveError::TooFewKnots {
                count: 5,
                degree: 2,
                needed: 6
            })
        ));
        assert!(matches!(
            KnotVector::try_new(vec![0., 1., f64::NAN, 3.], 1),
            Err(CurveError::NonFiniteKnot { index: 2, .. })
        ));
        assert!(matches!(
            KnotVector::try_new(vec![0., 1., 1., 1., 2., 3.], 1),
            Err(CurveError::KnotMultiplicity {
                index: 1,
                multiplicity: 3,
                ..
            })
        ));
        assert!(matches!(
            KnotVector::try_new(vec![0., 1., 1., 2.], 1),
            Err(CurveError::EmptyDomain {
                start: 1.0,
                end: 1.0
            })
        ));
        assert!(KnotVector::try_new(vec![0.; 4], usize::MAX).is_err());
        assert!(KnotVector::try_uniform(3, usize::MAX).is_err());
        assert!(KnotVector::try_open_uniform(3, usize::MAX).is_err());
    }

    #[test]
    fn standard_vectors_and_their_domains() {
        let u = KnotVector::try_uniform(4, 3).unwrap();
        assert_eq!(u.values(), &[0., 1., 2., 3., 4., 5., 6., 7.]);
        assert_eq!(u.domain(), (3.0, 4.0));
        let o = KnotVector::try_open_uniform(5, 2).unwrap();
        assert_eq!(o.values(), &[0., 0., 0., 1., 2., 3., 3., 3.]);
        assert_eq!(o.domain(), (0.0, 3.0));
        assert_eq!(o.control_point_count(), 5);
        assert_eq!(o.breakpoints(), vec![0., 1., 2., 3.]);
        assert!(KnotVector::try_open_uniform(2, 2).is_err());
    }

    #[test]
    fn spans_from_either_side() {
        let k = KnotVector::try_new(vec![0., 0., 0., 1., 1., 2., 3., 3., 3.], 2).unwrap();
        assert_eq!(k.span(0.0, Approach::FromAbove), 2);
        assert_eq!(k.span(0.0, Approach::FromBelow), 2);
        assert_eq!(k.span(0.5, Approach::FromBelow), 2);
        assert_eq!(k.span(1.0, Approach::FromAbove), 4);
        assert_eq!(k.span(1.0, Approach::FromBelow), 2);
        assert_eq!(k.span(3.0, Approach::FromAbove), 5);
        assert_eq!(k.span(3.0, Approach::FromBelow), 5);
        assert_eq!(k.multiplicity(1.0), 2);
    }
}
