//! Solids from curves: a profile swept along a path with rotation-minimizing
//! frames ([`try_sweep`], [`try_sweep_with_holes`]), revolved about an axis
//! ([`try_revolve`], [`try_revolve_curve`]) or lofted through sections
//! ([`try_loft`]).
//!
//! This layer sits above [`mesh`](crate::mesh) and [`curve`](crate::curve):
//! it flattens curves to a chord tolerance, builds the sections' polygon
//! soup, refuses a profile or path that would fold, and builds the solid
//! through the mesh layer, so every solid it returns is closed, oriented and
//! consistent.

mod loft;
mod revolve;
mod sweep;

pub use loft::try_loft;
pub use revolve::{
    MAX_TURN_SLIVERS, MAX_TURN_STEPS, RevolveAxis, Segments, try_revolve, try_revolve_curve,
};
pub use sweep::{Argument, MAX_VERTICES, SolidPart, SweepError, try_sweep, try_sweep_with_holes};
