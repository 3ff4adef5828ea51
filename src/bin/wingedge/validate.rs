//! `wingedge validate FILE...`: a verdict per file, every defect located;
//! `--image OUT.png` draws them (one file only).

use std::path::PathBuf;
use std::process::ExitCode;

use serde_json::{Value, json};
use wingedge::geom::Tolerance;
use wingedge::io::{Format, ImportOptions, WeldMode, import};
use wingedge::render::{DefectImageOptions, render_defects};
use wingedge::validate::{Options, Report, Rule, report_json, validate_import};

use crate::output::{Out, Outcome, measure};

/// The `validate` flags, as parsed by clap.
pub struct Args {
    pub files: Vec<PathBuf>,
    pub json: bool,
    pub weld: Option<f64>,
    pub no_weld: bool,
    pub planarity: Option<f64>,
    pub show: usize,
    pub max_face_corners: usize,
    pub format: Option<Format>,
    /// Where to draw the defects (`--image`), one input file only.
    pub image: Option<PathBuf>,
    /// The picture's width and height (`--image-size`).
    pub image_size: (u32, u32),
}

/// The weld mode and tolerances of `--weld`, `--no-weld` and
/// `--planarity`, or the message refusing a bad tolerance.
pub fn weld_mode(
    weld: Option<f64>,
    no_weld: bool,
    planarity: Option<f64>,
) -> Result<(WeldMode, Tolerance), String> {
    for (flag, value) in [("--weld", weld), ("--planarity", planarity)] {
        if let Some(v) = value.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!(
                "{flag} {v}: a tolerance is a finite fraction of the bounding-box diagonal, at least 0"
            ));
        }
    }
    let mut tolerance = Tolerance::default();
    if let Some(p) = planarity {
        tolerance.planarity = p;
    }
    let mode = match (no_weld, weld) {
        (true, _) => WeldMode::None,
        (false, Some(t)) => WeldMode::Within(Tolerance {
            weld: t,
            ..tolerance
        }),
        (false, None) => WeldMode::Exact,
    };
    Ok((mode, tolerance))
}

pub fn run(args: Args) -> Outcome {
    let (weld, tolerance) = weld_mode(args.weld, args.no_weld, args.planarity)?;
    if args.image.is_some() && args.files.len() != 1 {
        return Err(format!(
            "--image draws one file's defects, but {} files were given: validate them one at a time",
            args.files.len()
        ));
    }
    let options = Options {
        tolerance,
        ..Options::default()
    };
    let mut unreadable = false;
    let mut invalid = false;
    let mut json_out = Vec::new();
    let mut out = Out::new();
    for path in &args.files {
        let outcome = import(
            path,
            &ImportOptions {
                format: args.format,
                weld,
                max_face_corners: args.max_face_corners,
                ..ImportOptions::default()
            },
        )
        .map_err(|e| (e.to_string(), e.line()))
        .and_then(|import| {
            validate_import(&import, &options)
                .map(|report| (import, report))
                .map_err(|e| (format!("{}: {e}", path.display()), None))
        });
        match outcome {
            Err((message, line)) => {
                unreadable = true;
                if args.json {
                    json_out.push(json!({
                        "file": path.display().to_string(),
                        "valid": false,
                        "error": message,
                        "line": line,
                        "vertices": null, "edges": null, "faces": null,
                        "shells": null, "genus": null, "volume": null,
                        "violations": [],
                    }));
                } else {
                    out.write(format_args!(
                        "{}: unreadable\n  error: {message}\n",
                        path.display()
                    ))?;
                }
            }
            Ok((import, report)) => {
                // A measure lost to overflow is reported and fails the run too.
                invalid |= !report.is_valid() || !report.overflowing_measures().is_empty();
                if args.json {
                    json_out.push(report_json(&report, Some(path), Some(&import.weld)));
                } else {
                    out.write(describe(path, &import, &report, args.show))?;
                }
                if let Some(image_path) = &args.image {
                    let (width, height) = args.image_size;
                    render_defects(
                        &import.soup,
                        &report.violations,
                        &DefectImageOptions { width, height },
                    )
                    .map_err(|e| e.to_string())
                    .and_then(|image| image.write_png(image_path).map_err(|e| e.to_string()))
                    .map_err(|e| format!("--image: {e}"))?;
                }
            }
        }
    }
    if args.json {
        let text = serde_json::to_string_pretty(&Value::Array(json_out))
            .map_err(|e| format!("cannot write JSON: {e}"))?;
        out.write(format_args!("{text}\n"))?;
    }
    out.finish()?;
    Ok(if unreadable {
        ExitCode::from(2)
    } else if invalid {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// The text report of one file, as `validate` prints it.
pub fn describe(
    path: &std::path::Path,
    import: &wingedge::io::Import,
    report: &Report,
    show: usize,
) -> String {
    let weld = &import.weld;
    let number = |x: Option<f64>| x.map_or_else(|| "-".to_string(), |v| measure(v, 6));
    let mut out = format!(
        "{}: {}\n  vertices {}  edges {}  faces {}  shells {}  holes {}  genus {}  volume {}  area {}\n",
        path.display(),
        report.validity.describe(),
        report.vertices,
        report.edges,
        report.faces,
        report.shells,
        report.holes,
        report
            .genus
            .map_or_else(|| "-".to_string(), |g| g.to_string()),
        number(report.volume),
        measure(report.area, 6),
    );
    let overflowing = report.overflowing_measures();
    if !overflowing.is_empty() {
        out += &format!(
            "  warning: {} overflow f64 (the coordinates are too large to multiply); the topology and the checks are exact\n",
            overflowing.join(", ")
        );
    }
    for note in &import.notes {
        out += &format!("  note: {note}\n");
    }
    if weld.merged > 0 || !weld.refused.is_empty() {
        // STL repeats every corner: the weld merges corners.
        let what = if import.format == Format::Stl {
            "corners"
        } else {
            "vertices"
        };
        out += &format!("  weld: merged {} {what}\n", weld.merged);
        for r in &weld.refused {
            out += &format!("    {r}\n");
        }
    }
    if report.shell_details.len() > 1 {
        for (i, s) in report.shell_details.iter().enumerate().take(show) {
            out += &format!(
                "  shell {i}: faces {}  χ {}  genus {}  volume {}  {}  depth {}\n",
                s.faces,
                s.euler_characteristic,
                s.genus.map_or_else(|| "-".to_string(), |g| g.to_string()),
                measure(s.volume, 6),
                if s.closed { "closed" } else { "open" },
                match (s.closed, s.depth) {
                    (false, _) => "-".to_string(),
                    (true, None) => "undecided".to_string(),
                    (true, Some(d)) => d.to_string(),
                },
            );
        }
        if report.shell_details.len() > show {
            out += &format!(
                "  … and {} more shells\n",
                report.shell_details.len() - show
            );
        }
    }
    if let Some(why) = &report.not_built {
        out += &format!("  not built as a winged-edge solid: {why}\n");
    }
    for rule in Rule::ALL {
        let count = report.count(rule);
        if count == 0 {
            continue;
        }
        out += &format!("  {rule}: {count}\n");
        for v in report.of(rule).take(show) {
            out += &format!("    {}\n", v.message);
        }
        if count > show {
            out += &format!("    … and {} more\n", count - show);
        }
    }
    out
}
