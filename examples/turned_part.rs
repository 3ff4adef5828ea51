//! A part modelled in code: a cubic B-spline profile turned about `z`,
//! drilled by an octagon swept along a bent B-spline path, with a slot cut
//! across its neck. Prints how the turned body's volume converges to the
//! exact volume of revolution of the curve as the chord tolerance shrinks,
//! then the drilled part's ray-integrated volume, and renders it.
//!
//! ```text
//! cargo run --release --example turned_part [-- OUT.png]
//! ```
//!
//! The exact volume of the curve's solid of revolution is Pappus's
//! `V = π |∫ x(t)² y'(t) dt|` (the closing edge along the axis adds
//! nothing); on each knot span the integrand is a polynomial of degree
//! `3 p − 1 = 8`, which five-point Gauss–Legendre quadrature integrates
//! exactly (up to rounding). The same part is `fixtures/scenes/turned_part.json`.

use std::f64::consts::{PI, TAU};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use glam::{DVec2, DVec3};
use wingedge::csg::{AxisBox, Csg, CsgExpr, Polyhedron};
use wingedge::curve::{BSpline, Curve};
use wingedge::mesh::Solid;
use wingedge::render::{RenderOptions, render};
use wingedge::scene::{CameraSpec, LightSpec, Scene};
use wingedge::shape::{RevolveAxis, try_revolve_curve, try_sweep};
use wingedge::validate::{Options, validate_soup};

/// Five-point Gauss–Legendre nodes and weights on `[-1, 1]`.
const GAUSS: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

fn profile() -> Result<BSpline, Box<dyn std::error::Error>> {
    let points = [
        [0.0, 0.0],
        [1.2, 0.0],
        [1.3, 0.9],
        [0.5, 1.4],
        [0.8, 2.5],
        [0.0, 3.0],
    ];
    Ok(BSpline::try_open_uniform(
        points.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect(),
        3,
    )?)
}

/// `π |∫ x² y' dt|` over the curve, span by span.
fn volume_of_revolution(curve: &BSpline) -> Result<f64, Box<dyn std::error::Error>> {
    let breaks = curve.knots().breakpoints();
    let mut integral = 0.0;
    for span in breaks.windows(2) {
        let (a, b) = (span[0], span[1]);
        let (mid, half) = ((a + b) / 2.0, (b - a) / 2.0);
        for (node, weight) in GAUSS {
            let t = mid + half * node;
            let p = curve.try_point_at(t)?;
            let d = curve.try_derivative_at(t, 1)?;
            integral += weight * half * p.x * p.x * d.y;
        }
    }
    Ok(PI * integral.abs())
}

fn validated(solid: &Solid) -> Result<(), Box<dyn std::error::Error>> {
    let report = validate_soup(&solid.to_soup(), None, &Options::default())?;
    if !report.is_valid() {
        return Err(format!("not a valid solid: {:?}", report.violations.first()).into());
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .map_or_else(|| PathBuf::from("target/turned_part.png"), PathBuf::from);
    let curve = profile()?;
    let exact = volume_of_revolution(&curve)?;
    println!("turned body: exact volume of revolution {exact:.12}\n");
    println!("| tolerance | faces | volume | relative error | build + validate |");
    println!("|---:|---:|---:|---:|---:|");
    for tolerance in [1e-2, 1e-3, 1e-4, 1e-5] {
        let start = Instant::now();
        let body = try_revolve_curve(&curve, &RevolveAxis::Z, TAU, tolerance)?;
        validated(&body)?;
        let seconds = start.elapsed().as_secs_f64();
        let volume = body.volume();
        println!(
            "| {tolerance:e} | {} | {volume:.12} | {:.2e} | {:.3} s |",
            body.face_count(),
            (volume - exact).abs() / exact,
            seconds
        );
    }

    // The part: the body minus a bent bore and a slot.
    let body = try_revolve_curve(&curve, &RevolveAxis::Z, TAU, 2e-4)?;
    let octagon: Vec<DVec2> = (0..8)
        .map(|k| {
            let a = f64::from(k) * TAU / 8.0;
            DVec2::new(0.22 * a.cos(), 0.22 * a.sin())
        })
        .collect();
    let path = BSpline::try_open_uniform(
        vec![
            DVec3::new(-2.0, 0.0, 0.5),
            DVec3::new(0.0, 0.0, 1.6),
            DVec3::new(2.0, 0.0, 0.5),
        ],
        2,
    )?;
    let bore = try_sweep(&octagon, &path, 1e-3)?;
    validated(&bore)?;
    let leaf = |solid: Solid, label: &str| -> Result<CsgExpr, Box<dyn std::error::Error>> {
        Ok(CsgExpr::Leaf {
            primitive: Arc::new(Polyhedron::try_new(solid)?),
            label: label.into(),
        })
    };
    let slot = CsgExpr::leaf(AxisBox::try_new(
        DVec3::new(-0.35, -2.0, 2.2),
        DVec3::new(0.35, 2.0, 2.4),
    )?);
    let csg = Csg::try_new(CsgExpr::Difference(vec![
        leaf(body, "body")?,
        leaf(bore, "bore")?,
        slot,
    ]))?;
    let estimate = csg.try_volume(0.005)?;
    println!(
        "\ndrilled part: volume {:.5} by {} rays (spacing {:.4})",
        estimate.volume, estimate.rays, estimate.spacing
    );

    let scene = Scene {
        csg,
        camera: Some(CameraSpec {
            eye: DVec3::new(4.6, -6.2, 4.2),
            look_at: DVec3::new(0.0, 0.0, 1.3),
            up: DVec3::Z,
            fov_deg: 32.0,
        }),
        light: Some(LightSpec::Directional {
            direction: DVec3::new(-0.6, -1.2, 2.0),
            ambient: 0.2,
        }),
        shadows: true,
    };
    let (image, _) = render(&scene, &RenderOptions::default(), &|_| {});
    image.write_png(&out)?;
    println!("rendered {}", out.display());
    Ok(())
}
