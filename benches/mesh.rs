//! Benchmarks of the mesh layer: building winged-edge solids from soups and
//! walking their adjacency.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;
use wingedge::mesh::{PolygonSoup, Solid};

/// A closed triangulated UV sphere with about `2 n²` triangles.
fn sphere_soup(n: usize) -> PolygonSoup {
    let rings = n;
    let segments = 2 * n;
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

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group.sample_size(10);
    for n in [32, 256] {
        let soup = sphere_soup(n);
        group.bench_with_input(
            BenchmarkId::new("sphere_triangles", soup.polygons.len()),
            &soup,
            |b, soup| b.iter(|| Solid::try_from_soup(black_box(soup)).expect("closed sphere")),
        );
    }
    group.finish();
}

fn traverse(c: &mut Criterion) {
    let solid = Solid::try_from_soup(&sphere_soup(128)).expect("closed sphere");
    c.bench_function("vertex_stars_all", |b| {
        b.iter(|| {
            solid
                .vertices()
                .map(|(v, _)| solid.vertex_edges(v).count())
                .sum::<usize>()
        })
    });
    c.bench_function("volume", |b| b.iter(|| black_box(&solid).volume()));
}

criterion_group!(benches, build, traverse);
criterion_main!(benches);
