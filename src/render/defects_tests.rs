use std::path::Path;

use super::*;
use crate::validate::{Options, validate_soup};

/// The unit cube, faces counter-clockwise from outside (as in
/// `fixtures/broken/self_intersection.obj`).
fn cube() -> PolygonSoup {
    let positions = (0..8)
        .map(|i| {
            let [x, y] = [[0, 0], [1, 0], [1, 1], [0, 1]][i % 4];
            DVec3::new(f64::from(x), f64::from(y), f64::from((i / 4) as u8))
        })
        .collect();
    let faces = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [1, 2, 6, 5],
        [2, 3, 7, 6],
        [3, 0, 4, 7],
    ];
    PolygonSoup::new(positions, faces)
}

fn violations(soup: &PolygonSoup) -> Vec<Violation> {
    validate_soup(soup, None, &Options::default())
        .expect("validates")
        .violations
}

fn outside(legend: PixelBox, x: i64, y: i64) -> bool {
    x < legend.0 || y < legend.1 || x >= legend.0 + legend.2 || y >= legend.1 + legend.3
}

/// Every pixel outside the legend, as `(x, y, colour)`.
fn scene_pixels(image: &Image, legend: PixelBox) -> Vec<(i64, i64, [u8; 3])> {
    let mut out = Vec::new();
    for y in 0..image.height() {
        for x in 0..image.width() {
            let (xi, yi) = (i64::from(x), i64::from(y));
            if outside(legend, xi, yi) {
                out.push((xi, yi, image.pixel(x, y).expect("in the image")));
            }
        }
    }
    out
}

fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let (p, a, b) = (p.truncate(), a.truncate(), b.truncate());
    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    (p - (a + t * (b - a))).length()
}

#[test]
fn the_rim_of_a_hole_is_drawn_along_the_hole_and_nowhere_else() {
    let mut soup = cube();
    soup.polygons.remove(1); // the top face, z = 1
    let found = violations(&soup);
    assert_eq!(
        found
            .iter()
            .filter(|v| v.rule == Rule::EdgeInOneFace)
            .count(),
        4
    );
    let (image, frame, legend) = draw(&soup, &found, 400, 300);
    let red = defect_colour(Rule::EdgeInOneFace);
    let rim: Vec<(DVec3, DVec3)> = [4, 5, 6, 7]
        .iter()
        .map(|&v| {
            let w = 4 + (v - 4 + 1) % 4;
            (
                frame.project(soup.positions[v]),
                frame.project(soup.positions[w]),
            )
        })
        .collect();
    for &(a, b) in &rim {
        for t in [0.25, 0.5, 0.75] {
            let p = a.lerp(b, t);
            let near = (-2..=2).any(|dy| {
                (-2..=2).any(|dx| {
                    let (x, y) = (p.x.floor() as i64 + dx, p.y.floor() as i64 + dy);
                    x >= 0 && y >= 0 && image.pixel(x as u32, y as u32) == Some(red)
                })
            });
            assert!(near, "no rim colour near {p:?}");
        }
    }
    let mut coloured = 0;
    for (x, y, colour) in scene_pixels(&image, legend) {
        if colour == red {
            coloured += 1;
            let centre = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, 0.0);
            let nearest = rim
                .iter()
                .map(|&(a, b)| distance_to_segment(centre, a, b))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= 3.0,
                "rim colour at ({x}, {y}), {nearest} px from the rim"
            );
        }
    }
    assert!(coloured > 100, "{coloured} rim pixels");
}

/// Whether a pixel is `colour` scaled by a factor (as shading does).
fn is_shade_of(pixel: [u8; 3], colour: [u8; 3]) -> bool {
    let brightest = pixel.iter().copied().max().unwrap_or(0);
    brightest > 60
        && (0..3).all(|c| {
            let expected = f64::from(colour[c]) * f64::from(pixel[0].max(1)) / f64::from(colour[0]);
            (f64::from(pixel[c]) - expected).abs() <= 3.0
        })
}

