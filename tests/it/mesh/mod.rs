//! Making solids: builders, Euler operators, the winged-edge invariants,
//! building from soups, and solids from curves (the B-spline basis, sweeps,
//! revolves and lofts).

mod builders;
mod curve_basis;
mod euler_builders;
mod euler_ops;
mod soup_build;
mod sweeps;
mod topology_props;
