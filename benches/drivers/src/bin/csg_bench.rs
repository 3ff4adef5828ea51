//! Ray-cast CSG throughput, printed as a table: rays per second through a
//! union of 100 polyhedral leaves and through a deep tree, and the time the
//! volume integration needs to reach 1e-3 relative accuracy on the bundled
//! drilled cube (known volume).
//!
//! `cargo run --release -p wingedge-bench --bin csg_bench` (about 20 s on two cores).

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;
use wingedge::csg::{AxisBox, Csg, CsgExpr, HalfSpace, Polyhedron, Sphere, Stats};
use wingedge::geom::Ray;
use wingedge::mesh::{Solid, builders};
use wingedge::scene::Scene;

#[path = "../../../../src/test_rng.rs"]
mod test_rng;

/// The shared seeded generator, so every run casts the same rays.
struct Rng(Box<dyn FnMut() -> f64>);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(Box::new(test_rng::uniform(seed)))
    }

    fn next(&mut self) -> f64 {
        (self.0)()
    }

    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.next(), self.next(), self.next()) * 2.0 - DVec3::ONE;
            if v.length_squared() > 1e-6 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

/// `solid` scaled about the origin and moved (vertex coordinates rewritten,
/// as a transform node does to a mesh leaf).
fn placed(solid: &Solid, scale: f64, offset: DVec3) -> Solid {
    let ids: Vec<_> = solid.vertices().map(|(id, _)| id).collect();
    let index = |v| ids.iter().position(|&w| w == v).unwrap_or(0);
    let positions: Vec<DVec3> = ids
        .iter()
        .map(|&v| solid.position(v) * scale + offset)
        .collect();
    let polygons: Vec<Vec<usize>> = solid
        .faces()
        .map(|(f, _)| solid.face_vertices(f).map(index).collect())
        .collect();
    Solid::try_from_polygons(&positions, polygons).expect("a moved valid solid is valid")
}

/// Rays from a sphere of radius `r` around `centre`, aimed at random points
/// of the ball of radius `r / 2`.
fn rays(n: usize, centre: DVec3, r: f64, seed: u64) -> Vec<Ray> {
    let mut rng = Rng::new(seed);
    (0..n)
        .map(|_| {
            let from = centre + rng.unit() * r;
            let to = centre + rng.unit() * (0.5 * r * rng.next());
            Ray::new(from, to - from)
        })
        .collect()
}

struct Row {
    scene: String,
    leaves: usize,
    depth: usize,
    spans_1t: f64,
    first_1t: f64,
    spans_2t: f64,
    tests_per_ray: f64,
}

fn measure(name: &str, csg: &Csg, rays: &[Ray]) -> Row {
    let mut stats = Stats::default();
    let start = Instant::now();
    let mut crossings = 0usize;
    for r in rays {
        crossings += csg.spans(r, &mut stats).hits.len();
    }
    let spans_1t = rays.len() as f64 / start.elapsed().as_secs_f64();
    let mut first_stats = Stats::default();
    let start = Instant::now();
    let mut hits = 0usize;
    for r in rays {
        hits += usize::from(csg.first_hit(r, &mut first_stats).is_some());
    }
    let first_1t = rays.len() as f64 / start.elapsed().as_secs_f64();
    let start = Instant::now();
    let parallel: usize = rays
        .par_iter()
        .map(|r| csg.spans(r, &mut Stats::default()).hits.len())
        .sum();
    let spans_2t = rays.len() as f64 / start.elapsed().as_secs_f64();
    assert_eq!(parallel, crossings);
    assert!(hits > 0);
    Row {
        scene: name.to_string(),
        leaves: csg.leaves().len(),
        depth: csg.depth(),
        spans_1t,
        first_1t,
        spans_2t,
        tests_per_ray: stats.primitive_ray_tests as f64 / rays.len() as f64,
    }
}

/// 100 Platonic solids on a 10 × 10 grid, exact polyhedral leaves.
fn hundred_polyhedra() -> Csg {
    let shapes = [
        builders::tetrahedron(),
        builders::cube(),
        builders::octahedron(),
        builders::icosahedron(),
        builders::dodecahedron(),
    ];
    let mut leaves = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let shape = &shapes[(i * 3 + j) % shapes.len()];
            let offset = DVec3::new(i as f64 * 3.0, j as f64 * 3.0, ((i + j) % 3) as f64);
            let solid = placed(shape, 0.8, offset);
            leaves.push(CsgExpr::leaf(Polyhedron::try_new(solid).expect("valid")));
        }
    }
    Csg::try_new(CsgExpr::Union(leaves)).expect("a valid tree")
}

