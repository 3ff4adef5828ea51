//! Every mesh format through the library: round trips (bit for bit where
//! the format keeps `f64`, within `f32` rounding and counted where it does
//! not), trimesh's exports of one model validating as its OBJ does, and
//! hostile files refused with their exact messages and places.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use glam::DVec3;
use wingedge::io::{
    Format, ImportError, ImportOptions, Location, export_bytes, import, import_bytes,
};
use wingedge::mesh::{Solid, builders};
use wingedge::validate::{Options, validate_import};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join("formats")
}

fn read(bytes: &[u8], format: Format) -> Result<wingedge::io::Import, ImportError> {
    import_bytes(
        Path::new(&format!("t.{format}")),
        bytes,
        format,
        &ImportOptions::default(),
    )
}

/// A solid whose coordinates `f32` cannot hold: the dodecahedron moved off
/// the grid and scaled by π.
fn awkward_solid() -> Solid {
    let soup = builders::by_name("dodecahedron").unwrap().to_soup();
    let positions = soup
        .positions
        .iter()
        .map(|p| *p * std::f64::consts::PI + DVec3::new(0.1, 1e-3 / 3.0, 12345.678))
        .collect();
    Solid::try_from_soup(&wingedge::mesh::PolygonSoup {
        positions,
        polygons: soup.polygons,
    })
    .unwrap()
}

fn vertex_bits(solid: &Solid) -> Vec<[u64; 3]> {
    let mut bits: Vec<[u64; 3]> = solid
        .vertices()
        .map(|(_, v)| v.position.to_array().map(f64::to_bits))
        .collect();
    bits.sort_unstable();
    bits
}

/// OBJ, PLY, OFF and 3MF keep every bit: the same vertices, the same faces
/// (polygons kept in OBJ, PLY, OFF; triangulated in 3MF), the same volume.
#[test]
fn formats_that_keep_f64_round_trip_bit_for_bit() {
    let solid = awkward_solid();
    for format in [Format::Obj, Format::Ply, Format::Off, Format::ThreeMf] {
        let (bytes, report) = export_bytes(&solid, format).unwrap();
        assert_eq!(report.rounded, 0, "{format}");
        assert_eq!(report.warning(Path::new("x")), None);
        let back = read(&bytes, format).unwrap_or_else(|e| panic!("{format}: {e}"));
        let rebuilt = Solid::try_from_soup(&back.soup).unwrap();
        assert_eq!(vertex_bits(&rebuilt), vertex_bits(&solid), "{format}");
        if format == Format::ThreeMf {
            assert_eq!(rebuilt.face_count(), 36, "12 pentagons as 3 triangles each");
        } else {
            assert_eq!(rebuilt.to_soup().polygons.len(), 12, "{format}");
            let original: Vec<Vec<usize>> = solid
                .to_soup()
                .polygons
                .iter()
                .map(|p| p.vertices.to_vec())
                .collect();
            let read: Vec<Vec<usize>> = back
                .soup
                .polygons
                .iter()
                .map(|p| p.vertices.to_vec())
                .collect();
            assert_eq!(
                read, original,
                "{format}: the same polygons in the same order"
            );
        }
        let report = validate_import(&back, &Options::default()).unwrap();
        assert!(report.is_valid(), "{format}: {:?}", report.validity);
        let (a, b) = (report.volume.unwrap(), solid.volume());
        assert!(
            (a - b).abs() <= 1e-12 * b,
            "{format}: volume {a} against {b}"
        );
    }
}

