//! Property tests of the winged-edge invariants and the nine adjacency
//! relations on random prisms (convex and star-shaped, non-convex profiles)
//! and random pyramids over convex polygons.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use proptest::prelude::*;
use wingedge::mesh::{EdgeId, FaceId, Side, Solid, VertexId, builders};

/// A star-shaped polygon in the plane z = `z`: strictly increasing angles,
/// radii in [0.2, 2] (non-convex in general). With `convex`, all radii equal.
fn star_polygon(angles: &[f64], radii: &[f64], convex: bool, z: f64) -> Vec<DVec3> {
    let mut a: Vec<f64> = angles.to_vec();
    a.sort_by(f64::total_cmp);
    a.dedup_by(|x, y| (*x - *y).abs() < 1e-3);
    a.iter()
        .zip(radii)
        .map(|(&t, &r)| {
            let r = if convex { 1.0 } else { r };
            DVec3::new(r * t.cos(), r * t.sin(), z)
        })
        .collect()
}

fn polygon_strategy() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (3usize..12).prop_flat_map(|n| {
        (
            prop::collection::vec(0.0..std::f64::consts::TAU, n),
            prop::collection::vec(0.2f64..2.0, n),
        )
    })
}

fn sweep_strategy() -> impl Strategy<Value = DVec3> {
    (-1.0f64..1.0, -1.0f64..1.0, 0.1f64..3.0).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// Every invariant the issue names, checked through the public relations,
/// on a closed solid of one shell with `handles` through holes.
fn assert_relations(solid: &Solid, handles: i64) {
    solid.check_consistency().expect("consistent");

    // Each edge appears in the loops of exactly its faces, once per side, in
    // opposite directions.
    let mut seen: HashMap<EdgeId, Vec<(FaceId, VertexId, VertexId)>> = HashMap::new();
    for (f, _) in solid.faces() {
        for l in solid.face_loops(f) {
            // Walking each loop (outer or ring) returns to its start.
            let uses: Vec<_> = solid.loop_uses(l).collect();
            assert_eq!(solid.use_next(*uses.last().unwrap()), uses[0]);
        }
        let uses: Vec<_> = solid.face_loop(f).collect();
        for u in uses {
            seen.entry(u.edge)
                .or_default()
                .push((f, solid.use_start(u), solid.use_end(u)));
        }
    }
    for (e, edge) in solid.edges() {
        let users = &seen[&e];
        let faces: Vec<FaceId> = solid.edge_faces(e).collect();
        assert_eq!(users.len(), faces.len());
        assert_eq!(users.len(), 2, "closed solids have two faces per edge");
        assert_ne!(users[0].0, users[1].0);
        assert_eq!(
            (users[0].1, users[0].2),
            (users[1].2, users[1].1),
            "opposite directions"
        );
        for &(f, a, b) in users {
            let expected = if f == edge.left_face {
                (edge.origin, edge.dest)
            } else {
                (edge.dest, edge.origin)
            };
            assert_eq!((a, b), expected);
        }
        // The four wings are the loop neighbours.
        let [cw_left, ccw_left, cw_right, ccw_right] = solid.edge_wings(e);
        let left = wingedge::mesh::EdgeUse {
            edge: e,
            side: Side::Left,
        };
        let right = left.opposite();
        assert_eq!(solid.use_next(left).edge, ccw_left);
        assert_eq!(solid.use_prev(left).edge, cw_left);
        assert_eq!(solid.use_next(right).edge, ccw_right);
        assert_eq!(solid.use_prev(right).edge, cw_right);
    }

    // Every vertex star is one closed cycle through all the vertex's edges.
    let mut degree: HashMap<VertexId, usize> = HashMap::new();
    for (_, e) in solid.edges() {
        *degree.entry(e.origin).or_default() += 1;
        *degree.entry(e.dest).or_default() += 1;
    }
    for (v, _) in solid.vertices() {
        let star: Vec<EdgeId> = solid.vertex_edges(v).collect();
        assert_eq!(star.len(), degree[&v]);
        assert!(star.len() >= 3);
        assert_eq!(
            star.iter().collect::<HashSet<_>>().len(),
            star.len(),
            "each edge once"
        );
        let faces: Vec<FaceId> = solid.vertex_faces(v).collect();
        assert_eq!(
            faces.len(),
            star.len(),
            "closed: a face between consecutive edges"
        );
    }

    // The nine relations agree with each other.
    for (v, _) in solid.vertices() {
        for f in solid.vertex_faces(v) {
            assert!(
                solid.face_vertices(f).any(|w| w == v),
                "f in faces(v) ⇒ v in vertices(f)"
            );
        }
        for e in solid.vertex_edges(v) {
            assert!(
                solid.edge_vertices(e).contains(&v),
                "e in edges(v) ⇒ v in vertices(e)"
            );
        }
        for w in solid.vertex_vertices(v) {
            assert!(
                solid.vertex_vertices(w).any(|x| x == v),
                "adjacency is symmetric"
            );
        }
    }
    for (f, _) in solid.faces() {
        for e in solid.face_edges(f) {
            assert!(
                solid.edge_faces(e).any(|g| g == f),
                "e in edges(f) ⇒ f in faces(e)"
            );
        }
        for g in solid.face_neighbours(f) {
            assert!(
                solid.face_neighbours(g).any(|h| h == f),
                "neighbourhood is symmetric"
            );
        }
        for v in solid.face_vertices(f) {
            assert!(
                solid.vertex_faces(v).any(|g| g == f),
                "v in vertices(f) ⇒ f in faces(v)"
            );
        }
        assert_eq!(solid.face_vertices(f).count(), solid.face_edges(f).count());
    }
    for (e, _) in solid.edges() {
        for w in solid.edge_wings(e) {
            let shared: HashSet<VertexId> = solid.edge_vertices(e).into_iter().collect();
            assert!(
                solid.edge_vertices(w).iter().any(|v| shared.contains(v)),
                "a wing touches its edge"
            );
        }
    }
    // Euler–Poincaré: V − E + F − R = 2 (S − H).
    assert_eq!(solid.euler_characteristic(), 2 * (1 - handles));
    assert!(solid.volume() > 0.0);
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(96)))]

    #[test]
    fn random_prisms_keep_every_invariant(
        (angles, radii) in polygon_strategy(),
        convex in any::<bool>(),
        reverse in any::<bool>(),
        sweep in sweep_strategy(),
    ) {
        let mut profile = star_polygon(&angles, &radii, convex, 0.5);
        prop_assume!(profile.len() >= 3);
        if reverse {
            profile.reverse();
        }
        let solid = match builders::prism(&profile, sweep) {
            Ok(solid) => solid,
            // Random radii can make a vertex lie exactly on the chord of its
            // neighbours; the builder refuses such profiles with an error.
            Err(e) => return Err(TestCaseError::reject(format!("{e}"))),
        };
        assert_relations(&solid, 0);
        let n = profile.len();
        prop_assert_eq!((solid.vertex_count(), solid.edge_count(), solid.face_count()), (2 * n, 3 * n, n + 2));
        let fit = wingedge::geom::Plane::try_fit_newell(&profile).unwrap();
        let expected = fit.vector_area.length() * sweep.z;
        prop_assert!((solid.volume() - expected).abs() <= 1e-12 * expected.max(1.0));
    }

    #[test]
    fn random_pyramids_keep_every_invariant(
        (angles, radii) in polygon_strategy(),
        apex in (-2.0f64..2.0, -2.0f64..2.0, 0.2f64..3.0),
    ) {
        let base = star_polygon(&angles, &radii, true, 0.0);
        prop_assume!(base.len() >= 3);
        let solid = builders::pyramid(&base, DVec3::new(apex.0, apex.1, -apex.2)).unwrap();
        assert_relations(&solid, 0);
        let n = base.len();
        prop_assert_eq!((solid.vertex_count(), solid.edge_count(), solid.face_count()), (n + 1, 2 * n, n + 1));
    }
}

#[test]
fn platonic_solids_keep_every_invariant() {
    for name in builders::NAMES {
        // The frame has a hole through it; the others are spheres.
        let handles = i64::from(name == "frame");
        assert_relations(&builders::by_name(name).unwrap(), handles);
    }
}
