//! `wingedge convert IN OUT`: a mesh from any format to any other,
//! validated on the way, written only when what is written is a valid
//! solid (unless `--allow-invalid`).

use std::path::PathBuf;
use std::process::ExitCode;

use wingedge::io::{
    ExportReport, Format, ImportOptions, export_bytes, export_soup, import, import_bytes,
    write_atomically,
};
use wingedge::validate::{Options, Report, validate_and_build, validate_import};

use crate::output::{Out, Outcome};
use crate::validate::{describe, weld_mode};

/// The `convert` flags, as parsed by clap.
pub struct Args {
    pub input: PathBuf,
    pub output: PathBuf,
    pub format: Option<Format>,
    pub to: Option<Format>,
    pub weld: Option<f64>,
    pub no_weld: bool,
    pub allow_invalid: bool,
    pub show: usize,
    pub max_face_corners: usize,
}

pub fn run(args: Args) -> Outcome {
    let to = match args.to.or_else(|| Format::from_path(&args.output)) {
        Some(f) => f,
        None => {
            return Err(format!(
                "{}: cannot tell the output format from the extension (name it with --to obj|stl|ply|off|3mf|gltf|glb)",
                args.output.display()
            ));
        }
    };
    let (weld, tolerance) = weld_mode(args.weld, args.no_weld, None)?;
    let options = ImportOptions {
        format: args.format,
        weld,
        max_face_corners: args.max_face_corners,
        ..ImportOptions::default()
    };
    let validation = Options {
        tolerance,
        ..Options::default()
    };
    let input = import(&args.input, &options).map_err(|e| e.to_string())?;
    let (report, solid) = validate_and_build(&input, &validation)
        .map_err(|e| format!("{}: {e}", args.input.display()))?;
    let mut out = Out::new();
    if !report.is_valid() && !args.allow_invalid {
        out.write(describe(&args.input, &input, &report, args.show))?;
        out.write(format_args!(
            "{}: not written: the input is not a valid closed solid (--allow-invalid writes it anyway)\n",
            args.output.display()
        ))?;
        out.finish()?;
        return Ok(ExitCode::from(1));
    }
    let named = |e: &dyn std::fmt::Display| format!("{}: {e}", args.output.display());
    let written = match &solid {
        Some(solid) => {
            let (bytes, written) = export_bytes(solid, to).map_err(|e| named(&e))?;
            // What is written is what was proven: a format that rounds is
            // read back and validated before the file is replaced.
            if !to.keeps_f64() && report.is_valid() && !args.allow_invalid {
                let back = import_bytes(&args.output, &bytes, to, &ImportOptions::default())
                    .map_err(|e| format!("reading back what would be written: {e}"))?;
                let again = validate_import(&back, &Options::default()).map_err(|e| named(&e))?;
                if !again.is_valid() {
                    return refuse_rounded(&mut out, &args, &again, &written);
                }
            }
            write_atomically(&args.output, |w| std::io::Write::write_all(w, &bytes))
                .map_err(|e| format!("{}: cannot write: {e}", args.output.display()))?;
            written
        }
        // Faces that make no winged-edge solid, written as they are.
        None => export_soup(&input.soup, &args.output, to).map_err(|e| e.to_string())?,
    };
    if let Some(warning) = written.warning(&args.output) {
        eprintln!("warning: {warning}");
    }
    let welded = if input.weld.merged > 0 {
        format!(
            ", {} {} welded",
            input.weld.merged,
            if input.format == Format::Stl {
                "corners"
            } else {
                "vertices"
            }
        )
    } else {
        String::new()
    };
    out.write(format_args!(
        "{} ({}{welded}: {}) -> {} ({}): vertices {}  faces {}\n",
        args.input.display(),
        input.format,
        report.validity.describe(),
        args.output.display(),
        to,
        written.vertices,
        written.faces,
    ))?;
    out.finish()?;
    Ok(ExitCode::SUCCESS)
}

/// The input is valid, but rounding to the output format's `f32` breaks
/// it: nothing is written.
fn refuse_rounded(out: &mut Out, args: &Args, again: &Report, written: &ExportReport) -> Outcome {
    out.write(format_args!(
        "{}: not written: rounding {} of {} coordinates to f32 for {} makes the solid invalid ({}; {} violation(s))\n",
        args.output.display(),
        written.rounded,
        written.coordinates,
        written.format,
        again.validity.describe(),
        again.violations.len(),
    ))?;
    for v in again.violations.iter().take(args.show) {
        out.write(format_args!("  {}: {}\n", v.rule, v.message))?;
    }
    out.write("  (a format that keeps f64 — obj, ply, off, 3mf — writes it exactly; --allow-invalid writes it anyway)\n")?;
    Ok(ExitCode::from(1))
}
