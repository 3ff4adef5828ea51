//! The `wingedge` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use wingedge::io::{Format, ImportOptions};

mod cells;
mod convert;
mod csg;
mod info;
mod input;
mod mesh;
mod mesh_scene;
mod output;
mod progress;
mod query;
mod render;
mod repair;
mod validate;
mod volume;

/// wingedge: a B-rep polyhedron kernel on the winged-edge structure.
#[derive(Debug, Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print counts and measures of a solid read from a mesh file or built in
    /// (exit code 1, with a warning, when a measure overflows f64).
    Info {
        /// The mesh file to read (obj, stl, ply, off, 3mf, gltf, glb).
        #[arg(required_unless_present = "builtin", conflicts_with = "builtin")]
        file: Option<PathBuf>,
        /// A built-in solid: tetrahedron, cube, octahedron, dodecahedron,
        /// icosahedron or prism.
        #[arg(long)]
        builtin: Option<String>,
        /// Also write the solid as OBJ to this path.
        #[arg(long, value_name = "OUT.obj")]
        write: Option<PathBuf>,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
    },
    /// Classify points against a closed solid or a CSG scene: prints
    /// `inside`, `outside` or `boundary`, one per input point, in input
    /// order. Exact for polyhedra and half-spaces.
    Classify {
        /// The mesh file of the solid (any format), or a CSG scene (`.json`).
        mesh: PathBuf,
        /// A text file with one `x y z` per line (`-` for standard input);
        /// blank lines and `#` comments are skipped.
        points: String,
        /// parity (+x ray, any closed solid), normals (convex solids only) or
        /// winding (generalized winding number; open meshes too, and meshes
        /// that cannot be a solid, such as an edge of three faces, answered
        /// from their triangles with a note on standard error). Meshes only:
        /// a scene classifies by its tree.
        #[arg(long, value_enum, default_value_t = MethodArg::Parity)]
        method: MethodArg,
        /// Scenes: print the CSG work counters to standard error.
        #[arg(long)]
        stats: bool,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        #[command(flatten)]
        paths: PathArgs,
    },
    /// Cast rays at a closed solid: prints, per ray, `inside`, `outside` or
    /// `boundary` for its origin, then the ascending parameters t > 0 of its
    /// crossings with the boundary. For a CSG scene (`.json`): per ray,
    /// `inside` or `outside` (just after the origin), then its spans inside
    /// the solid as `[t0, t1]`.
    Raycast {
        /// The mesh file of the solid (any format), or a CSG scene (`.json`).
        mesh: PathBuf,
        /// A text file with one `ox oy oz dx dy dz` per line (`-` for standard
        /// input); blank lines and `#` comments are skipped.
        rays: String,
        /// Scenes: print the CSG work counters to standard error.
        #[arg(long)]
        stats: bool,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        #[command(flatten)]
        paths: PathArgs,
    },
    /// Print the volume of a mesh or a scene: closed form for a single
    /// solid, otherwise by integrating ray spans over a grid.
    Volume {
        /// The scene (.json) or mesh file.
        target: PathBuf,
        /// Grid spacing of the parallel rays (default: the longest side of
        /// the bounds / 400, finer along x or y where a leaf that adds
        /// volume is narrower than 4 cells).
        #[arg(long, value_name = "H")]
        spacing: Option<f64>,
        /// Integrate ray spans even for a single solid with a closed form.
        #[arg(long)]
        integrate: bool,
        /// Print the work counters to standard error.
        #[arg(long)]
        stats: bool,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        #[command(flatten)]
        paths: PathArgs,
    },
    /// Validate mesh files (obj, stl, ply, off, 3mf, gltf, glb): a graded
    /// verdict per file and every defect with its line (text formats) or
    /// face number. Exit code 0 when every file is a valid closed solid, 1
    /// when any has defects (or a volume or area that overflows f64), 2 when
    /// any cannot be read.
    Validate {
        /// The mesh files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print one JSON array (one object per file) instead of text.
        #[arg(long)]
        json: bool,
        /// Weld vertices closer than TOL × the bounding-box diagonal (only
        /// where that closes open edges). Default: bit-identical positions.
        #[arg(long, value_name = "TOL", conflicts_with = "no_weld")]
        weld: Option<f64>,
        /// Merge no vertices at all.
        #[arg(long)]
        no_weld: bool,
        /// Planarity tolerance as a fraction of the bounding-box diagonal
        /// (default 1e-6).
        #[arg(long, value_name = "TOL")]
        planarity: Option<f64>,
        /// How many instances of each broken rule to print (text output).
        #[arg(long, default_value_t = 3)]
        show: usize,
        /// Refuse a face with more corners than this (checking a face costs
        /// time quadratic in its corners).
        #[arg(long, value_name = "N", default_value_t = wingedge::io::DEFAULT_MAX_FACE_CORNERS)]
        max_face_corners: usize,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        /// Also draw the mesh with its defects marked (framed on them, a
        /// legend of the counts per rule) as a PNG file; one input file
        /// only. The exit code is the verdict's.
        #[arg(long, value_name = "OUT.png")]
        image: Option<PathBuf>,
        /// The size of the --image picture.
        #[arg(long, value_name = "WxH", default_value = "800x600", value_parser = render::parse_size, requires = "image")]
        image_size: (u32, u32),
    },
    /// Convert a mesh between formats (obj, stl, ply, off, 3mf, gltf, glb),
    /// validating it on the way: exit code 0 when written, 1 with the
    /// report when the input (or its rounding to f32 for stl and gltf) is
    /// not a valid closed solid (nothing written), 2 when it cannot be
    /// read or written. A warning says how many coordinates rounding to
    /// f32 changed.
    Convert {
        /// The mesh to read.
        input: PathBuf,
        /// The file to write; its format by the extension (or --to).
        output: PathBuf,
        /// The input's format (default: by the extension, OBJ for any other).
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        /// The output's format (default: by the extension).
        #[arg(long, value_name = "FORMAT")]
        to: Option<Format>,
        /// Weld vertices closer than TOL × the bounding-box diagonal (only
        /// where that closes open edges). Default: bit-identical positions.
        #[arg(long, value_name = "TOL", conflicts_with = "no_weld")]
        weld: Option<f64>,
        /// Merge no vertices at all.
        #[arg(long)]
        no_weld: bool,
        /// Write the mesh even when it is not a valid closed solid.
        #[arg(long)]
        allow_invalid: bool,
        /// How many instances of each broken rule to print.
        #[arg(long, default_value_t = 3)]
        show: usize,
        /// Refuse a face with more corners than this.
        #[arg(long, value_name = "N", default_value_t = wingedge::io::DEFAULT_MAX_FACE_CORNERS)]
        max_face_corners: usize,
    },
    /// The octree cells of a solid or a CSG scene, each In, Out or On its
    /// boundary (exact for flat surfaces, conservative for spheres and
    /// cylinders), with the certified volume interval [V_in, V_in + V_on];
    /// only cells the boundary may meet are refined.
    Cells {
        /// The solid (a mesh file) or scene (.json).
        target: PathBuf,
        /// The finest depth (2^depth cells along each side of the root cube).
        #[arg(long, default_value_t = 6)]
        depth: u32,
        /// Write the dense array of the finest cells as a numpy .npy file
        /// (uint8, shape (n, n, n): 0 out, 1 on, 2 in; depth at most 9).
        #[arg(long, value_name = "OUT.npy")]
        npy: Option<PathBuf>,
        /// Write the In cells' outer faces as OBJ: a valid closed solid
        /// whose volume lies within [V_in, V_in + V_on] (it is V_in unless
        /// cells touching only at an edge or a corner had sub-cells filled;
        /// the command prints the volume and how many were filled).
        #[arg(long, value_name = "OUT.obj")]
        obj: Option<PathBuf>,
        /// The mesh's format (obj, stl, ply, off, 3mf, gltf, glb); default:
        /// by the extension, OBJ for any other.
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        #[command(flatten)]
        paths: PathArgs,
    },
    /// Mesh a field document (blobs and field CSG, JSON) or a CSG scene by
    /// marching cubes into a validated closed solid and write it as OBJ. Exit code 0 for a
    /// valid solid, 1 for an empty field (nothing written), 2 for a
    /// document or grid that is refused (a cell below f64's resolution far
    /// from the origin among them; nothing written).
    Mesh {
        /// The field document or CSG scene (.json). A scene (a document
        /// with "root") is meshed over its exact point classification: every
        /// grid node decided exactly, vertices at cell-edge midpoints.
        field: PathBuf,
        /// The OBJ to write.
        #[arg(short = 'o', long = "output", value_name = "OUT.obj")]
        output: PathBuf,
        /// Cells along the longest side of the field's bounds (default: the
        /// document's "resolution", else 64).
        #[arg(long, value_name = "N")]
        resolution: Option<usize>,
        /// Put vertices at edge midpoints instead of interpolating.
        #[arg(long)]
        midpoints: bool,
        /// Print the field and march work counters to standard error.
        #[arg(long)]
        stats: bool,
    },
    /// Evaluate a scene's CSG tree by exact booleans into one solid and
    /// write it as OBJ, with its counts, genus, volume and the validator's
    /// verdict. Exit code 0 for a valid solid, 1 when a boolean's result
    /// could not be made valid (located, nothing written), 2 for a scene
    /// that cannot be read or evaluated.
    Csg {
        /// The scene (.json).
        scene: PathBuf,
        /// The OBJ to write.
        #[arg(short = 'o', long = "output", value_name = "OUT.obj")]
        output: PathBuf,
        /// Chord tolerance of spheres and cylinders, a fraction of their
        /// radius (default 1e-3).
        #[arg(long, value_name = "T")]
        tolerance: Option<f64>,
        /// Evaluate the whole tree in one pass over all leaves, instead of
        /// node by node where that is exact (the same solid; slower on
        /// large trees; for comparison).
        #[arg(long)]
        one_pass: bool,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// Take a mesh leaf that is not a valid solid (self-intersecting,
        /// overlapping shells, holes, flipped faces) as `wingedge repair`
        /// makes it, by its winding number, instead of refusing it.
        #[arg(long)]
        resolve: bool,
        #[command(flatten)]
        paths: PathArgs,
    },
    /// Repair a mesh (obj, stl, ply, off, 3mf, gltf, glb) into a valid
    /// solid: vertices welded, degenerate and repeated faces dropped,
    /// pieces oriented outward, holes filled, self-intersections and
    /// overlapping shells resolved exactly (the region where the winding
    /// number is positive); every change reported with its place in the
    /// input. Exit code 0 when written (an empty solid for a mesh that
    /// encloses nothing, saying why), 1 when holes were left open or no
    /// valid solid could be made (nothing written), 2 when the input cannot
    /// be read.
    Repair {
        /// The mesh to repair.
        input: PathBuf,
        /// The file to write (its format by the extension).
        #[arg(short = 'o', long = "output", value_name = "OUT")]
        output: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// Fill only holes of at most N edges; larger ones are reported and
        /// stay open (then no solid is written).
        #[arg(long, value_name = "N")]
        max_hole_edges: Option<usize>,
        /// Weld vertices closer than TOL × the bounding-box diagonal (only
        /// where that closes open edges), before repairing. Default:
        /// bit-identical positions.
        #[arg(long, value_name = "TOL")]
        weld: Option<f64>,
        /// The input's format (default: by the extension, OBJ for any other).
        #[arg(long, value_name = "FORMAT")]
        format: Option<Format>,
        /// Refuse a face with more corners than this.
        #[arg(long, value_name = "N", default_value_t = wingedge::io::DEFAULT_MAX_FACE_CORNERS)]
        max_face_corners: usize,
    },
    /// Render a scene to a PNG: Lambert shading with the scene's light,
    /// shadows only if the scene asks.
    Render {
        /// The scene file.
        scene: PathBuf,
        /// The PNG to write.
        #[arg(short = 'o', long = "output", value_name = "OUT.png")]
        output: PathBuf,
        /// Image size.
        #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = render::parse_size)]
        size: (u32, u32),
        /// Print the work counters to standard error.
        #[arg(long)]
        stats: bool,
        #[command(flatten)]
        paths: PathArgs,
    },
}

