//! Cells of a closed OBJ solid, timed for the comparison with trimesh's
//! voxelization (`benches/peers/cells_peer.py`): one JSON line with the
//! time of `Octree::classify` (the BVH, the exact face tiles and the
//! labelling; reading and building the solid are not timed), the interval,
//! the counts and the peak resident memory of this process.
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin cells_bench -- MODEL.obj DEPTH [REPEATS]
//! ```
//!
//! The best of `REPEATS` (default 3) runs is printed.

use std::path::Path;
use std::time::Instant;

use wingedge::cells::{Label, Octree};
use wingedge::io::read_obj;
use wingedge::mesh::Solid;

#[path = "../peers_io.rs"]
#[allow(dead_code)]
mod peers_io;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(model), Some(depth)) = (args.first(), args.get(1)) else {
        return Err("usage: cells_bench MODEL.obj DEPTH [REPEATS]".into());
    };
    let depth: u32 = depth.parse()?;
    let repeats: usize = args.get(2).map_or(Ok(3), |r| r.parse())?;
    let soup = read_obj(Path::new(model))?;
    let solid = Solid::try_from_soup(&soup)?;
    let memory_before = peers_io::peak_rss_mib();
    let mut best = f64::INFINITY;
    let mut tree = None;
    for _ in 0..repeats.max(1) {
        // The previous tree is dropped first, so that peak memory is one tree's.
        drop(tree.take());
        let start = Instant::now();
        let t = Octree::classify(&solid, depth)?;
        best = best.min(start.elapsed().as_secs_f64());
        tree = Some(t);
    }
    let tree = tree.ok_or("no run")?;
    let (low, high) = tree.try_volume_bounds().unwrap();
    let count = |label| tree.leaves().iter().filter(|c| c.label == label).count();
    let (origin, side) = tree.root();
    println!(
        "{{\"triangles\": {}, \"depth\": {depth}, \"threads\": {}, \"seconds\": {best:.4}, \
         \"cell\": {}, \"root_origin\": [{}, {}, {}], \"root_side\": {side}, \
         \"v_in\": {low}, \"v_high\": {high}, \"mesh_volume\": {}, \"leaves\": {}, \
         \"in\": {}, \"on\": {}, \"out\": {}, \"regions\": {}, \
         \"peak_rss_mib_before\": {}, \"peak_rss_mib\": {}}}",
        soup.polygons.len(),
        rayon::current_num_threads(),
        side / f64::from(1u32 << depth),
        origin.x,
        origin.y,
        origin.z,
        solid.volume(),
        tree.leaves().len(),
        count(Label::In),
        count(Label::On),
        count(Label::Out),
        tree.regions(),
        memory_before.unwrap_or(f64::NAN),
        peers_io::peak_rss_mib().unwrap_or(f64::NAN),
    );
    Ok(())
}
