//! Benchmarks of the validate layer: every check (self-intersection
//! included) on a closed triangulated sphere, and the OBJ import of the same
//! sphere. `benches/drivers/src/bin/peers_wingedge.rs validate` times a whole file end to
//! end and `benches/peers/run.py` compares it with trimesh + manifold3d and
//! parry.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use wingedge::io::{ObjOptions, import_obj_bytes, to_obj_string};
use wingedge::mesh::{Solid, builders};
use wingedge::validate::{Options, validate_soup};

fn validate(c: &mut Criterion) {
    let mut group = c.benchmark_group("validate");
    group.sample_size(10);
    for n in [64, 256] {
        let soup = builders::sphere_soup(n);
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
    let soup = builders::sphere_soup(256);
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
