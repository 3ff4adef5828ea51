//! `wingedge cells TARGET --depth N [--npy OUT] [--obj OUT]`: the octree
//! cells of a solid or a CSG scene, In, Out or On, with the certified
//! volume interval, the dense array and the In cells' outer faces.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use wingedge::cells::{Label, MAX_DENSE_DEPTH, Octree, write_npy};
use wingedge::csg::Stats;
use wingedge::geom::{Readable, ReadableVec};
use wingedge::io::{ImportOptions, import, write_obj};
use wingedge::mesh::Solid;
use wingedge::scene::{Scene, is_scene_path};

use crate::output::{Out, Outcome};

pub fn run(
    target: &Path,
    depth: u32,
    npy: Option<&Path>,
    obj: Option<&Path>,
    options: &ImportOptions,
) -> Outcome {
    if npy.is_some() && depth > MAX_DENSE_DEPTH {
        return Err(format!(
            "--npy: depth {depth} is beyond the limit of {MAX_DENSE_DEPTH} for a dense array"
        ));
    }
    let named = |e: &dyn std::fmt::Display| format!("{}: {e}", target.display());
    let mut mesh_volume = None;
    let (tree, seconds, scene_stats) = if is_scene_path(target) && options.format.is_none() {
        let scene = Scene::from_file_with(target, options).map_err(|e| e.to_string())?;
        let start = Instant::now();
        let mut stats = Stats::default();
        let tree = Octree::classify_csg(&scene.csg, depth, &mut stats).map_err(|e| named(&e))?;
        (tree, start.elapsed().as_secs_f64(), Some(stats))
    } else {
        let soup = import(target, options).map_err(|e| e.to_string())?.soup;
        let solid = Solid::try_from_soup(&soup).map_err(|e| named(&e))?;
        let start = Instant::now();
        let tree = Octree::classify(&solid, depth).map_err(|e| named(&e))?;
        mesh_volume = Some(solid.volume());
        (tree, start.elapsed().as_secs_f64(), None)
    };
    // A certified interval or none: refused before anything is printed.
    let (low, high) = tree.try_volume_bounds().map_err(|e| named(&e))?;
    let mut out = Out::new();
    let (origin, side) = tree.root();
    out.write(format_args!(
        "{}: depth {depth}, root cube at {} of side {}\n",
        target.display(),
        ReadableVec(origin),
        Readable(side)
    ))?;
    out.write("depth        in       out        on\n")?;
    for (d, c) in tree.counts().iter().enumerate() {
        out.write(format_args!(
            "{d:5} {:9} {:9} {:9}\n",
            c.inside, c.outside, c.on
        ))?;
    }
    let (low, high) = (Readable(low), Readable(high));
    match mesh_volume {
        Some(v) => out.write(format_args!(
            "volume in [{low}, {high}] (certified; the mesh's rounded volume is {})\n",
            Readable(v)
        ))?,
        None => out.write(format_args!("volume in [{low}, {high}] (certified)\n"))?,
    };
    match scene_stats {
        None => out.write(format_args!(
            "{} leaves, {} point classifications (one per region), {seconds:.3} s\n",
            tree.leaves().len(),
            tree.regions()
        ))?,
        Some(s) => out.write(format_args!(
            "{} leaves, {} leaf box tests, {} leaf point classifications, {} subtrees culled by bounds, {} right operands skipped, {seconds:.3} s\n",
            tree.leaves().len(),
            s.primitive_cell_tests,
            s.primitive_point_tests,
            s.culled_subtrees,
            s.skipped_right_sides
        ))?,
    };
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
    if let Some(path) = obj {
        write_shell(&tree, path)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes the In cells' outer faces as OBJ.
fn write_shell(tree: &Octree, path: &Path) -> Result<(), String> {
    let named = |e: &dyn std::fmt::Display| format!("{}: --obj: {e}", path.display());
    let shell = tree.in_shell().map_err(|e| named(&e))?;
    if shell.soup.polygons.is_empty() {
        eprintln!("no In cells: {} not written", path.display());
        return Ok(());
    }
    let solid = Solid::try_from_soup(&shell.soup).map_err(|e| named(&e))?;
    write_obj(&solid, path).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    eprintln!(
        "wrote {} ({} faces, volume {}; {} sub-cells of On cells filled at contacts along edges or at corners)",
        path.display(),
        solid.face_count(),
        solid.volume(),
        shell.filled,
    );
    Ok(())
}
