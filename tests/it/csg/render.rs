//! Rendering does only the work the scene asks for, and the picture has the
//! solid where the camera looks.

use std::path::Path;

use wingedge::render::{RenderOptions, render};
use wingedge::scene::Scene;

fn scene(shadows: bool) -> Scene {
    let text = format!(
        r#"{{"root": {{"difference": [
            {{"box": {{"min": [-1,-1,-1], "max": [1,1,1]}}}},
            {{"sphere": {{"center": [1,1,1], "radius": 1.2}}}}]}},
          "camera": {{"eye": [0,-6,0], "look_at": [0,0,0], "fov_deg": 40}},
          "light": {{"direction": [0.3,-1,0.5]}},
          "shadows": {shadows}}}"#
    );
    Scene::from_json(&text, "inline", Path::new(".")).unwrap()
}

#[test]
fn shadow_rays_only_when_asked_and_normals_only_for_hits() {
    let options = RenderOptions {
        width: 40,
        height: 30,
        ..RenderOptions::default()
    };
    let (image, stats) = render(&scene(false), &options, &|_| {});
    assert_eq!(stats.shadow_rays, 0);
    assert_eq!(stats.rays, 40 * 30);
    // The background is a vertical gradient: the left column shows it.
    let hits = (0..30)
        .flat_map(|y| (0..40).map(move |x| (x, y)))
        .filter(|&(x, y)| image.pixel(x, y) != image.pixel(0, y))
        .count() as u64;
    // One normal per pixel that shows the solid, none for the background.
    assert!(hits > 100, "{hits}");
    assert_eq!(stats.normals, hits, "{stats}");
    let (_, with_shadows) = render(&scene(true), &options, &|_| {});
    assert!(with_shadows.shadow_rays > 0);
    assert!(with_shadows.shadow_rays <= with_shadows.normals);
    // The centre shows the front face (lit), the corner the background.
    assert_ne!(image.pixel(20, 15), image.pixel(0, 15));
}
