//! manifold3d, the independent oracle, on marching-cubes output: it must
//! accept every mesh as a manifold (status `NoError`) with wingedge's
//! genus, triangle count and volume. Requires the oracle
//! (`python3 -m pip install -r tests/oracle/requirements.txt`).

use std::fmt::Write as _;
use std::path::Path;
use wingedge::SetOp;

use glam::DVec3;
use serde_json::Value;
use wingedge::field::marching::{march_grid, solid_of};
use wingedge::field::{
    Blobs, Falloff, Field, FieldCsg, MarchingOptions, Placement, SampleGrid, Source, load_json,
    try_mesh,
};
use wingedge::mesh::PolygonSoup;
use wingedge::validate::{Options, validate_soup};

use crate::common::test_rng;

fn obj(soup: &PolygonSoup) -> String {
    let mut text = String::new();
    for p in &soup.positions {
        writeln!(text, "v {:?} {:?} {:?}", p.x, p.y, p.z).unwrap();
    }
    for polygon in &soup.polygons {
        let corners: Vec<String> = polygon
            .vertices
            .iter()
            .map(|i| (i + 1).to_string())
            .collect();
        writeln!(text, "f {}", corners.join(" ")).unwrap();
    }
    text
}

fn blob(c: DVec3, r: f64, w: f64) -> Box<dyn Field> {
    Box::new(Blobs::try_new(vec![Source::try_new(c, r, w).unwrap()], Falloff::SoftObject).unwrap())
}

#[test]
fn manifold3d_accepts_marching_cubes_meshes_with_the_same_genus_and_volume() {
    let mut meshes: Vec<(String, PolygonSoup)> = Vec::new();
    let three = load_json(Path::new("fixtures/fields/three_blobs.json")).unwrap();
    for (resolution, placement) in [
        (24, Placement::Interpolated),
        (48, Placement::Interpolated),
        (40, Placement::Midpoint),
    ] {
        let opts = MarchingOptions {
            resolution,
            placement,
            ..MarchingOptions::default()
        };
        meshes.push((
            format!("three_{resolution}.obj"),
            try_mesh(three.field.as_ref(), &opts).unwrap().soup,
        ));
    }
    // A torus-like ring of blobs (genus 1) and a carved pair.
    let ring: Vec<Source> = (0..12)
        .map(|i| {
            let a = f64::from(i) * std::f64::consts::TAU / 12.0;
            Source::try_new(DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), 0.0), 1.2, 1.0).unwrap()
        })
        .collect();
    let ring = Blobs::try_new(ring, Falloff::SoftObject).unwrap();
    meshes.push((
        "ring.obj".into(),
        try_mesh(
            &ring,
            &MarchingOptions {
                resolution: 40,
                ..MarchingOptions::default()
            },
        )
        .unwrap()
        .soup,
    ));
    let carved = FieldCsg::new(
        SetOp::Difference,
        blob(DVec3::ZERO, 2.0, 1.0),
        blob(DVec3::new(0.0, 0.0, 0.9), 1.4, 1.0),
    );
    meshes.push((
        "carved.obj".into(),
        try_mesh(
            &carved,
            &MarchingOptions {
                resolution: 30,
                ..MarchingOptions::default()
            },
        )
        .unwrap()
        .soup,
    ));
    // Random sample grids.
    let mut u = test_rng::uniform(24);
    for n in 0..20 {
        let values: Vec<f64> = (0..6 * 5 * 4).map(|_| u()).collect();
        let grid = SampleGrid::try_new(DVec3::ZERO, 0.5, [6, 5, 4], values).unwrap();
        let (soup, _) = march_grid(&grid, &MarchingOptions::default());
        if !soup.polygons.is_empty() {
            meshes.push((format!("random_{n}.obj"), soup));
        }
    }
    assert!(meshes.len() > 20);

    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("marching-cubes-oracle");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let paths: Vec<_> = meshes
        .iter()
        .map(|(name, soup)| {
            let path = dir.join(name);
            std::fs::write(&path, obj(soup)).unwrap();
            path
        })
        .collect();
    let stdout = crate::common::oracle::run("marching_cubes_oracle.py", &paths);
    let answers: Value = serde_json::from_slice(&stdout).expect("the oracle's JSON");
    let mut genus_one = 0;
    for (name, soup) in &meshes {
        let oracle = &answers[name.as_str()];
        assert_eq!(oracle["status"], "NoError", "{name}: {oracle}");
        let report = validate_soup(soup, None, &Options::default()).unwrap();
        assert!(report.is_valid(), "{name}");
        let volume = solid_of(soup).unwrap().volume();
        let theirs = oracle["volume"].as_f64().unwrap();
        assert!(
            (volume - theirs).abs() <= 1e-9 * volume.abs(),
            "{name}: {volume} vs {theirs}"
        );
        assert_eq!(
            oracle["triangles"].as_u64().unwrap() as usize,
            soup.polygons.len(),
            "{name}"
        );
        let shells = report.shell_details.len();
        // Genus compared on single shells (the two count several shells
        // differently).
        let genus: i64 = report.genus.expect("a genus");
        if shells == 1 {
            assert_eq!(oracle["genus"].as_i64().unwrap(), genus, "{name}");
        }
        if name == "ring.obj" {
            assert_eq!(genus, 1);
            genus_one += 1;
        }
    }
    assert_eq!(genus_one, 1);
}
