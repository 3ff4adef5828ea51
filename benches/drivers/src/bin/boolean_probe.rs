//! Times one boolean of two offset UV spheres, stage by stage:
//! `cargo run --release -p wingedge-bench --bin boolean_probe -- RINGS`.

use glam::DVec3;
use wingedge::SetOp;
use wingedge::boolean::{BooleanOptions, boolean};
use wingedge::mesh::{Solid, builders};

fn main() {
    let rings: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(64);
    let a = builders::sphere(rings);
    let mut soup = builders::sphere_soup(rings);
    for p in &mut soup.positions {
        *p += DVec3::new(0.3, 0.2, 0.1);
    }
    let b = Solid::try_from_soup(&soup).expect("a sphere");
    println!("{} + {} faces", a.face_count(), b.face_count());
    for check in [true, false] {
        let start = std::time::Instant::now();
        let r = boolean(
            &a,
            &b,
            SetOp::Difference,
            BooleanOptions {
                check_operands: check,
                ..BooleanOptions::default()
            },
        )
        .expect("a valid difference");
        let s = &r.stats;
        println!(
            "check {check}: {:.3} s total; {}; {} contacts, {} new points, {} faces",
            start.elapsed().as_secs_f64(),
            s.stages_text(),
            s.contacts,
            s.new_points,
            r.solid.face_count()
        );
    }
}
