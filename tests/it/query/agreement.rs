//! Property tests: the three point-in-polyhedron methods agree on every
//! valid closed fixture; parity equals the rounded winding number; ray
//! crossings in any direction agree with parity.

use std::sync::OnceLock;

use crate::common::fixtures::closed_fixtures;
use glam::DVec3;
use proptest::prelude::*;
use wingedge::geom::Ray;
use wingedge::query::{Accel, Containment, Method, Transition};

fn fixtures() -> &'static Vec<(&'static str, Accel)> {
    static F: OnceLock<Vec<(&'static str, Accel)>> = OnceLock::new();
    F.get_or_init(|| {
        closed_fixtures()
            .into_iter()
            .map(|(name, solid)| (name, Accel::new(&solid)))
            .collect()
    })
}

/// A point in the fixture's box grown by a quarter: either generic, or
/// snapped to a 1/8 grid so that many points lie exactly on faces, edges,
/// vertices and fan diagonals, and many `+x` rays run through them.
fn point_in(accel: &Accel, u: [f64; 3], snap: bool) -> DVec3 {
    let b = accel.bounds();
    let pad = b.size() * 0.25;
    let lo = b.min - pad;
    let p = lo + (b.size() + pad * 2.0) * DVec3::from_array(u);
    if snap { (p * 8.0).round() / 8.0 } else { p }
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(400)))]

    #[test]
    fn methods_agree_and_parity_is_the_rounded_winding_number(
        fixture in 0usize..10,
        u in prop::array::uniform3(0.0f64..1.0),
        snap in any::<bool>(),
        dir in prop::array::uniform3(-1.0f64..1.0),
    ) {
        let (name, accel) = &fixtures()[fixture % fixtures().len()];
        let p = point_in(accel, u, snap);
        let parity = accel.classify(p).unwrap();
        let winding = accel.classify_with(p, Method::Winding).unwrap();
        prop_assert_eq!(parity, winding, "{}: {}", name, p);
        if accel.convexity().is_ok() {
            let normals = accel.classify_with(p, Method::Normals).unwrap();
            prop_assert_eq!(parity, normals, "{}: {}", name, p);
        }
        if parity != Containment::OnBoundary {
            let w = accel.winding_number(p).unwrap();
            let rounded = w.round() as i64;
            // The value is a float construction: points within ~1e-13 of a
            // face lose digits, but never the rounding.
            prop_assert!((w - rounded as f64).abs() < 0.25, "{}: w = {} at {}", name, w, p);
            let expected = if parity == Containment::Inside { 1 } else { 0 };
            prop_assert_eq!(rounded, expected, "{}: w = {} at {}", name, w, p);
        }
        // A ray in a random direction (snapped too, so that it often runs
        // through edges and vertices or along faces).
        let mut d = DVec3::from_array(dir);
        if snap {
            d = (d * 2.0).round();
        }
        if d != DVec3::ZERO {
            let r = accel.ray_crossings(&Ray::new(p, d)).unwrap();
            prop_assert_eq!(r.origin, parity, "{}: {} along {}", name, p, d);
            let mut inside = match r.origin {
                Containment::Inside => true,
                Containment::Outside => false,
                Containment::OnBoundary => {
                    r.hits.first().map(|h| h.transition) == Some(Transition::Exit)
                }
            };
            for h in &r.hits {
                prop_assert!(h.t > 0.0);
                prop_assert_eq!(
                    h.transition,
                    if inside { Transition::Exit } else { Transition::Enter },
                    "{}: {} along {}: {:?}", name, p, d, r
                );
                inside = !inside;
            }
            prop_assert!(!inside, "{}: {} along {} ends inside: {:?}", name, p, d, r);
            for w in r.hits.windows(2) {
                prop_assert!(w[0].t <= w[1].t);
            }
            let first = accel.first_hit(&Ray::new(p, d)).unwrap();
            prop_assert_eq!(first.map(|c| c.t), r.hits.first().map(|c| c.t));
        }
    }
}
