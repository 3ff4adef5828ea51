//! The ring operations that predicates on implicit points are written in,
//! once, for both stages: the interval filter and exact dyadic arithmetic.

use crate::geom::Sign;
use crate::geom::dyadic::Dyadic;

/// Addition, subtraction and multiplication of numbers built from `f64`
/// inputs, and the sign of the result when it is certain.
pub(crate) trait Arithmetic: Clone {
    /// The exact value of a finite `x`.
    fn of(x: f64) -> Self;
    /// `self + other`.
    fn plus(&self, other: &Self) -> Self;
    /// `self − other`.
    fn minus(&self, other: &Self) -> Self;
    /// `self · other`.
    fn times(&self, other: &Self) -> Self;
    /// The sign of the value when it is certain; exact arithmetic always
    /// knows it.
    fn sign(&self) -> Option<Sign>;
}

impl Arithmetic for Dyadic {
    fn of(x: f64) -> Dyadic {
        Dyadic::of(x)
    }

    fn plus(&self, other: &Dyadic) -> Dyadic {
        self + other
    }

    fn minus(&self, other: &Dyadic) -> Dyadic {
        self - other
    }

    fn times(&self, other: &Dyadic) -> Dyadic {
        self * other
    }

    fn sign(&self) -> Option<Sign> {
        Some(Dyadic::sign(self))
    }
}
