//! Builds a CSG tree in code and asks it the four questions: spans along a
//! ray, the first hit with its normal, points (including one on a face where
//! two solids touch), and the volume — with the work counters.
//!
//! `cargo run --release --example csg_in_code`

use std::sync::Arc;

use glam::{DAffine3, DVec3};
use wingedge::csg::{AxisBox, Csg, CsgExpr, Cylinder, HalfSpace, Sphere, Stats};
use wingedge::geom::Ray;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A 2×2×2 block with a spherical pocket, a second block touching it on
    // the face x = 1, a tilted peg, and everything above z = 0.8 cut away.
    let block = CsgExpr::leaf(AxisBox::try_new(DVec3::splat(-1.0), DVec3::ONE)?);
    let pocket = CsgExpr::leaf(Sphere::try_new(DVec3::new(0.0, 0.0, 1.0), 0.75)?);
    let neighbour = CsgExpr::leaf(AxisBox::try_new(
        DVec3::new(1.0, -1.0, -1.0),
        DVec3::new(2.0, 1.0, 0.0),
    )?);
    let peg = CsgExpr::Leaf {
        primitive: Arc::new(Cylinder::try_new(DVec3::ZERO, DVec3::Z * 2.0, 0.25)?),
        label: "peg".into(),
    }
    .transformed(
        DAffine3::from_translation(DVec3::new(1.5, 0.0, 0.0)) * DAffine3::from_rotation_x(0.3),
    );
    let cut = CsgExpr::leaf(HalfSpace::try_new(DVec3::new(0.0, 0.0, 0.8), DVec3::Z)?);
    let expr = CsgExpr::Intersection(vec![
        CsgExpr::Union(vec![block.difference(pocket), neighbour, peg]),
        cut,
    ]);
    let csg = Csg::try_new(expr)?;
    println!(
        "{} leaves, {} operators, depth {}",
        csg.leaves().len(),
        csg.operator_count(),
        csg.depth()
    );

    let mut stats = Stats::default();
    let ray = Ray::new(DVec3::new(-3.0, 0.0, 0.5), DVec3::X);
    let spans = csg.spans(&ray, &mut stats);
    println!("spans along {ray:?}:");
    for (a, b) in spans.intervals() {
        println!(
            "  [{a:.4}, {b:.4}]  (x from {:.4} to {:.4})",
            ray.at(a).x,
            ray.at(b).x
        );
    }

    let down = Ray::new(DVec3::new(0.2, 0.1, 3.0), -DVec3::Z);
    if let Some(hit) = csg.first_hit(&down, &mut stats) {
        let normal = csg.hit_normal(&down, &hit, &mut stats);
        let leaf = csg.leaf(hit.leaf).map_or("?", |l| l.label.as_str());
        println!(
            "first hit looking down: t = {:.4} at {:.4} on {leaf}, outward normal {:.3}",
            hit.t, hit.point, normal
        );
    }

    for p in [
        DVec3::new(1.0, 0.5, -0.5),  // on the face shared by the two blocks
        DVec3::new(0.0, 0.0, 0.25),  // on the pocket's wall (exactly: 1 − 0.75)
        DVec3::new(0.0, 0.0, 0.8),   // inside the pocket, on the cutting plane
        DVec3::new(-0.8, -0.8, 0.8), // on the cut
        DVec3::new(-0.5, -0.5, 0.0),
    ] {
        println!("point {p}: {}", csg.classify_point(p, &mut stats).as_word());
    }

    let volume = csg.try_volume(0.01)?;
    println!(
        "volume ≈ {:.5} from {} rays with spacing {}",
        volume.volume, volume.rays, volume.spacing
    );
    println!("work for the queries above: {stats}");
    Ok(())
}
