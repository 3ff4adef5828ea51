//! `wingedge cells SOLID.obj --depth N [--npy OUT]`: the octree cells of a
//! solid, In, Out or On, with the certified volume interval.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use wingedge::cells::{Label, MAX_DENSE_DEPTH, Octree, write_npy};
use wingedge::io::read_obj;
use wingedge::mesh::Solid;
use wingedge::scene::is_scene_path;

use crate::output::{Out, Outcome};

pub fn run(target: &Path, depth: u32, npy: Option<&Path>) -> Outcome {
    if is_scene_path(target) {
        return Err(format!(
            "{}: cells of scene files are not built yet; give a solid (.obj)",
            target.display()
        ));
    }
    if npy.is_some() && depth > MAX_DENSE_DEPTH {
        return Err(format!(
            "--npy: depth {depth} is beyond the limit of {MAX_DENSE_DEPTH} for a dense array"
        ));
    }
    let soup = read_obj(target).map_err(|e| e.to_string())?;
    let solid = Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", target.display()))?;
    let start = Instant::now();
    let tree = Octree::classify(&solid, depth).map_err(|e| format!("{}: {e}", target.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    let mut out = Out::new();
    let (origin, side) = tree.root();
    out.write(format_args!(
        "{}: depth {depth}, root cube at ({}, {}, {}) of side {side}\n",
        target.display(),
        origin.x,
        origin.y,
        origin.z
    ))?;
    out.write("depth        in       out        on\n")?;
    for (d, c) in tree.counts().iter().enumerate() {
        out.write(format_args!(
            "{d:5} {:9} {:9} {:9}\n",
            c.inside, c.outside, c.on
        ))?;
    }
    let (low, high) = tree.volume_bounds();
    out.write(format_args!(
        "volume in [{low}, {high}] (certified; the mesh's rounded volume is {})\n",
        solid.volume()
    ))?;
    out.write(format_args!(
        "{} leaves, {} point classifications (one per region), {seconds:.3} s\n",
        tree.leaves().len(),
        tree.regions()
    ))?;
    out.finish()?;
    if let Some(path) = npy {
        let dense = tree
            .dense()
            .map_err(|e| format!("{}: --npy: {e}", path.display()))?;
        write_npy(path, &dense, 1 << tree.depth())
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        let on = tree
            .leaves()
            .iter()
            .filter(|c| c.label == Label::On)
            .count();
        eprintln!(
            "wrote {} ({n}×{n}×{n} uint8: 0 out, 1 on, 2 in; {on} on cells)",
            path.display(),
            n = 1 << tree.depth()
        );
    }
    Ok(ExitCode::SUCCESS)
}