/// 16 copies of one sphere mesh of 39,600 triangles, each turned and
/// moved by a transform node (so each is copied into the world with its
/// own query structure), united; and the seconds that building took.
fn transformed_spheres() -> (Csg, f64) {
    let leaf = Polyhedron::try_new(builders::sphere(100)).expect("valid");
    let start = Instant::now();
    let copies = (0..16)
        .map(|i| {
            let a = f64::from(i);
            let turn = glam::DQuat::from_euler(glam::EulerRot::XYZ, a * 0.3, a * 0.7, a * 1.1);
            let at = DVec3::new(f64::from(i % 4) * 1.5, f64::from(i / 4) * 1.5, 0.0);
            CsgExpr::leaf(leaf.clone())
                .transformed(glam::DAffine3::from_rotation_translation(turn, at))
        })
        .collect();
    let csg = Csg::try_new(CsgExpr::Union(copies)).expect("a valid tree");
    (csg, start.elapsed().as_secs_f64())
}

/// A left-deep chain of 48 operators over boxes, balls and half-spaces that
/// all overlap the middle, so that little can be culled.
fn deep_tree() -> Csg {
    let mut rng = Rng::new(7);
    let mut expr = CsgExpr::leaf(AxisBox::try_new(DVec3::splat(-1.0), DVec3::ONE).expect("box"));
    for k in 0..48 {
        let c = (rng.unit() * 0.9).to_array();
        let centre = DVec3::from(c);
        expr = match k % 4 {
            0 => expr.difference(CsgExpr::leaf(Sphere::try_new(centre, 0.35).expect("ball"))),
            1 => expr.union(CsgExpr::leaf(
                AxisBox::try_new(centre - 0.2, centre + 0.2).expect("box"),
            )),
            2 => expr.intersection(CsgExpr::leaf(
                HalfSpace::try_new(rng.unit() * 1.1, rng.unit()).expect("half-space"),
            )),
            _ => expr.difference(CsgExpr::leaf(
                AxisBox::try_new(centre - 0.15, centre + 0.15).expect("box"),
            )),
        };
    }
    Csg::try_new(expr).expect("a valid tree")
}

fn main() {
    let threads = rayon::current_num_threads();
    println!("ray-cast CSG benchmark ({threads} threads for the parallel column)\n");
    let poly = hundred_polyhedra();
    let poly_rays = rays(200_000, DVec3::new(13.5, 13.5, 1.0), 25.0, 1);
    let deep = deep_tree();
    let deep_rays = rays(200_000, DVec3::ZERO, 3.0, 2);
    let (spheres, spheres_build) = transformed_spheres();
    let spheres_rays = rays(200_000, DVec3::new(2.25, 2.25, 0.0), 6.0, 3);
    let rows = [
        measure("100 polyhedral leaves (union)", &poly, &poly_rays),
        measure("deep tree (48 operators)", &deep, &deep_rays),
        measure(
            "16 transformed meshes of 39,600 triangles (union)",
            &spheres,
            &spheres_rays,
        ),
    ];
    println!(
        "| scene | leaves | depth | spans, rays/s (1 thread) | first hit, rays/s (1 thread) | spans, rays/s ({threads} threads) | primitive tests / ray |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for r in &rows {
        println!(
            "| {} | {} | {} | {:.0} | {:.0} | {:.0} | {:.2} |",
            r.scene, r.leaves, r.depth, r.spans_1t, r.first_1t, r.spans_2t, r.tests_per_ray
        );
    }

    println!(
        "\nbuilding the tree of 16 transformed meshes (each copied into the world with its query structure): {spheres_build:.3} s"
    );

    // Volume: halve the cell area until the estimate is within 1e-3.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/scenes/drilled_cube.json"
    );
    let scene = Scene::from_file(std::path::Path::new(path)).expect("bundled scene");
    let r: f64 = 0.5;
    let exact = 8.0
        - (3.0 * std::f64::consts::PI * r * r * 2.0 - 16.0 * r.powi(3)
            + 8.0 * (2.0 - 2f64.sqrt()) * r.powi(3));
    println!("\nvolume of fixtures/scenes/drilled_cube.json (exact {exact:.6}):\n");
    println!("| spacing h | rays | volume | relative error | time ({threads} threads) |");
    println!("|---:|---:|---:|---:|---:|");
    let mut h = 0.2;
    let mut runs = Vec::new();
    while h > 0.003 {
        let start = Instant::now();
        let v = scene.csg.try_volume(h).expect("bounded scene");
        let seconds = start.elapsed().as_secs_f64();
        let error = ((v.volume - exact) / exact).abs();
        println!(
            "| {h:.4} | {} | {:.6} | {error:.2e} | {:.4} s |",
            v.rays, v.volume, seconds
        );
        runs.push((h, error, seconds));
        h /= 2f64.sqrt();
    }
    // The coarsest spacing from which every finer one stays within 1e-3.
    let settled = (0..runs.len()).find(|&i| runs[i..].iter().all(|r| r.1 < 1e-3));
    if let Some(i) = settled {
        let (h, _, seconds) = runs[i];
        println!(
            "\n1e-3 relative accuracy (and every finer spacing tried) from h = {h:.4}: {seconds:.4} s"
        );
    }
}
