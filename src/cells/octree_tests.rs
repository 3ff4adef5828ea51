//! Tests of `octree.rs`.

use super::*;
use crate::mesh::builders::{cube, icosahedron, l_prism, tetrahedron};

/// The parallel build of a solid's octree gives the sequential build's
/// leaves, in the same order, and the same counts and regions — also
/// where cells are decided above the depth the parallel part starts at.
#[test]
fn the_parallel_build_gives_the_sequential_leaves() {
    for (name, solid) in [
        ("tetrahedron", tetrahedron()),
        ("cube", cube()),
        ("icosahedron", icosahedron()),
        ("L-prism", l_prism()),
    ] {
        for depth in 0..=6 {
            let (origin, side) = root_cube(&solid.bounding_box(), depth).unwrap();
            let target = SolidTarget {
                accel: Accel::new(&solid),
                tiles: BoundaryTiles::try_new(&solid).unwrap(),
            };
            let one = Octree::build(&target, origin, side, depth);
            let all = Octree::build_parallel(&target, origin, side, depth);
            assert_eq!(one.leaves, all.leaves, "{name} at depth {depth}");
            assert_eq!(one.counts, all.counts, "{name} at depth {depth}");
            assert_eq!(one.regions, all.regions, "{name} at depth {depth}");
            let (low, high) = all.try_volume_bounds().unwrap();
            let v = solid.volume();
            assert!(
                low <= v && v <= high,
                "{name} at depth {depth}: {v} not in [{low}, {high}]"
            );
        }
    }
}

/// A certified interval is finite and holds the volume, or there is
/// none: a cube of side 2^1001 (volume 2^3003) overflows and one of
/// side 2^-344 (volume 2^-1032) underflows, each refused by name where
/// an audit found `[NaN, inf]` and `[0, 0]` called certified.
#[test]
fn a_volume_interval_out_of_f64_is_refused() {
    let scaled = |k: i32| {
        let mut soup = cube().to_soup();
        for p in &mut soup.positions {
            *p *= 2f64.powi(k);
        }
        Octree::classify(&Solid::try_from_soup(&soup).unwrap(), 3)
    };
    for k in [1000, -345] {
        let e = scaled(k).unwrap().try_volume_bounds().unwrap_err();
        assert!(matches!(e, CellsError::VolumeOutOfRange { .. }), "{e}");
        let words = if k > 0 { "overflow" } else { "underflow" };
        assert!(e.to_string().ends_with(words), "{e}");
    }
    for k in [300, -300] {
        let tree = scaled(k).unwrap();
        let (low, high) = tree.try_volume_bounds().unwrap();
        let v = 8.0 * 2f64.powi(3 * k);
        assert!(
            low.is_finite() && high.is_finite() && low <= v && v <= high,
            "{k}"
        );
    }
}
