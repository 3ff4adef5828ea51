//! Benchmarks of the mesh layer: building winged-edge solids from soups and
//! walking their adjacency.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wingedge::mesh::{Solid, builders};

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    group.sample_size(10);
    for n in [32, 256] {
        let soup = builders::sphere_soup(n);
        group.bench_with_input(
            BenchmarkId::new("sphere_triangles", soup.polygons.len()),
            &soup,
            |b, soup| b.iter(|| Solid::try_from_soup(black_box(soup)).expect("closed sphere")),
        );
    }
    group.finish();
}

fn traverse(c: &mut Criterion) {
    let solid = Solid::try_from_soup(&builders::sphere_soup(128)).expect("closed sphere");
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
