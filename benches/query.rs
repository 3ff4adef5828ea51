//! Benchmarks of the query layer on a generated UV sphere (seeded inputs):
//! accel build, point classification (parity, batch) and first-hit rays.
//!
//! The table against the peers on the shared meshes comes from
//! `examples/query_table.rs` and `examples/peers_query.py`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;
use wingedge::geom::Ray;
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::query::{Accel, Method};

/// A closed triangulated UV sphere with about `4 n²` triangles.
fn sphere(n: usize) -> Solid {
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
    Solid::try_from_soup(&PolygonSoup::new(positions, polygons)).expect("closed sphere")
}

/// Seeded uniform numbers in [0, 1).
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

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
        let solid = sphere(n);
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
