//! The `wingedge` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod classify;
mod info;
mod input;
mod raycast;
mod validate;

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
    /// Classify points against a closed solid: prints `inside`, `outside` or
    /// `boundary`, one per input point, in input order. Exact.
    Classify {
        /// The OBJ file of the solid.
        mesh: PathBuf,
        /// A text file with one `x y z` per line (`-` for standard input);
        /// blank lines and `#` comments are skipped.
        points: String,
        /// parity (+x ray, any closed solid), normals (convex solids only) or
        /// winding (generalized winding number; open meshes too).
        #[arg(long, value_enum, default_value_t = MethodArg::Parity)]
        method: MethodArg,
    },
    /// Cast rays at a closed solid: prints, per ray, `inside`, `outside` or
    /// `boundary` for its origin, then the ascending parameters t > 0 of its
    /// crossings with the boundary.
    Raycast {
        /// The OBJ file of the solid.
        mesh: PathBuf,
        /// A text file with one `ox oy oz dx dy dz` per line (`-` for standard
        /// input); blank lines and `#` comments are skipped.
        rays: String,
    },
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Info {
            file,
            builtin,
            write,
        } => info::run(file, builtin, write),
        Command::Classify {
            mesh,
            points,
            method,
        } => classify::run(&mesh, &points, method.into()),
        Command::Raycast { mesh, rays } => raycast::run(&mesh, &rays),
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