/// Where a scene's leaves may be read from.
#[derive(Debug, Args)]
struct PathArgs {
    /// Also allow a scene's leaves (mesh, field and included scene files)
    /// inside DIR (repeatable). By default a leaf must resolve, symbolic
    /// links followed, inside the scene file's folder or the working
    /// directory, and must be a regular file.
    #[arg(long = "allow-path", value_name = "DIR")]
    allow_path: Vec<PathBuf>,
}

/// The `--method` values of `classify`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum MethodArg {
    /// Parity of a +x ray's crossings.
    Parity,
    /// Inner side of every face plane (convex solids only).
    Normals,
    /// Generalized winding number above one half.
    Winding,
}

impl From<MethodArg> for wingedge::query::Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Parity => wingedge::query::Method::Parity,
            MethodArg::Normals => wingedge::query::Method::Normals,
            MethodArg::Winding => wingedge::query::Method::Winding,
        }
    }
}

/// Import options with the format and the folders scene leaves may also
/// resolve into.
fn options(format: Option<Format>, paths: PathArgs) -> ImportOptions {
    ImportOptions {
        format,
        allowed_roots: paths.allow_path,
        ..ImportOptions::default()
    }
}

fn main() -> ExitCode {
    // Stages that build and drop large tables then hold the largest of
    // them, not their sum.
    wingedge::spatial::return_large_frees_to_the_system();
    // An interrupted write leaves the old file and no partial one.
    #[cfg(target_os = "linux")]
    wingedge::io::remove_partial_files_on_signal();
    let cli = Cli::parse();
    output::exit(match cli.command {
        Command::Info {
            file,
            builtin,
            write,
            format,
        } => info::run(file, builtin, write, format),
        Command::Classify {
            mesh,
            points,
            method,
            stats,
            format,
            paths,
        } => query::classify(
            &mesh,
            &points,
            method.into(),
            stats,
            &options(format, paths),
        ),
        Command::Raycast {
            mesh,
            rays,
            stats,
            format,
            paths,
        } => query::raycast(&mesh, &rays, stats, &options(format, paths)),
        Command::Volume {
            target,
            spacing,
            integrate,
            stats,
            format,
            paths,
        } => volume::run(&target, spacing, integrate, stats, &options(format, paths)),
        Command::Cells {
            target,
            depth,
            npy,
            obj,
            format,
            paths,
        } => cells::run(
            &target,
            depth,
            npy.as_deref(),
            obj.as_deref(),
            &options(format, paths),
        ),
        Command::Convert {
            input,
            output,
            format,
            to,
            weld,
            no_weld,
            allow_invalid,
            show,
            max_face_corners,
        } => convert::run(convert::Args {
            input,
            output,
            format,
            to,
            weld,
            no_weld,
            allow_invalid,
            show,
            max_face_corners,
        }),
        Command::Mesh {
            field,
            output,
            resolution,
            ..
        } if mesh_scene::is_scene(&field) => mesh_scene::run(&field, &output, resolution),
        Command::Mesh {
            field,
            output,
            resolution,
            midpoints,
            stats,
        } => mesh::run(&field, &output, resolution, midpoints, stats),
        Command::Csg {
            scene,
            output,
            tolerance,
            one_pass,
            json,
            resolve,
            paths,
        } => csg::run(
            &scene,
            &output,
            tolerance,
            one_pass,
            json,
            &ImportOptions {
                resolve_leaves: resolve,
                ..options(None, paths)
            },
        ),
        Command::Repair {
            input,
            output,
            json,
            max_hole_edges,
            weld,
            format,
            max_face_corners,
        } => repair::run(repair::Args {
            input,
            output,
            json,
            max_hole_edges,
            weld,
            format,
            max_face_corners,
        }),
        Command::Render {
            scene,
            output,
            size,
            stats,
            paths,
        } => render::run(&scene, &output, size, stats, &options(None, paths)),
        Command::Validate {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
            max_face_corners,
            format,
            image,
            image_size,
        } => validate::run(validate::Args {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
            max_face_corners,
            format,
            image,
            image_size,
        }),
    })
}