/// STL and glTF hold `f32`: what comes back is each coordinate rounded to
/// `f32`, and the report counts exactly the coordinates that changed.
#[test]
fn f32_formats_round_trip_within_rounding_and_count_it() {
    let solid = awkward_solid();
    let changed = solid
        .vertices()
        .flat_map(|(_, v)| v.position.to_array())
        .filter(|&x| f64::from(x as f32) != x)
        .count();
    assert!(changed > 50);
    let mut expected: Vec<[u64; 3]> = solid
        .vertices()
        .map(|(_, v)| v.position.to_array().map(|x| f64::from(x as f32).to_bits()))
        .collect();
    expected.sort_unstable();
    for format in [Format::Stl, Format::Gltf, Format::Glb] {
        let (bytes, report) = export_bytes(&solid, format).unwrap();
        assert_eq!(report.rounded, changed, "{format}");
        assert_eq!(report.coordinates, 60);
        let warning = report.warning(Path::new("out")).unwrap();
        assert!(
            warning.starts_with(&format!(
                "out: {changed} of 60 coordinates changed when rounded to f32"
            )),
            "{warning}"
        );
        let back = read(&bytes, format).unwrap();
        let rebuilt = Solid::try_from_soup(&back.soup).unwrap();
        assert_eq!(vertex_bits(&rebuilt), expected, "{format}");
        assert_eq!(rebuilt.face_count(), 36);
        if format == Format::Stl {
            assert_eq!(
                back.weld.merged,
                36 * 3 - 20,
                "every repeated corner welded"
            );
        }
        assert!(
            validate_import(&back, &Options::default())
                .unwrap()
                .is_valid()
        );
    }
    // Coordinates `f32` holds exactly are not counted.
    let cube = builders::by_name("cube").unwrap();
    assert_eq!(export_bytes(&cube, Format::Stl).unwrap().1.rounded, 0);
    // Beyond the range of f32: refused, never written as infinity.
    let far = Solid::try_from_soup(&wingedge::mesh::PolygonSoup {
        positions: cube
            .to_soup()
            .positions
            .iter()
            .map(|p| *p * 1e300)
            .collect(),
        polygons: cube.to_soup().polygons,
    })
    .unwrap();
    let e = export_bytes(&far, Format::Glb).unwrap_err();
    assert!(
        e.to_string()
            .contains("beyond the range of f32 that glb holds"),
        "{e}"
    );
    assert!(export_bytes(&far, Format::Ply).is_ok());
}

