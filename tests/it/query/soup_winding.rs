//! The winding number of meshes that cannot be winged-edge solids
//! (`query::SoupWinding`), against the buildable part of the same mesh and
//! against points whose answer is known.

use std::path::Path;

use glam::DVec3;
use wingedge::io::read_obj;
use wingedge::mesh::{BuildError, PolygonSoup, Solid};
use wingedge::query::{Accel, Containment, Method, SoupWinding};

fn soup(path: &str) -> PolygonSoup {
    read_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).expect("fixture reads")
}

/// Points of a grid over `[lo, hi]³` whose coordinates are no round
/// numbers, so that none lies on a face of the fixtures (all at quarter
/// steps).
fn grid(lo: f64, hi: f64, n: usize) -> Vec<DVec3> {
    let step = (hi - lo) / n as f64;
    let at = |i: usize| lo + (i as f64 + 0.381_966) * step;
    (0..n * n * n)
        .map(|i| DVec3::new(at(i % n), at(i / n % n), at(i / (n * n))))
        .collect()
}

/// A cube with a fin on one edge (three faces there) is no solid, and its
/// winding answers are the cube's at every point off the fin: the fin alone
/// adds less than ½ anywhere off its own plane.
#[test]
fn a_fin_changes_no_answer_of_the_cube_it_hangs_on() {
    let fin = soup("fixtures/soups/fin.obj");
    assert!(matches!(
        Solid::try_from_soup(&fin),
        Err(BuildError::NonManifoldEdge { .. })
    ));
    let winding = SoupWinding::try_new(&fin).unwrap();
    // The fin's four edges: the one it shares with the cube's two faces,
    // and its three free ones.
    assert_eq!(winding.open_edges(), 4);
    let mut cube = fin.clone();
    cube.polygons.pop();
    let cube = Accel::new(&Solid::try_from_soup(&cube).unwrap());
    let points = grid(-0.6, 2.4, 24);
    let ours = winding.classify_batch(&points).unwrap();
    assert_eq!(ours, cube.classify_batch(&points, Method::Parity).unwrap());
    assert!(ours.contains(&Containment::Inside) && ours.contains(&Containment::Outside));
    // The fin itself is the surface.
    assert_eq!(
        winding.classify(DVec3::new(1.5, 0.5, -0.5)).unwrap(),
        Containment::OnBoundary
    );
}

/// Two cubes sharing an edge (four faces there): every edge's uses cancel,
/// so the answer is the exact crossing count, boundary points included.
#[test]
fn two_cubes_on_one_edge_are_answered_exactly() {
    let two = soup("fixtures/broken/edge_in_more_than_two_faces.obj");
    assert!(Solid::try_from_soup(&two).is_err());
    let winding = SoupWinding::try_new(&two).unwrap();
    assert_eq!(winding.open_edges(), 0);
    // Quarter steps over [-0.5, 2.5]³: many points on faces, edges and the
    // shared edge itself.
    let steps: Vec<f64> = (0..13).map(|i| -0.5 + 0.25 * i as f64).collect();
    let mut points = Vec::new();
    for &x in &steps {
        for &y in &steps {
            for &z in &steps {
                points.push(DVec3::new(x, y, z));
            }
        }
    }
    let within = |p: DVec3, lo: DVec3, hi: DVec3, strict: bool| {
        (0..3).all(|k| {
            if strict {
                p[k] > lo[k] && p[k] < hi[k]
            } else {
                p[k] >= lo[k] && p[k] <= hi[k]
            }
        })
    };
    let boxes = [
        (DVec3::ZERO, DVec3::ONE),
        (DVec3::new(1.0, 1.0, 0.0), DVec3::new(2.0, 2.0, 1.0)),
    ];
    let answers = winding.classify_batch(&points).unwrap();
    for (&p, &got) in points.iter().zip(&answers) {
        let want = if boxes.iter().any(|&(lo, hi)| within(p, lo, hi, true)) {
            Containment::Inside
        } else if boxes.iter().any(|&(lo, hi)| within(p, lo, hi, false)) {
            Containment::OnBoundary
        } else {
            Containment::Outside
        };
        assert_eq!(got, want, "{p}");
    }
    assert_eq!(
        winding.classify(DVec3::new(1.0, 1.0, 0.5)).unwrap(),
        Containment::OnBoundary
    );
}

/// An icosahedron with two faces wound the wrong way: deep inside and far
/// outside the answers are the mended icosahedron's; next to a flipped
/// face, inside, the flipped face outweighs the rest (the winding number's
/// known limit on such input, documented at `SoupWinding`).
#[test]
fn flipped_faces_keep_the_answers_deep_inside_and_far_outside() {
    let flipped = soup("fixtures/soups/flipped_faces.obj");
    assert!(matches!(
        Solid::try_from_soup(&flipped),
        Err(BuildError::InconsistentOrientation { .. })
    ));
    let winding = SoupWinding::try_new(&flipped).unwrap();
    // Each flipped triangle's three edges are run twice the same way.
    assert_eq!(winding.open_edges(), 6);
    // From the centre each face subtends 1/20 of the sphere: 1 − 2·2/20.
    let centre = winding.winding_number(DVec3::ZERO).unwrap();
    assert!((centre - 0.8).abs() < 1e-12, "{centre}");
    let mut mended = flipped.clone();
    for p in [0, 10] {
        mended.polygons[p].vertices.reverse();
    }
    let mended = Accel::new(&Solid::try_from_soup(&mended).unwrap());
    let points: Vec<DVec3> = grid(-6.0, 6.0, 30)
        .into_iter()
        .filter(|p| p.length() < 0.4 || p.length() > 4.0)
        .collect();
    assert!(points.len() > 1000);
    let ours = winding.classify_batch(&points).unwrap();
    assert_eq!(
        ours,
        mended.classify_batch(&points, Method::Parity).unwrap()
    );
    assert!(ours.contains(&Containment::Inside) && ours.contains(&Containment::Outside));
    // Just inside the first flipped face's centre.
    let [a, b, c] = [0, 1, 2].map(|k| flipped.positions[flipped.polygons[0].vertices[k]]);
    let near = (a + b + c) / 3.0 * 0.99;
    assert_eq!(
        mended.classify_with(near, Method::Parity).unwrap(),
        Containment::Inside
    );
    assert_eq!(winding.classify(near).unwrap(), Containment::Outside);
}

/// Bad input is still refused, by name.
#[test]
fn empty_and_non_finite_soups_are_refused() {
    let mut fin = soup("fixtures/soups/fin.obj");
    fin.positions[9].z = f64::NAN;
    let e = SoupWinding::try_new(&fin).unwrap_err();
    assert!(
        matches!(e, BuildError::NonFinitePosition { vertex: 9, .. }),
        "{e}"
    );
    assert!(
        e.to_string().contains("vertex 9 has a non-finite position"),
        "{e}"
    );
    fin.polygons.clear();
    assert_eq!(
        SoupWinding::try_new(&fin).unwrap_err(),
        BuildError::NoPolygons
    );
}
