//! Lambert shading of first hits, with optional shadow rays.

use glam::DVec3;
use rayon::prelude::*;

use super::{Camera, Image};
use crate::csg::{LeafId, Stats};
use crate::geom::Ray;
use crate::scene::{DEFAULT_AMBIENT, LightSpec, Scene};

/// How to render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Shadow rays start this far off the surface along its normal, as a
    /// fraction of the camera's distance to its target (the scene's scale),
    /// so that a surface does not shadow itself through the rounding of the
    /// hit point. Default `1e-7`. Used only when the scene asks for shadows.
    pub shadow_bias: f64,
}

impl Default for RenderOptions {
    fn default() -> RenderOptions {
        RenderOptions {
            width: 640,
            height: 480,
            shadow_bias: 1e-7,
        }
    }
}

/// A palette for leaves: soft colours that tell the leaves apart.
const PALETTE: [[f64; 3]; 8] = [
    [0.85, 0.55, 0.35],
    [0.35, 0.60, 0.85],
    [0.55, 0.80, 0.45],
    [0.90, 0.80, 0.40],
    [0.75, 0.50, 0.80],
    [0.40, 0.80, 0.80],
    [0.90, 0.50, 0.55],
    [0.70, 0.70, 0.70],
];

fn leaf_colour(leaf: LeafId) -> DVec3 {
    DVec3::from(PALETTE[leaf.0 as usize % PALETTE.len()])
}

/// About how many pixels one parallel task shades (whole rows of them).
const ROWS_PER_BAND: usize = 4096;

fn background(v: f64) -> DVec3 {
    DVec3::new(0.93, 0.94, 0.96).lerp(DVec3::new(0.72, 0.76, 0.82), v)
}

fn to_srgb8(c: DVec3) -> [u8; 3] {
    let f = |x: f64| (x.clamp(0.0, 1.0).powf(1.0 / 2.2) * 255.0).round() as u8;
    [f(c.x), f(c.y), f(c.z)]
}

/// Renders the scene: one camera ray per pixel (the root merge stops at the
/// first hit), the hit's outward normal (computed only for shading), Lambert
/// with the scene's light (a default light above the camera's left shoulder
/// if the scene has none), and a shadow ray per lit pixel only when
/// `scene.shadows` is set. Rows run in parallel; `progress` gets the
/// fraction of rows done.
#[must_use]
pub fn render(
    scene: &Scene,
    options: &RenderOptions,
    progress: &(dyn Fn(f64) + Sync),
) -> (Image, Stats) {
    let camera = scene
        .camera
        .as_ref()
        .map_or_else(|| Camera::framing(scene.csg.bounds()), Camera::from_spec);
    let light = scene.light.unwrap_or(LightSpec::Directional {
        direction: camera.up * 0.9 - camera.right * 0.5 - camera.forward * 0.6,
        ambient: DEFAULT_AMBIENT,
    });
    let (width, height) = (options.width.max(1), options.height.max(1));
    let bias = options.shadow_bias * camera.distance;
    let done = std::sync::atomic::AtomicU32::new(0);
    // The pixels are written in place, a band of rows per task, and each
    // band's counters summed (integers: any order gives the same total):
    // memory is three bytes a pixel, whatever the image's shape.
    let row_bytes = 3 * width as usize;
    let band_rows = (ROWS_PER_BAND / width as usize).max(1);
    let mut bytes = vec![0u8; row_bytes * height as usize];
    let stats = bytes
        .par_chunks_mut(row_bytes * band_rows)
        .enumerate()
        .map(|(band, rows)| {
            let mut stats = Stats::default();
            for (k, row) in rows.chunks_exact_mut(row_bytes).enumerate() {
                let y = (band * band_rows + k) as u32;
                for (x, pixel) in (0..width).zip(row.chunks_exact_mut(3)) {
                    let ray = camera.pixel_ray(x, y, width, height);
                    let colour = shade(scene, &ray, &light, bias, &mut stats)
                        .unwrap_or_else(|| background(f64::from(y) / f64::from(height)));
                    pixel.copy_from_slice(&to_srgb8(colour));
                }
                let finished = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(f64::from(finished) / f64::from(height));
            }
            stats
        })
        .reduce(Stats::default, |mut a, b| {
            a += b;
            a
        });
    let image = Image::from_rgb_bytes(width, height, bytes)
        .unwrap_or_else(|| unreachable!("three bytes for every pixel"));
    (image, stats)
}

fn shade(
    scene: &Scene,
    ray: &Ray,
    light: &LightSpec,
    bias: f64,
    stats: &mut Stats,
) -> Option<DVec3> {
    let csg = &scene.csg;
    let hit = csg.first_hit(ray, stats)?;
    let normal = csg.hit_normal(ray, &hit, stats);
    let (to_light, t_max, ambient) = match *light {
        LightSpec::Directional { direction, ambient } => {
            (direction.normalize_or_zero(), f64::INFINITY, ambient)
        }
        LightSpec::Point { position, ambient } => {
            let v = position - hit.point;
            (v.normalize_or_zero(), v.length(), ambient)
        }
    };
    let mut lambert = normal.dot(to_light).max(0.0);
    if scene.shadows && lambert > 0.0 {
        let origin = hit.point + normal * bias;
        let shadow = Ray::new(origin, to_light);
        if csg.occluded(&shadow, t_max, stats) {
            lambert = 0.0;
        }
    }
    Some(leaf_colour(hit.leaf) * (ambient + (1.0 - ambient) * lambert))
}
