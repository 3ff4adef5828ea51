//! Arbitrary bytes as each binary mesh format (binary STL, binary PLY,
//! 3MF, GLB) and, through the first byte, as the text ones: the readers
//! must refuse or read, never panic or allocate beyond the input; what is
//! read has finite positions and indices in range, builds or is refused
//! by the solid's builder, and a built solid written back in the same
//! format reads back with as many faces.

use std::path::Path;

use wingedge::io::{Format, ImportOptions, WeldMode, export_bytes, import_bytes};
use wingedge::mesh::Solid;

/// The formats, picked by the input's first byte (the rest is the file).
const FORMATS: [Format; 6] = [
    Format::Stl,
    Format::Ply,
    Format::ThreeMf,
    Format::Glb,
    Format::Off,
    Format::Gltf,
];

/// Reads `bytes` as `format` and checks what comes back.
pub fn check(format: Format, bytes: &[u8]) {
    let path = Path::new("fuzz.mesh");
    for weld in [WeldMode::Exact, WeldMode::None] {
        let options = ImportOptions {
            format: Some(format),
            weld,
            ..ImportOptions::default()
        };
        let import = match import_bytes(path, bytes, format, &options) {
            Ok(import) => import,
            Err(e) => {
                assert!(e.to_string().starts_with("fuzz.mesh"), "unnamed error: {e}");
                return;
            }
        };
        let soup = &import.soup;
        assert!(!soup.polygons.is_empty(), "an import without faces");
        assert_eq!(import.vertex_numbers.len(), soup.positions.len());
        assert!(
            soup.positions.iter().all(|p| p.is_finite()),
            "a non-finite position"
        );
        for (i, p) in soup.polygons.iter().enumerate() {
            assert!(
                p.vertices.len() >= 3,
                "polygon {i} of {} corners",
                p.vertices.len()
            );
            assert!(
                p.vertices.iter().all(|&v| v < soup.positions.len()),
                "polygon {i} out of range"
            );
            assert!(
                import.location(i).is_some(),
                "polygon {i} without a location"
            );
        }
        let Ok(solid) = Solid::try_from_soup(soup) else {
            continue;
        };
        solid
            .check_consistency()
            .expect("a built solid is consistent");
        if solid.face_count() > 0
            && solid
                .faces()
                .all(|(f, _)| solid.face_vertices(f).count() == 3)
            && let Ok((written, _)) = export_bytes(&solid, format)
        {
            let back = import_bytes(path, &written, format, &ImportOptions::default())
                .unwrap_or_else(|e| panic!("what was written does not read back: {e}"));
            assert_eq!(back.soup.polygons.len(), solid.face_count());
        }
    }
}

/// The fuzz target's entry: the first byte picks the format.
pub fn run(data: &[u8]) {
    if let Some((&pick, bytes)) = data.split_first() {
        check(FORMATS[pick as usize % FORMATS.len()], bytes);
    }
}
