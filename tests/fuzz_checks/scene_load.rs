//! Arbitrary bytes as a scene file → `Scene::from_json` (mesh paths relative
//! to `base`, `fixtures/scenes/`, so that the seeds' meshes load) → if it
//! loads: classify a point, trace a ray, render a tiny image and estimate
//! the volume on a coarse grid. A bad scene must give a `SceneError`, never
//! a panic.

use std::path::Path;

use wingedge::csg::Stats;
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::render::{RenderOptions, render};
use wingedge::scene::Scene;

/// Checks one input.
pub fn run(data: &[u8], base: &Path) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let scene = match Scene::from_json(text, "fuzz.json", base) {
        Ok(scene) => scene,
        Err(e) => {
            assert!(!e.to_string().is_empty());
            return;
        }
    };
    let csg = &scene.csg;
    let mut stats = Stats::default();
    let bounds = csg.bounds();
    let centre = (bounds.min + bounds.max) * 0.5;
    let p = if centre.is_finite() {
        centre
    } else {
        DVec3::ZERO
    };
    let _ = csg.classify_point(p, &mut stats);
    let eye = scene
        .camera
        .map_or(p + DVec3::new(3.0, 2.0, 1.0), |c| c.eye);
    let ray = Ray::new(eye, p - eye);
    let spans = csg.spans(&ray, &mut stats);
    let mut previous = 0.0;
    for hit in &spans.hits {
        assert!(hit.t > previous, "spans not strictly ascending: {spans:?}");
        previous = hit.t;
    }
    if let Some(hit) = csg.first_hit(&ray, &mut stats) {
        assert_eq!(Some(hit.t), spans.hits.first().map(|h| h.t));
        let _ = csg.hit_normal(&ray, &hit, &mut stats);
    }
    let options = RenderOptions {
        width: 3,
        height: 2,
        ..RenderOptions::default()
    };
    let (image, _) = render(&scene, &options, &|_| {});
    assert_eq!((image.width(), image.height()), (3, 2));
    let spacing = bounds.size().max_element() / 4.0;
    let _ = csg.try_volume(spacing);
}
