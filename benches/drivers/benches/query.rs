//! Benchmarks of the query layer on a generated UV sphere (seeded inputs):
//! accel build, point classification (parity, batch) and first-hit rays.
//!
//! The comparison with the peers (same meshes, points and rays, one run)
//! is `benches/peers/run.py`, which drives `benches/drivers/src/bin/peers_wingedge.rs`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;
use wingedge::geom::Ray;
use wingedge::mesh::builders;
use wingedge::query::{Accel, Method};

#[path = "../../../src/test_rng.rs"]
mod test_rng;
use test_rng::uniform;

fn points(n: usize) -> Vec<DVec3> {
    let mut u = uniform(0x9E37_79B9_7F4A_7C15);
    (0..n)
        .map(|_| DVec3::new(u(), u(), u()) * 2.0 - DVec3::ONE)
        .collect()
}

fn rays(n: usize) -> Vec<Ray> {
    let mut u = uniform(0xD1B5_4A32_D192_ED03);
    (0..n)
        .map(|_| {
            let o = (DVec3::new(u(), u(), u()) * 2.0 - DVec3::ONE).normalize_or(DVec3::X) * 2.6;
            let target = DVec3::new(u(), u(), u()) * 2.0 - DVec3::ONE;
            Ray::new(o, (target - o).normalize())
        })
        .collect()
}

fn query(c: &mut Criterion) {
    let mut group = c.benchmark_group("query");
    group.sample_size(10);
    for n in [50, 200] {
        let solid = builders::sphere(n);
        let tris = solid.face_count();
        group.throughput(Throughput::Elements(tris as u64));
        group.bench_with_input(BenchmarkId::new("accel_build", tris), &solid, |b, s| {
            b.iter(|| Accel::new(black_box(s)))
        });
        let accel = Accel::new(&solid);
        let pts = points(100_000);
        group.throughput(Throughput::Elements(pts.len() as u64));
        group.bench_with_input(BenchmarkId::new("classify_parity", tris), &pts, |b, p| {
            b.iter(|| accel.classify_batch(black_box(p), Method::Parity))
        });
        let rs = rays(100_000);
        group.throughput(Throughput::Elements(rs.len() as u64));
        group.bench_with_input(BenchmarkId::new("first_hit", tris), &rs, |b, r| {
            b.iter(|| accel.first_hit_batch(black_box(r)))
        });
        group.bench_with_input(BenchmarkId::new("ray_crossings", tris), &rs, |b, r| {
            b.iter(|| accel.ray_crossings_batch(black_box(r)))
        });
    }
    group.finish();
}

criterion_group!(benches, query);
criterion_main!(benches);
