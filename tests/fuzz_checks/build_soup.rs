//! The `build_soup` check: bytes → a small polygon soup →
//! `Solid::try_from_soup` → consistency check and measures, and the soup's
//! winding number (`SoupWinding`), which must answer as the solid's accel
//! where the soup builds. Any panic is a bug: bad soups must give a
//! `BuildError`.
//!
//! Bytes decode into a small soup: the first byte is the vertex count (mod
//! 24, plus one); then three bytes per vertex, each a coordinate on a coarse
//! integer grid `−2..=2` (so that coincident and collinear vertices are
//! common) or, for the bytes 250–253, NaN, +∞, 1e300 and 1e−300; then
//! polygons, each a length byte (mod 7) followed by that many vertex indices
//! (mod count + 1, so sometimes out of range).

use wingedge::glam::DVec3;
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::query::{Accel, Method, SoupWinding};

/// Runs the check on one input.
pub fn run(data: &[u8]) {
    let Some((&count, rest)) = data.split_first() else {
        return;
    };
    let count = usize::from(count % 24) + 1;
    if rest.len() < count * 3 {
        return;
    }
    let (coords, mut rest) = rest.split_at(count * 3);
    let positions: Vec<DVec3> = coords
        .chunks_exact(3)
        .map(|c| {
            let f = |b: u8| match b {
                250 => f64::NAN,
                251 => f64::INFINITY,
                252 => 1e300,
                253 => 1e-300,
                _ => f64::from(b % 5) - 2.0,
            };
            DVec3::new(f(c[0]), f(c[1]), f(c[2]))
        })
        .collect();
    let mut polygons: Vec<Vec<usize>> = Vec::new();
    while let Some((&len, tail)) = rest.split_first() {
        let len = usize::from(len % 7);
        if tail.len() < len {
            break;
        }
        let (indices, tail) = tail.split_at(len);
        polygons.push(
            indices
                .iter()
                .map(|&i| usize::from(i) % (count + 1))
                .collect(),
        );
        rest = tail;
    }
    let soup = PolygonSoup::new(positions, polygons);
    // The winding number of the soup: refused only for bad numbers, which
    // the build refuses too; on a soup that builds, the same answers as
    // the solid's accel.
    let probes = [
        DVec3::ZERO,
        DVec3::new(0.5, 0.25, 0.125),
        DVec3::splat(-1.5),
    ];
    let winding = SoupWinding::try_new(&soup);
    let built = Solid::try_from_soup(&soup);
    match (&winding, &built) {
        (Ok(w), Ok(solid)) => {
            let accel = Accel::new(solid);
            for p in probes {
                assert_eq!(
                    w.classify(p).ok(),
                    accel.classify_with(p, Method::Winding).ok(),
                    "{p}"
                );
            }
        }
        (Ok(w), Err(_)) => {
            for p in probes {
                let _ = (w.classify(p), w.winding_number(p));
            }
        }
        (Err(e), Ok(_)) => panic!("the soup builds but its winding number is refused: {e}"),
        (Err(_), Err(_)) => {}
    }
    if let Ok(solid) = built {
        solid
            .check_consistency()
            .expect("a built solid is consistent");
        let _ = (
            solid.volume(),
            solid.surface_area(),
            solid.centroid(),
            solid.shells(),
        );
        for (v, _) in solid.vertices() {
            let _ = solid.vertex_faces(v).count();
        }
        for (f, _) in solid.faces() {
            let _ = (solid.face_side(f, DVec3::ZERO), solid.face_area(f));
        }
    }
}
