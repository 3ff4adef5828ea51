//! The batch forms (which reorder work internally for locality) give the
//! same answers, in input order, as the single queries.

use glam::DVec3;
use wingedge::geom::Ray;
use wingedge::mesh::builders;
use wingedge::query::{Accel, Method};

use crate::common::test_rng::uniform;

#[test]
fn batches_match_single_queries() {
    // 19,320 triangles.
    let solid = builders::sphere(70);
    let accel = Accel::new(&solid);
    assert!(accel.stats().triangles > 16 * 1024);
    let mut u = uniform(7);
    // Random points plus mesh vertices (boundary) and points on the +x rays
    // through vertices (ties).
    let mut points: Vec<DVec3> = (0..12_000)
        .map(|_| DVec3::new(u(), u(), u()) * 2.4 - DVec3::splat(1.2))
        .collect();
    for (_, v) in solid.vertices().take(2000) {
        points.push(v.position);
        points.push(v.position - DVec3::new(3.0, 0.0, 0.0));
    }
    let batch = accel.classify_batch(&points, Method::Parity).unwrap();
    for (p, b) in points.iter().zip(&batch) {
        assert_eq!(accel.classify(*p).unwrap(), *b, "{p}");
    }
    let rays: Vec<Ray> = (0..10_000)
        .map(|_| {
            let o = (DVec3::new(u(), u(), u()) * 2.0 - DVec3::ONE).normalize_or(DVec3::X) * 3.0;
            let target = DVec3::new(u(), u(), u()) * 2.0 - DVec3::ONE;
            Ray::new(o, target - o)
        })
        .collect();
    let hits = accel.first_hit_batch(&rays).unwrap();
    for (r, h) in rays.iter().zip(&hits) {
        assert_eq!(accel.first_hit(r).unwrap(), *h);
    }
    // Small batches (no reordering; fewer rays than interleaved lanes, and
    // a part-filled last chunk) and an empty one.
    for n in [0, 1, 5, 8, 9, 700] {
        assert_eq!(accel.first_hit_batch(&rays[..n]).unwrap(), hits[..n]);
    }
    let crossings = accel.ray_crossings_batch(&rays[..2000]).unwrap();
    for (r, c) in rays.iter().zip(&crossings) {
        assert_eq!(accel.ray_crossings(r).unwrap(), *c);
        assert_eq!(
            c.hits.first().map(|h| h.t),
            accel.first_hit(r).unwrap().map(|h| h.t)
        );
    }
}

#[test]
fn a_batch_names_its_first_invalid_ray() {
    use wingedge::query::QueryError;
    let accel = Accel::new(&builders::cube());
    let good = Ray::new(DVec3::new(0.1, 0.2, 5.0), DVec3::NEG_Z);
    let mut rays = vec![good; 20_000];
    rays[12_345] = Ray::new(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X);
    rays[17_000] = Ray::new(DVec3::ZERO, DVec3::ZERO);
    rays[19_999] = Ray::new(DVec3::ZERO, DVec3::new(0.0, f64::INFINITY, 0.0));
    let first = |e: QueryError| match e {
        QueryError::InvalidRay { index, .. } => index,
        other => panic!("{other}"),
    };
    assert_eq!(first(accel.first_hit_batch(&rays).unwrap_err()), 12_345);
    assert_eq!(first(accel.ray_crossings_batch(&rays).unwrap_err()), 12_345);
    rays[12_345] = good;
    assert_eq!(first(accel.first_hit_batch(&rays).unwrap_err()), 17_000);
    rays[17_000] = good;
    assert_eq!(first(accel.first_hit_batch(&rays).unwrap_err()), 19_999);
    rays[19_999] = good;
    let hits = accel.first_hit_batch(&rays).unwrap();
    assert!(hits.iter().all(|h| h.is_some_and(|c| c.t == 4.0)));
}
