//! Solids written as OBJ read back with the same topology and measures.

use crate::common::temp_dir::TempDir;
use wingedge::io::{read_obj, to_obj_string, write_obj};
use wingedge::mesh::{Solid, builders};

#[test]
fn every_builtin_survives_a_round_trip() {
    let dir = TempDir::new("roundtrip");
    for name in builders::NAMES {
        let solid = builders::by_name(name).unwrap();
        let path = dir.path().join(format!("{name}.obj"));
        write_obj(&solid, &path).unwrap();
        let back = Solid::try_from_soup(&read_obj(&path).unwrap()).unwrap();
        back.check_consistency().unwrap();
        if solid.ring_count() > 0 {
            // OBJ has no holes: faces with rings come back as triangles,
            // the same surface (same vertices, genus and volume).
            assert_eq!(back.vertex_count(), solid.vertex_count(), "{name}");
            assert_eq!(back.ring_count(), 0);
            assert_eq!(back.shells()[0].genus(), solid.shells()[0].genus());
            assert_eq!(back.volume(), solid.volume(), "{name}");
            continue;
        }
        assert_eq!(
            (back.vertex_count(), back.edge_count(), back.face_count()),
            (solid.vertex_count(), solid.edge_count(), solid.face_count()),
            "{name}"
        );
        // Shortest round-trip formatting: positions come back bit for bit.
        let sorted = |s: &Solid| {
            let mut p: Vec<[f64; 3]> = s.vertices().map(|(_, v)| v.position.to_array()).collect();
            p.sort_by(|a, b| a.partial_cmp(b).unwrap());
            p
        };
        assert_eq!(sorted(&solid), sorted(&back), "{name}");
        assert!(
            (back.volume() - solid.volume()).abs() <= 1e-14 * solid.volume(),
            "{name}"
        );
        // Polygons are kept: the dodecahedron stays 12 pentagons.
        let degrees: Vec<usize> = back.faces().map(|(f, _)| back.face_degree(f)).collect();
        let original: Vec<usize> = solid.faces().map(|(f, _)| solid.face_degree(f)).collect();
        assert_eq!(degrees, original);
    }
}

#[test]
fn obj_text_is_one_based_and_counter_clockwise() {
    let text = to_obj_string(&builders::tetrahedron());
    let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
    assert_eq!(faces.len(), 4);
    assert!(text.lines().filter(|l| l.starts_with("v ")).count() == 4);
    assert!(faces.iter().all(|f| {
        f.split_whitespace()
            .skip(1)
            .all(|i| (1..=4).contains(&i.parse::<usize>().unwrap()))
    }));
}

/// C99 hexadecimal floats (`%a`, as manifold writes its test meshes) read
/// to exactly the bits they name: a cube of side 0.1 at 1e8 written in hex
/// reads back bit for bit as the same cube written in decimal, and
/// validates.
#[test]
fn hexadecimal_floats_read_exactly() {
    fn hex(x: f64) -> String {
        let bits = x.to_bits();
        let sign = if bits >> 63 == 1 { "-" } else { "" };
        let exponent = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1 << 52) - 1);
        if exponent == 0 {
            format!("{sign}0x0.{fraction:013x}p-1022")
        } else {
            format!("{sign}0x1.{fraction:013x}p{:+}", exponent - 1023)
        }
    }
    let cube =
        wingedge::mesh::builders::cuboid(glam::DVec3::splat(1e8), glam::DVec3::splat(1e8 + 0.1))
            .unwrap();
    let decimal = wingedge::io::to_obj_string(&cube);
    let hexadecimal: String = decimal
        .lines()
        .map(|line| match line.strip_prefix("v ") {
            Some(rest) => {
                let xs: Vec<String> = rest
                    .split_whitespace()
                    .map(|t| hex(t.parse().unwrap()))
                    .collect();
                format!("v {}\n", xs.join(" "))
            }
            None => format!("{line}\n"),
        })
        .collect();
    assert!(hexadecimal.contains("v 0x1."), "{hexadecimal}");
    let options = wingedge::io::ObjOptions::default();
    let read = |text: &str| {
        wingedge::io::import_obj_bytes(std::path::Path::new("t.obj"), text.as_bytes(), &options)
            .unwrap()
            .soup
    };
    let (a, b) = (read(&decimal), read(&hexadecimal));
    let bits = |s: &wingedge::mesh::PolygonSoup| -> Vec<[u64; 3]> {
        s.positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect()
    };
    assert_eq!(bits(&a), bits(&b));
    let report =
        wingedge::validate::validate_soup(&b, None, &wingedge::validate::Options::default())
            .unwrap();
    assert!(report.is_valid(), "{report:?}");
}
