//! Numbers in messages: plain decimals for ordinary magnitudes, scientific
//! notation for huge and tiny ones (so `1e300` is not printed as 301
//! digits), always the shortest form that reads back to the same `f64`.

use std::fmt;

use glam::DVec3;

/// An `f64` as a message shows it: `0.25`, `-3`, `1e300`, `5e-324`, `NaN`,
/// `inf`. Plain decimals for `1e-5 ≤ |x| < 1e16` (and zero), scientific
/// notation otherwise; both round-trip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Readable(pub f64);

impl fmt::Display for Readable {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        if !x.is_finite() || x == 0.0 || (1e-5..1e16).contains(&magnitude) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// A point or vector as a message shows it: `(x, y, z)` with each
/// coordinate [`Readable`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReadableVec(pub DVec3);

impl fmt::Display for ReadableVec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        write!(
            f,
            "({}, {}, {})",
            Readable(v.x),
            Readable(v.y),
            Readable(v.z)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordinary_numbers_are_plain_and_extreme_ones_scientific() {
        let shown = |x: f64| Readable(x).to_string();
        assert_eq!(shown(0.25), "0.25");
        assert_eq!(shown(-3.0), "-3");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(-f64::MAX), "-1.7976931348623157e308");
        assert_eq!(shown(5e-324), "5e-324");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(f64::INFINITY), "inf");
        for x in [1e300, 5e-324, 1.2345e-7, 123456.789, 1e16] {
            assert_eq!(shown(x).parse::<f64>().unwrap(), x);
        }
        assert_eq!(
            ReadableVec(DVec3::new(1e300, 0.5, -1e-9)).to_string(),
            "(1e300, 0.5, -1e-9)"
        );
    }
}
