//! Cross-checks against manifold3d, the independent oracle
//! (`tests/oracle/`, run through `common::oracle`).

mod manifold;
mod marching_cubes;
