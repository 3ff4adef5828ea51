//! Benchmarks of the validate layer: every check (self-intersection
//! included) on a closed triangulated sphere, and the OBJ import of the same
//! sphere. `examples/validate_bench.rs` times a whole file end to end and
//! `benches/peers_validate.py` compares it with trimesh + manifold3d.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;
use wingedge::io::{ObjOptions, import_obj_bytes, to_obj_string};
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::validate::{Options, validate_soup};

/// A closed triangulated UV sphere with about `4 n²` triangles.
fn sphere_soup(n: usize) -> PolygonSoup {
    let (rings, segments) = (n, 2 * n);
    let mut positions = vec![DVec3::Z, -DVec3::Z];
    for i in 1..rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ));
        }
    }
    let at = |i: usize, j: usize| 2 + (i - 1) * segments + j % segments;
    let mut polygons: Vec<Vec<usize>> = Vec::new();
    for j in 0..segments {
        polygons.push(vec![0, at(1, j), at(1, j + 1)]);
        polygons.push(vec![1, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            polygons.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            polygons.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    PolygonSoup::new(positions, polygons)
}

fn validate(c: &mut Criterion) {
    let mut group = c.benchmark_group("validate");
    group.sample_size(10);
    for n in [64, 256] {
        let soup = sphere_soup(n);
        group.bench_with_input(
            BenchmarkId::new("sphere_all_checks", soup.polygons.len()),
            &soup,
            |b, soup| {
                b.iter(|| {
                    let report = validate_soup(black_box(soup), None, &Options::default())
                        .expect("a finite soup");
                    assert!(report.is_valid());
                })
            },
        );
    }
    let soup = sphere_soup(256);
    let text = to_obj_string(&Solid::try_from_soup(&soup).expect("closed sphere"));
    group.bench_function(BenchmarkId::new("import_obj", soup.polygons.len()), |b| {
        b.iter(|| {
            import_obj_bytes(
                std::path::Path::new("sphere.obj"),
                black_box(text.as_bytes()),
                &ObjOptions::default(),
            )
            .expect("valid OBJ")
        })
    });
    group.finish();
}

criterion_group!(benches, validate);
criterion_main!(benches);