/// trimesh's exports of one torus validate to the verdict, counts and
/// volume of its OBJ, in every format.
#[test]
fn trimesh_exports_validate_as_their_obj() {
    let summary = |name: &str| {
        let import = import(&fixtures().join(name), &ImportOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let report = validate_import(&import, &Options::default()).unwrap();
        (report, import)
    };
    let (obj, _) = summary("torus.obj");
    assert!(obj.is_valid());
    for name in [
        "torus.stl",
        "torus_ascii.stl",
        "torus.ply",
        "torus_ascii.ply",
        "torus.off",
        "torus.3mf",
        "torus.glb",
        "torus.gltf",
    ] {
        let (report, import) = summary(name);
        assert_eq!(report.validity, obj.validity, "{name}");
        assert_eq!(
            (report.vertices, report.edges, report.faces, report.genus),
            (obj.vertices, obj.edges, obj.faces, obj.genus),
            "{name}"
        );
        let (a, b) = (report.volume.unwrap(), obj.volume.unwrap());
        assert!((a - b).abs() < 1e-6 * b, "{name}: volume {a} against {b}");
        if name.ends_with(".stl") {
            assert_eq!(import.weld.merged, 192 * 3 - 96, "{name}");
        }
    }
    for name in ["two_boxes.3mf", "two_boxes.glb"] {
        let (report, import) = summary(name);
        assert!(report.is_valid(), "{name}");
        assert_eq!((report.shells, report.faces), (2, 24), "{name}");
        assert!((report.volume.unwrap() - 3.0).abs() < 1e-12, "{name}");
        let groups: std::collections::BTreeSet<_> = import
            .soup
            .polygons
            .iter()
            .map(|p| p.attributes.group.as_deref().unwrap().to_string())
            .collect();
        assert_eq!(groups.len(), 2, "{name}: one group per object");
    }
}

/// Every polygon says where it came from.
#[test]
fn polygons_are_located_in_their_files() {
    let at = |name: &str, polygon: usize| {
        let import = import(&fixtures().join(name), &ImportOptions::default()).unwrap();
        import.location(polygon).unwrap().to_string()
    };
    assert_eq!(at("torus.stl", 5), "triangle 5 (byte 334)");
    assert_eq!(at("torus_ascii.stl", 0), "line 2");
    assert_eq!(at("torus.off", 0), "line 99");
    assert!(at("torus.ply", 1).starts_with("face 1 (byte "));
    assert_eq!(
        at("two_boxes.3mf", 13),
        "3D/3dmodel.model: /model/resources/object[@id='2']/mesh/triangles/triangle[2] (build item 2)"
    );
    assert!(
        at("torus.glb", 3)
            .starts_with("meshes[0].primitives[0] triangle 3 (accessors[0], placed by nodes["),
        "{}",
        at("torus.glb", 3)
    );
}

fn zip(entries: &[(&str, &[u8])], method: zip::CompressionMethod) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options = zip::write::SimpleFileOptions::default().compression_method(method);
    for (name, content) in entries {
        zip.start_file(*name, options).unwrap();
        zip.write_all(content).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

/// Hostile files of each format: refused with the message and the place.
#[test]
fn hostile_files_are_refused_with_their_place() {
    let message = |bytes: &[u8], format| read(bytes, format).unwrap_err().to_string();
    let stl = std::fs::read(fixtures().join("torus.stl")).unwrap();
    // A binary STL cut short, and one whose count claims 10^9 triangles.
    assert_eq!(
        message(&stl[..1000], Format::Stl),
        "t.stl: byte 80: the file ends after 1000 bytes, but the binary header's count of 192 triangles needs 9684 bytes (truncated, or a count that lies)"
    );
    let mut lying = stl[..1024].to_vec();
    lying[80..84].copy_from_slice(&1_000_000_000u32.to_le_bytes());
    assert!(
        message(&lying, Format::Stl)
            .contains("count of 1000000000 triangles needs 50000000084 bytes")
    );
    let mut nan = stl.clone();
    nan[84 + 50 * 7 + 16..84 + 50 * 7 + 20].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = message(&nan, Format::Stl);
    assert!(
        e.starts_with("t.stl: triangle 7 (byte 434): vertex 21 has a non-finite coordinate ("),
        "{e}"
    );
    assert!(e.contains("NaN"), "{e}");

    // PLY: a face count that lies, an index out of range.
    let ply = std::fs::read(fixtures().join("torus.ply")).unwrap();
    let text = String::from_utf8_lossy(&ply);
    let header_end = text.find("end_header\n").unwrap() + 11;
    let header = text[..header_end].replace("element face 192", "element face 1000000000");
    let mut lying = header.into_bytes();
    lying.extend_from_slice(&ply[header_end..]);
    let e = message(&lying, Format::Ply);
    assert!(e.contains("the header's 1000000000 `face` records"), "{e}");
    let ascii = std::fs::read_to_string(fixtures().join("torus_ascii.ply")).unwrap();
    let bad_index = ascii.replacen("\n3 ", "\n3 96 ", 1);
    let e = message(bad_index.as_bytes(), Format::Ply);
    assert!(
        e.contains("vertex index 96 is out of range: 96 vertices are defined"),
        "{e}"
    );

    // OFF: NaN.
    let off = std::fs::read_to_string(fixtures().join("torus.off")).unwrap();
    let first_vertex = off.lines().nth(2).unwrap();
    let nan = off.replacen(first_vertex, "nan 0 0", 1);
    assert_eq!(
        message(nan.as_bytes(), Format::Off),
        "t.off:3: vertex 0 has a non-finite coordinate (NaN, 0, 0)"
    );

    // 3MF: a zip bomb (50 MB of spaces in a 50 KB entry), a declared size
    // beyond the limit, an index out of range.
    let mut bomb = b"<model>".to_vec();
    bomb.resize(50_000_000, b' ');
    let packed = zip(
        &[("3D/3dmodel.model", &bomb)],
        zip::CompressionMethod::Deflated,
    );
    assert!(packed.len() < 200_000, "{}", packed.len());
    let e = message(&packed, Format::ThreeMf);
    assert!(
        e.starts_with("t.3mf: 3D/3dmodel.model: a zip entry of "),
        "{e}"
    );
    assert!(e.contains("(a zip bomb?) exceeds the limit of"), "{e}");
    let model = std::fs::read(fixtures().join("two_boxes.3mf")).unwrap();
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(model)).unwrap();
    let mut xml = String::new();
    std::io::Read::read_to_string(&mut archive.by_name("3D/3dmodel.model").unwrap(), &mut xml)
        .unwrap();
    let broken = xml.replacen(
        "<triangle v1=\"1\" v2=\"3\" v3=\"0\" />",
        "<triangle v1=\"1\" v2=\"8\" v3=\"0\" />",
        1,
    );
    let e = message(
        &zip(
            &[("3D/3dmodel.model", broken.as_bytes())],
            zip::CompressionMethod::Stored,
        ),
        Format::ThreeMf,
    );
    assert_eq!(
        e,
        "t.3mf: 3D/3dmodel.model: /model/resources/object[@id='1']/mesh/triangles/triangle[1]: vertex index 8 is out of range: 8 vertices are defined"
    );
    let nan = xml.replacen("x=\"-0.5\"", "x=\"NaN\"", 1);
    let e = message(
        &zip(
            &[("3D/3dmodel.model", nan.as_bytes())],
            zip::CompressionMethod::Stored,
        ),
        Format::ThreeMf,
    );
    assert_eq!(
        e,
        "t.3mf: 3D/3dmodel.model: /model/resources/object[@id='1']/mesh/vertices/vertex[1]: `x` is not finite: NaN"
    );
    let e = message(b"PK\x03\x04 not really", Format::ThreeMf);
    assert!(
        e.starts_with("t.3mf: byte 0: not a 3MF file (a zip archive)"),
        "{e}"
    );

    // glTF: JSON nested too deep, an accessor whose count lies, a buffer
    // outside the document's folder.
    let deep = format!("{}{}", "[".repeat(200), "]".repeat(200));
    let e = message(deep.as_bytes(), Format::Gltf);
    assert!(e.contains("nested deeper than 128 levels"), "{e}");
    let gltf = std::fs::read_to_string(fixtures().join("torus.gltf")).unwrap();
    let lying = gltf.replacen("\"count\":576", "\"count\":5760000", 1);
    assert_eq!(
        message(lying.as_bytes(), Format::Gltf),
        "t.gltf: accessors[0]: 5760000 elements of 4 bytes, 4 apart from byte 0, do not fit in bufferViews[0]'s 2304 bytes (a count that lies)"
    );
    let outside = gltf.replacen("\"uri\":\"data:", "\"uri\":\"../../etc/passwd#", 1);
    let e = message(outside.as_bytes(), Format::Gltf);
    assert!(e.contains("buffers[0].uri: `../../etc/passwd#"), "{e}");
    assert!(
        e.contains("only `data:` URIs and relative paths inside the document's folder are read"),
        "{e}"
    );
    let glb = std::fs::read(fixtures().join("torus.glb")).unwrap();
    let e = message(&glb[..glb.len() - 10], Format::Glb);
    assert!(e.starts_with("t.glb: byte 8: the file ends after"), "{e}");
}

/// A file that is no mesh at all, for every format: an error naming the
/// file and the place, and `Location` of the first thing wrong.
#[test]
fn empty_and_foreign_files_are_refused() {
    // An empty OBJ file is the empty solid, as `to_obj_string` writes it;
    // the other formats have a header to miss.
    let empty = read(b"", Format::Obj).unwrap();
    assert!(empty.soup.positions.is_empty() && empty.soup.polygons.is_empty());
    for format in Format::ALL {
        if format != Format::Obj {
            let e = read(b"", format).unwrap_err();
            assert!(
                e.to_string().starts_with(&format!("t.{format}")),
                "{format}: {e}"
            );
        }
        let e = read(b"\x00\x01\x02 garbage", format).unwrap_err();
        assert!(
            e.to_string().starts_with(&format!("t.{format}")),
            "{format}: {e}"
        );
    }
    let e = read(b"solid x\nendsolid x\n", Format::Stl).unwrap_err();
    assert_eq!(
        e.to_string(),
        "t.stl: holds no faces (stl file with no triangles or polygons)"
    );
    assert_eq!(e.location(), None);
    let e = read(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", Format::Off).unwrap_err();
    assert_eq!(e.location(), Some(Location::Line(6)));
}
