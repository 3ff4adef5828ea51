//! Cross-checks against manifold3d, the independent oracle.
//!
//! `tests/oracle/manifold_oracle.py` builds meshes with manifold3d's own
//! primitives and booleans (seeded) and records manifold3d's answers about
//! them; these tests read the same meshes with wingedge and compare. The
//! oracle is required: without it these tests fail and say how to install it
//! (`python3 -m pip install -r tests/oracle/requirements.txt`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use serde_json::Value;
use wingedge::io::read_obj;
use wingedge::mesh::Solid;

/// Runs the oracle once per test binary and returns its output folder.
fn oracle() -> &'static (PathBuf, Value) {
    static ORACLE: OnceLock<(PathBuf, Value)> = OnceLock::new();
    ORACLE.get_or_init(|| {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/oracle/manifold_oracle.py");
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("manifold-oracle");
        let run = Command::new("python3")
            .arg(&script)
            .arg(&out)
            .output()
            .unwrap_or_else(|e| panic!("cannot run python3 for the manifold3d oracle: {e}"));
        assert!(
            run.status.success(),
            "the manifold3d oracle failed (exit {:?}):\n{}\ninstall it with: python3 -m pip install -r tests/oracle/requirements.txt",
            run.status.code(),
            String::from_utf8_lossy(&run.stderr)
        );
        let text = std::fs::read_to_string(out.join("oracle.json")).expect("the oracle writes oracle.json");
        (out, serde_json::from_str(&text).expect("oracle.json is JSON"))
    })
}

fn load(dir: &Path, name: &str) -> Solid {
    let soup = read_obj(&dir.join(format!("{name}.obj"))).unwrap_or_else(|e| panic!("{name}: {e}"));
    Solid::try_from_soup(&soup).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn counts_genus_and_volume_agree_with_manifold3d() {
    let (dir, report) = oracle();
    let meshes = report["meshes"].as_object().expect("meshes");
    assert!(
        meshes.len() >= 10,
        "the oracle made {} meshes",
        meshes.len()
    );
    for (name, expected) in meshes {
        let solid = load(dir, name);
        solid.check_consistency().unwrap();
        assert_eq!(expected["status"], "NoError", "{name}");
        let counts = (solid.vertex_count(), solid.edge_count(), solid.face_count());
        let want = |k: &str| expected[k].as_u64().expect("count") as usize;
        assert_eq!(
            counts,
            (want("vertices"), want("edges"), want("faces")),
            "{name}: V, E, F"
        );
        assert!(solid.is_closed(), "{name}");
        let shells = solid.shells();
        assert_eq!(shells.len(), 1, "{name}");
        assert_eq!(
            shells[0].genus(),
            expected["genus"].as_i64(),
            "{name}: genus"
        );
        let volume = expected["volume"].as_f64().expect("volume");
        let relative = (solid.volume() - volume).abs() / volume.abs();
        assert!(
            relative <= 1e-9,
            "{name}: volume {} vs manifold3d {volume} (relative {relative:e})",
            solid.volume()
        );
        println!(
            "{name}: V={} E={} F={} genus={:?} volume={} (manifold3d {volume}, rel {relative:.1e})",
            counts.0,
            counts.1,
            counts.2,
            shells[0].genus(),
            solid.volume()
        );
    }
}