#[test]
fn self_intersecting_faces_are_filled_in_their_colour() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/broken/self_intersection.obj");
    let soup = crate::io::read_obj(&path).expect("the fixture reads");
    let found = violations(&soup);
    assert!(found.iter().any(|v| v.rule == Rule::SelfIntersection));
    let (image, _, legend) = draw(&soup, &found, 320, 240);
    let amber = defect_colour(Rule::SelfIntersection);
    let shaded = scene_pixels(&image, legend)
        .into_iter()
        .filter(|&(_, _, p)| is_shade_of(p, amber))
        .count();
    assert!(
        shaded > 200,
        "{shaded} pixels in the self-intersection colour"
    );
    // The rest of the mesh is grey: some pixels are neither.
    let grey = scene_pixels(&image, legend)
        .into_iter()
        .filter(|&(_, _, p)| p[0] == p[1] && p[1] == p[2] && p != BACKGROUND)
        .count();
    assert!(grey > 200, "{grey} grey pixels");
}

#[test]
fn a_valid_cube_has_no_defect_colour() {
    let soup = cube();
    let found = violations(&soup);
    assert!(found.is_empty());
    let image = render_defects(&soup, &found, &DefectImageOptions::default()).expect("draws");
    let pixels: Vec<[u8; 3]> = image
        .rgb_bytes()
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    assert!(
        pixels.iter().all(|p| p[0] == p[1] && p[1] == p[2]),
        "only greys"
    );
    let surface = pixels
        .iter()
        .filter(|&&p| p != BACKGROUND && p != PANEL && p != INK)
        .count();
    assert!(
        surface > 800 * 600 / 20,
        "the cube fills the frame: {surface} pixels"
    );
}

#[test]
fn the_size_asked_for_is_the_size_drawn() {
    let soup = cube();
    for (width, height) in [(123, 45), (1, 1), (800, 600)] {
        let image =
            render_defects(&soup, &[], &DefectImageOptions { width, height }).expect("draws");
        assert_eq!((image.width(), image.height()), (width, height));
    }
    for (width, height) in [(0, 10), (10, 0), (100_000, 100_000)] {
        assert_eq!(
            render_defects(&soup, &[], &DefectImageOptions { width, height }),
            Err(DefectImageError::Size { width, height })
        );
    }
}

#[test]
fn the_legend_shows_each_rule_broken_with_its_swatch() {
    let mut soup = cube();
    soup.polygons.remove(1);
    let found = violations(&soup);
    let (image, _, legend) = draw(&soup, &found, 800, 600);
    let (mut ink, mut swatch) = (0, 0);
    for y in legend.1..legend.1 + legend.3 {
        for x in legend.0..legend.0 + legend.2 {
            match image.pixel(x as u32, y as u32) {
                Some(INK) => ink += 1,
                Some(p) if p == defect_colour(Rule::EdgeInOneFace) => swatch += 1,
                _ => {}
            }
        }
    }
    assert!(ink > 100, "{ink} text pixels");
    assert_eq!(swatch, 14 * 14, "one 14 × 14 swatch");
}

#[test]
fn ids_of_another_soup_and_an_empty_soup_draw_without_panicking() {
    let stray = Violation {
        rule: Rule::SelfIntersection,
        message: String::new(),
        line: None,
        lines: Vec::new(),
        vertices: vec![99, usize::MAX],
        faces: vec![7, usize::MAX],
        value: None,
    };
    let image = render_defects(
        &cube(),
        std::slice::from_ref(&stray),
        &DefectImageOptions::default(),
    );
    assert!(image.is_ok());
    let empty = PolygonSoup::new(Vec::new(), Vec::<Vec<usize>>::new());
    assert!(render_defects(&empty, &[stray], &DefectImageOptions::default()).is_ok());
}

#[test]
fn every_rule_has_its_own_colour_and_none_is_grey() {
    let colours: std::collections::BTreeSet<[u8; 3]> =
        Rule::ALL.into_iter().map(defect_colour).collect();
    assert_eq!(colours.len(), Rule::ALL.len());
    assert!(colours.iter().all(|c| !(c[0] == c[1] && c[1] == c[2])));
}
