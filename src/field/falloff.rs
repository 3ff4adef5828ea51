//! Falloff functions `g(r, R)`: a source's contribution at distance `r`.

/// How a source's influence falls off with distance `r` from its center,
/// for a source of radius `R`.
///
/// Every falloff is 1 at the center, decreases monotonically and is exactly
/// 0 for `r ≥ R`, so a source is felt only inside its ball — which is what
/// lets a field visit only the sources whose radius reaches a sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Falloff {
    /// The soft-object polynomial of Wyvill, McPheeters and Wyvill (1986):
    /// with `s = r / R`,
    /// `g = 1 − (4/9) s⁶ + (17/9) s⁴ − (22/9) s²` for `s < 1`, else 0.
    ///
    /// `g(R/2) = ½` exactly, so a lone unit source is a ball of radius
    /// `R / 2`; `g` and its slope are 0 at `r = R`, so sources blend
    /// smoothly. Needs no square root.
    #[default]
    SoftObject,
    /// A steeper blend: `g = (1 − s²)³` for `s < 1`, else 0 (the cube of a
    /// parabola; Blinn-like near the center, compact like the soft object).
    /// `g = ½` at `s = √(1 − 2^(−1/3)) ≈ 0.4537`.
    CubicParabola,
}

impl Falloff {
    /// `g` for a squared distance `r²` and squared radius `R²`.
    ///
    /// `r2` must be ≥ 0 and `radius2` > 0.
    #[must_use]
    pub fn value(self, r2: f64, radius2: f64) -> f64 {
        if r2 >= radius2 {
            return 0.0;
        }
        let s2 = r2 / radius2;
        match self {
            Falloff::SoftObject => {
                let s4 = s2 * s2;
                let s6 = s4 * s2;
                1.0 - (4.0 / 9.0) * s6 + (17.0 / 9.0) * s4 - (22.0 / 9.0) * s2
            }
            Falloff::CubicParabola => {
                let u = 1.0 - s2;
                u * u * u
            }
        }
    }

    /// The radius fraction `s = r / R` at which a unit-strength source
    /// reaches ½ (the radius of its ball as a fraction of `R`).
    #[must_use]
    pub fn half_radius_fraction(self) -> f64 {
        match self {
            Falloff::SoftObject => 0.5,
            Falloff::CubicParabola => (1.0 - 0.5f64.cbrt()).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_falloff_is_one_at_the_center_half_at_its_radius_fraction_and_zero_beyond_r() {
        for f in [Falloff::SoftObject, Falloff::CubicParabola] {
            assert_eq!(f.value(0.0, 4.0), 1.0);
            let s = f.half_radius_fraction() * 2.0;
            assert!((f.value(s * s, 4.0) - 0.5).abs() < 1e-12, "{f:?}");
            assert_eq!(f.value(4.0, 4.0), 0.0);
            assert_eq!(f.value(9.0, 4.0), 0.0);
            // Monotone decreasing on [0, R).
            let mut last = 1.0;
            for i in 1..100 {
                let r = 2.0 * f64::from(i) / 100.0;
                let g = f.value(r * r, 4.0);
                assert!(g < last && g >= 0.0, "{f:?} at {r}");
                last = g;
            }
        }
    }
}
