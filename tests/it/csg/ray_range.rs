//! Rays from users whose answers sit at the edge of `f64`: directions of any
//! finite length give the same spans in their own units, and rays whose
//! answer `f64` cannot hold are refused by name, not answered wrong.

use std::path::Path;

use wingedge::csg::{MAX_ORIGIN_DISTANCE, Stats, VolumeError};
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::query::QueryError;
use wingedge::scene::Scene;

fn platonic() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/scenes/platonic.json");
    Scene::from_file(&path).expect("the bundled scene loads")
}

fn spans(scene: &Scene, origin: DVec3, direction: DVec3) -> Result<Vec<(f64, f64)>, QueryError> {
    scene
        .csg
        .try_spans(&Ray::new(origin, direction), &mut Stats::default())
        .map(|s| s.intervals())
}

#[test]
fn a_direction_scaled_by_a_power_of_two_scales_every_t_exactly() {
    let scene = platonic();
    let origin = DVec3::new(-6.0, 0.5, 0.5);
    let unit = spans(&scene, origin, DVec3::X).unwrap();
    assert!(unit.len() >= 3, "{unit:?}");
    for k in [-1000, -600, -30, 7, 500, 1000] {
        let scale = 2f64.powi(k);
        let scaled = spans(&scene, origin, DVec3::X * scale).unwrap();
        let expected: Vec<(f64, f64)> = unit.iter().map(|&(a, b)| (a / scale, b / scale)).collect();
        assert_eq!(scaled, expected, "direction 2^{k}");
    }
    // Not a power of two: the same spans up to the rounding of t.
    let tiny = spans(&scene, origin, DVec3::new(1e-300, 0.0, 0.0)).unwrap();
    assert_eq!(tiny.len(), unit.len());
    for (&(a, b), &(c, d)) in tiny.iter().zip(&unit) {
        assert!(
            (a * 1e-300 - c).abs() <= 1e-15 * c.abs() && (b * 1e-300 - d).abs() <= 1e-15 * d.abs()
        );
    }
}

#[test]
fn a_direction_so_short_that_t_overflows_is_refused() {
    let scene = platonic();
    let err = spans(
        &scene,
        DVec3::new(-6.0, 0.5, 0.5),
        DVec3::new(5e-324, 0.0, 0.0),
    )
    .unwrap_err();
    assert!(
        matches!(err, QueryError::RayOutOfRange { index: 0, .. }),
        "{err}"
    );
    let message = err.to_string();
    assert!(
        message.contains("5e-324") && message.contains("overflows"),
        "{message}"
    );
    // Pointing away, it meets nothing: an answer, not a refusal.
    assert_eq!(
        spans(
            &scene,
            DVec3::new(-6.0, 0.5, 0.5),
            DVec3::new(-5e-324, 0.0, 0.0)
        )
        .unwrap(),
        vec![]
    );
}

#[test]
fn an_origin_beyond_the_range_is_refused_and_one_inside_it_answered() {
    let scene = platonic();
    let size = scene.csg.bounds().size().max_element();
    let near = spans(&scene, DVec3::new(-1e6, 0.5, 0.5), DVec3::X).unwrap();
    assert!(near.len() >= 3, "{near:?}");
    let far = DVec3::new(-f64::MAX, 0.5, 0.5);
    let err = spans(&scene, far, DVec3::X).unwrap_err();
    assert!(matches!(err, QueryError::RayOutOfRange { .. }), "{err}");
    assert!(err.to_string().contains("-1.7976931348623157e308"), "{err}");
    // Far away and pointing away: outside, no spans.
    assert_eq!(spans(&scene, far, -DVec3::X).unwrap(), vec![]);
    // Just inside the range: answered.
    let edge = scene.csg.bounds().min.x - 0.5 * MAX_ORIGIN_DISTANCE * size;
    assert!(
        !spans(&scene, DVec3::new(edge, 0.5, 0.5), DVec3::X)
            .unwrap()
            .is_empty()
    );
}

#[test]
fn a_volume_spacing_larger_than_the_solid_is_refused() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/scenes/drilled_cube.json");
    let scene = Scene::from_file(&path).unwrap();
    let err = scene.csg.try_volume(1e300).unwrap_err();
    assert!(matches!(err, VolumeError::SpacingTooLarge { .. }), "{err}");
    assert_eq!(
        err.to_string(),
        "ray spacing 1e300 is larger than the solid (its longest side is 2); use a spacing below that"
    );
}
