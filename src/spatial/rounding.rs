//! Directed rounding between `f64` and `f32`: the steps that keep stored
//! `f32` bounds conservative (a lower bound never above the exact value, an
//! upper bound never below it).

/// The largest `f32` not above `x` (`x` itself when representable; `−∞`
/// below the `f32` range only for `x = −∞`).
#[must_use]
pub(crate) fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f32_below(f) } else { f }
}

/// The next `f32` below `f` (`f` itself for `−∞` and NaN; below `±0` the
/// smallest negative subnormal). `f32::next_down` is newer than the crate's
/// minimum Rust.
#[must_use]
pub(crate) fn f32_below(f: f32) -> f32 {
    if f.is_nan() || f == f32::NEG_INFINITY {
        return f;
    }
    if f == 0.0 {
        return -f32::from_bits(1);
    }
    let bits = f.to_bits();
    f32::from_bits(if f > 0.0 { bits - 1 } else { bits + 1 })
}

/// The next `f64` below `x` (as [`f32_below`]).
#[must_use]
pub(crate) fn f64_below(x: f64) -> f64 {
    if x.is_nan() || x == f64::NEG_INFINITY {
        return x;
    }
    if x == 0.0 {
        return -f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits - 1 } else { bits + 1 })
}

/// The next `f64` above `x`.
#[must_use]
pub(crate) fn f64_above(x: f64) -> f64 {
    -f64_below(-x)
}

/// The smallest `f32` not below `x`.
#[must_use]
pub(crate) fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { -f32_below(-f) } else { f }
}
