//! The hard cases of booleans, printed as a table of volume, shells,
//! genus and verdict, to set beside manifold3d's answers
//! (`benches/peers/boolean_hard_cases.py`):
//! `cargo run --release -p wingedge-bench --bin hard_cases`.

use glam::{DAffine3, DVec3};
use wingedge::SetOp;
use wingedge::boolean::{BooleanOptions, boolean};
use wingedge::mesh::{Solid, builders};

fn cuboid(min: [f64; 3], max: [f64; 3]) -> Solid {
    builders::cuboid(DVec3::from(min), DVec3::from(max)).expect("a cuboid")
}

fn mapped(s: &Solid, map: DAffine3) -> Solid {
    let mut soup = s.to_soup();
    for p in &mut soup.positions {
        *p = map.transform_point3(*p);
    }
    Solid::try_from_soup(&soup).expect("a solid")
}

fn show(name: &str, a: &Solid, b: &Solid, operation: SetOp) {
    match boolean(a, b, operation, BooleanOptions::default()) {
        Ok(r) => println!(
            "| {name} | {:.17} | {} | {} | {} | {} |",
            r.solid.volume(),
            r.report.shells,
            r.report.genus.map_or("-".to_string(), |g| g.to_string()),
            r.solid.face_count(),
            r.report.validity.describe()
        ),
        Err(e) => println!("| {name} | refused | | | | {e} |"),
    }
}

fn main() {
    use SetOp::{Difference, Intersection, Union};
    println!("| case | volume | shells | genus | faces | verdict |\n|---|---|---|---|---|---|");
    let a = cuboid([0.0; 3], [1.0; 3]);
    show(
        "face-sharing union",
        &a,
        &cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
        Union,
    );
    show(
        "face-sharing intersection",
        &a,
        &cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
        Intersection,
    );
    show(
        "edge-sharing union",
        &a,
        &cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
        Union,
    );
    show(
        "vertex-sharing union",
        &a,
        &cuboid([1.0; 3], [2.0; 3]),
        Union,
    );
    show("cube minus itself", &a, &a, Difference);
    show(
        "cube minus coplanar-topped box",
        &a,
        &cuboid([0.25, 0.25, 0.5], [0.75, 0.75, 1.0]),
        Difference,
    );
    let b = cuboid([-1.0; 3], [1.0; 3]);
    let r = mapped(&b, DAffine3::from_rotation_z(1e-12));
    show("rotated 1e-12 rad: union", &b, &r, Union);
    show("rotated 1e-12 rad: intersection", &b, &r, Intersection);
    show("rotated 1e-12 rad: difference", &b, &r, Difference);
    let up = 1.0f64.next_up();
    let c = cuboid([0.0; 3], [up; 3]);
    show("1 ulp larger: union", &a, &c, Union);
    show("1 ulp larger: intersection", &a, &c, Intersection);
    show("1 ulp larger: difference", &c, &a, Difference);
    let s = builders::sphere(20);
    let t = mapped(&s, DAffine3::from_translation(DVec3::new(0.3, 0.2, 0.1)));
    for (scale, offset) in [(1.0, 0.0), (1.0, 1e8), (1e-8, 0.0)] {
        let map = DAffine3::from_translation(DVec3::splat(offset))
            * DAffine3::from_scale(DVec3::splat(scale));
        show(
            &format!("spheres difference, scale {scale:e}, offset {offset:e}"),
            &mapped(&s, map),
            &mapped(&t, map),
            Difference,
        );
    }
}
