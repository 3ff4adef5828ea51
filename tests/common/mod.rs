//! The helpers both test crates share: `tests/it/` (the library's
//! integration tests) and `tests/cli/` (the command line's) each include
//! this folder once, as `crate::common`.
//!
//! - [`test_rng`]: the seeded generator, `src/test_rng.rs` (the library's
//!   unit tests use the same file as `crate::test_rng`);
//! - [`mapped_soup`] and [`mapped_solid`]: a soup under any map of points, a
//!   solid under an affine map;
//! - [`oracle`]: the python3 manifold3d oracle of `tests/oracle/`;
//! - [`regressions_beside_source`]: proptest's failing seeds kept and
//!   replayed beside each test file;
//! - [`boolean_cases`]: near-degenerate boolean cases (the stress test's
//!   and the `boolean_stress` driver's);
//! - [`fixtures`]: closed solids with hard features for the query tests;
//! - [`rational_parity`]: an exact point-in-polyhedron reference that
//!   shares no code with the crate;
//! - [`temp_dir`]: scratch folders that remove themselves;
//! - [`cli`] (with the `cli` feature, which builds the binary): running
//!   `wingedge`.

// Each crate uses only some of the helpers.
#![allow(dead_code)]

pub mod boolean_cases;
#[cfg(feature = "cli")]
pub mod cli;
pub mod fixtures;
pub mod oracle;
pub mod rational_parity;
pub mod temp_dir;
#[path = "../../src/test_rng.rs"]
pub mod test_rng;

use glam::{DAffine3, DVec3};
use proptest::test_runner::{Config as ProptestConfig, FileFailurePersistence};
use wingedge::mesh::{PolygonSoup, Solid};

/// `soup` with every position mapped by `f`.
pub fn mapped_soup(soup: &PolygonSoup, f: impl Fn(DVec3) -> DVec3) -> PolygonSoup {
    let mut s = soup.clone();
    for p in &mut s.positions {
        *p = f(*p);
    }
    s
}

/// `solid` under the affine map `map`, built again from its mapped soup.
///
/// # Panics
///
/// If the mapped soup is not a solid.
pub fn mapped_solid(solid: &Solid, map: DAffine3) -> Solid {
    let soup = mapped_soup(&solid.to_soup(), |p| map.transform_point3(p));
    Solid::try_from_soup(&soup).expect("a solid")
}

/// `config` with failing seeds persisted beside the test's source file, as
/// `<file stem>.proptest-regressions`, and every seed there replayed first.
///
/// proptest's default (`SourceParallel`) looks upwards for a `main.rs` and
/// would use `tests/proptest-regressions/<module path>.txt`, away from the
/// module the seeds belong to.
pub fn regressions_beside_source(config: ProptestConfig) -> ProptestConfig {
    ProptestConfig {
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..config
    }
}
