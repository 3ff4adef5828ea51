//! Times first-hit ray casting alone on one shared mesh (profiling aid):
//! `ray_probe MESHES NAME` prints ns per ray on one thread, one query at a
//! time and as a batch (the interleaved stream walk), alternating.
use glam::DVec3;
use wingedge::geom::Ray;
use wingedge::io::read_obj;
use wingedge::mesh::Solid;
use wingedge::query::Accel;
fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_default());
    let name = std::env::args().nth(2).unwrap_or_default();
    let soup = read_obj(&dir.join(format!("{name}.obj"))).expect("obj");
    let solid = Solid::try_from_soup(&soup).expect("solid");
    let accel = Accel::new(&solid);
    let bytes = std::fs::read(dir.join(format!("{name}.rays.f64"))).expect("rays");
    let r: Vec<f64> = bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    let rays: Vec<Ray> = r
        .chunks_exact(6)
        .map(|c| Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5])))
        .collect();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    for _ in 0..3 {
        let t = std::time::Instant::now();
        let n = rays
            .iter()
            .filter(|r| accel.first_hit(r).ok().flatten().is_some())
            .count();
        let a = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        let m = pool.install(|| {
            accel
                .first_hit_batch(&rays)
                .map(|h| h.iter().filter(|x| x.is_some()).count())
        });
        let b = t.elapsed().as_secs_f64();
        println!(
            "{name}: one at a time {:.0} ns/ray ({n} hits), batch {:.0} ns/ray ({m:?})",
            a * 1e3,
            b * 1e3
        );
    }
}
