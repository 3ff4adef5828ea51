//! The `wingedge` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod classify;
mod info;
mod lines;
mod progress;
mod raycast;
mod render;
mod target;
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
    /// Print counts and measures of a solid read from an OBJ file or built in.
    Info {
        /// The OBJ file to read.
        #[arg(required_unless_present = "builtin", conflicts_with = "builtin")]
        file: Option<PathBuf>,
        /// A built-in solid: tetrahedron, cube, octahedron, dodecahedron,
        /// icosahedron or prism.
        #[arg(long)]
        builtin: Option<String>,
        /// Also write the solid as OBJ to this path.
        #[arg(long, value_name = "OUT.obj")]
        write: Option<PathBuf>,
    },
    /// Validate OBJ files: a graded verdict per file and every defect with
    /// its OBJ line. Exit code 0 when every file is a valid closed solid, 1
    /// when any has defects, 2 when any cannot be read.
    Validate {
        /// The OBJ files.
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
    },
    /// Classify points against a scene (.json) or a mesh: one word per line,
    /// inside, outside or boundary, in input order.
    Classify {
        /// The scene (.json) or mesh file.
        target: PathBuf,
        /// One `x y z` per line; `-` for standard input.
        points: PathBuf,
        /// Print the work counters to standard error.
        #[arg(long)]
        stats: bool,
    },
    /// Cast rays through a scene (.json) or a mesh: per ray, whether its
    /// origin is inside, then its spans inside the solid as [t0, t1].
    Raycast {
        /// The scene (.json) or mesh file.
        target: PathBuf,
        /// One `ox oy oz dx dy dz` per line; `-` for standard input.
        rays: PathBuf,
        /// Print the work counters to standard error.
        #[arg(long)]
        stats: bool,
    },
    /// Print the volume of a mesh or a scene: closed form for a single
    /// solid, otherwise by integrating ray spans over a grid.
    Volume {
        /// The scene (.json) or mesh file.
        target: PathBuf,
        /// Grid spacing of the parallel rays (default: the longest side of
        /// the bounds / 400).
        #[arg(long, value_name = "H")]
        spacing: Option<f64>,
        /// Integrate ray spans even for a single solid with a closed form.
        #[arg(long)]
        integrate: bool,
        /// Print the work counters to standard error.
        #[arg(long)]
        stats: bool,
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
    },
}

/// Prints `error: message` and returns exit code 2.
fn fail(message: &str) -> ExitCode {
    eprintln!("error: {message}");
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Info {
            file,
            builtin,
            write,
        } => info::run(file, builtin, write),
        Command::Classify {
            target,
            points,
            stats,
        } => classify::run(&target, &points, stats),
        Command::Raycast {
            target,
            rays,
            stats,
        } => raycast::run(&target, &rays, stats),
        Command::Volume {
            target,
            spacing,
            integrate,
            stats,
        } => volume::run(&target, spacing, integrate, stats),
        Command::Render {
            scene,
            output,
            size,
            stats,
        } => render::run(&scene, &output, size, stats),
        Command::Validate {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
        } => validate::run(validate::Args {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
        }),
    }
}
