//! The `wingedge` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod info;

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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Info {
            file,
            builtin,
            write,
        } => info::run(file, builtin, write),
    }
}
