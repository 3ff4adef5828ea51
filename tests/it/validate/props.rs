//! Bad input never panics: random OBJ text through import and validation,
//! and random soups through validation; a valid verdict always comes with a
//! built solid.

use std::path::Path;

use glam::DVec3;
use proptest::prelude::*;
use wingedge::io::{ObjOptions, WeldMode, import_obj_bytes};
use wingedge::mesh::{Polygon, PolygonSoup, Solid};
use wingedge::validate::{Options, Validity, validate_and_build, validate_soup};

fn line() -> impl Strategy<Value = String> {
    prop_oneof![
        (-2i32..3, -2i32..3, -2i32..3).prop_map(|(x, y, z)| format!("v {x} {y} {z}")),
        prop::collection::vec(-9i32..12, 0..6).prop_map(|idx| {
            let corners: Vec<String> = idx.iter().map(|i| i.to_string()).collect();
            format!("f {}", corners.join(" "))
        }),
        prop::collection::vec(1i32..9, 3..5).prop_map(|idx| {
            let corners: Vec<String> = idx.iter().map(|i| format!("{i}/1/{i}")).collect();
            format!("f {}", corners.join(" "))
        }),
        Just("vt 0 0".to_string()),
        Just("vn 0 0 1".to_string()),
        Just("g part".to_string()),
        Just("  o  thing  ".to_string()),
        Just("usemtl red".to_string()),
        Just("l 1 2 3".to_string()),
        Just("# comment".to_string()),
        Just("v nan 0 0".to_string()),
        Just("f 1/ /2 3".to_string()),
        Just("".to_string()),
    ]
}

fn soup() -> impl Strategy<Value = PolygonSoup> {
    (
        prop::collection::vec((0i32..3, 0i32..3, 0i32..3), 1..10),
        prop::collection::vec(prop::collection::vec(0usize..10, 1..6), 1..12),
    )
        .prop_map(|(points, polygons)| {
            let n = points.len();
            PolygonSoup {
                positions: points
                    .into_iter()
                    .map(|(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
                    .collect(),
                polygons: polygons
                    .into_iter()
                    .map(|p| Polygon::new(p.into_iter().map(|i| i % n)))
                    .collect(),
            }
        })
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(300)))]

    #[test]
    fn random_obj_text_never_panics(lines in prop::collection::vec(line(), 0..40), weld in 0..3u8) {
        let text = lines.join("\n");
        let weld = match weld {
            0 => WeldMode::None,
            1 => WeldMode::Exact,
            _ => WeldMode::Within(wingedge::geom::Tolerance { weld: 0.3, ..Default::default() }),
        };
        if let Ok(import) = import_obj_bytes(Path::new("p.obj"), text.as_bytes(), &ObjOptions { weld, ..ObjOptions::default() }) {
            let (report, solid) = validate_and_build(&import, &Options::default()).unwrap();
            prop_assert_eq!(report.faces, import.soup.polygons.len());
            if report.validity == Validity::ValidSolid {
                prop_assert!(solid.is_some());
                prop_assert!(report.volume.unwrap() > 0.0);
            }
        }
    }

    #[test]
    fn random_soups_never_panic(soup in soup()) {
        let report = validate_soup(&soup, None, &Options::default()).unwrap();
        if report.validity == Validity::ValidSolid {
            let solid = Solid::try_from_soup(&soup).unwrap();
            prop_assert!(solid.is_closed());
        }
        if report.validity >= Validity::OrientedSurface && report.not_built.is_none() {
            prop_assert!(report.shell_details.iter().all(|s| s.faces > 0));
        }
    }
}
