//! Arbitrary bytes as an OBJ file → import → build → every validation check,
//! the path `wingedge validate` takes. A bad file must give an `ObjError`
//! naming the file, never a panic.
//!
//! When the default import succeeds the bytes are imported again with the
//! tolerance weld of `--weld 1e-3`, so both weld paths see hostile soups. A solid
//! that validation builds must pass the winged-edge consistency check and
//! read back after the OBJ writer.

use std::path::Path;

use wingedge::geom::Tolerance;
use wingedge::io::{ObjOptions, WeldMode, import_obj_bytes, to_obj_string};
use wingedge::validate::{Options, validate_and_build};

/// Checks one input.
pub fn run(data: &[u8]) {
    if validate(data, WeldMode::Exact) {
        let tolerance = Tolerance {
            weld: 1e-3,
            ..Tolerance::default()
        };
        validate(data, WeldMode::Within(tolerance));
    }
}

/// Whether the bytes imported.
fn validate(bytes: &[u8], weld: WeldMode) -> bool {
    let path = Path::new("fuzz.obj");
    let import = match import_obj_bytes(
        path,
        bytes,
        &ObjOptions {
            weld,
            ..ObjOptions::default()
        },
    ) {
        Ok(import) => import,
        Err(e) => {
            assert!(e.to_string().starts_with("fuzz.obj"), "{e}");
            return false;
        }
    };
    assert_eq!(import.vertex_lines.len(), import.soup.positions.len());
    assert!(import.soup.positions.iter().all(|p| p.is_finite()));
    let (report, solid) = validate_and_build(&import, &Options::default())
        .expect("an imported soup is in range and finite");
    serde_json::to_string(&report).expect("a report serializes");
    assert!(report.violations.iter().all(|v| !v.message.is_empty()));
    if let Some(solid) = solid {
        solid
            .check_consistency()
            .expect("validation builds consistent solids");
        let written = to_obj_string(&solid);
        import_obj_bytes(path, written.as_bytes(), &ObjOptions::default())
            .expect("a written solid reads back");
    }
    true
}
