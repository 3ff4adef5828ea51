//! `wingedge repair IN -o OUT`: a valid solid from an imperfect mesh
//! (welded, cleaned, oriented, holes filled, self-intersections and
//! overlapping shells resolved), with a report of what changed, located
//! in the input.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use serde_json::{Value, json};
use wingedge::io::{
    Format, Import, ImportOptions, export_bytes, import, import_bytes, write_atomically,
};
use wingedge::repair::{OpenReason, RepairOptions, RepairReport, Repaired, repair};
use wingedge::validate::{Options, validate_import};

use crate::output::{Out, Outcome, measure};
use crate::validate::weld_mode;

/// The `repair` flags, as parsed by clap.
pub struct Args {
    pub input: PathBuf,
    pub output: PathBuf,
    pub json: bool,
    pub max_hole_edges: Option<usize>,
    pub weld: Option<f64>,
    pub format: Option<Format>,
    pub max_face_corners: usize,
}

/// Repairs `args.input` into `args.output`. Exit 0 when a valid solid (or
/// the empty result of a soup that encloses nothing, saying so) was
/// written; 1 when holes were left open (`--max-hole-edges`) or the result
/// could not be made valid, nothing written; 2 when the input cannot be
/// read or the output written.
pub fn run(args: Args) -> Outcome {
    let to = Format::from_path(&args.output).ok_or_else(|| {
        format!(
            "{}: cannot tell the output format from the extension (obj, stl, ply, off, 3mf, gltf, glb)",
            args.output.display()
        )
    })?;
    let (weld, _) = weld_mode(args.weld, false, None)?;
    let imported = import(
        &args.input,
        &ImportOptions {
            format: args.format,
            weld,
            max_face_corners: args.max_face_corners,
            ..ImportOptions::default()
        },
    )
    .map_err(|e| e.to_string())?;
    let name = args.input.display().to_string();
    let start = Instant::now();
    let options = RepairOptions {
        max_hole_edges: args.max_hole_edges,
        ..RepairOptions::default()
    };
    let repaired = match repair(&imported.soup, &options) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {name}: {e}; {} not written", args.output.display());
            return Ok(ExitCode::from(1));
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let mut out = Out::new();
    let Some(solid) = &repaired.solid else {
        let open = repaired.report.left_open.len();
        if args.json {
            out.write(format!(
                "{:#}\n",
                report_json(&name, None, &imported, &repaired, seconds)
            ))?;
        } else {
            out.write(describe(&name, &imported, &repaired, seconds))?;
        }
        out.finish()?;
        eprintln!(
            "error: {name}: {open} hole{} left open, so no solid; {} not written",
            if open == 1 { "" } else { "s" },
            args.output.display()
        );
        return Ok(ExitCode::from(1));
    };
    let (bytes, written) =
        export_bytes(solid, to).map_err(|e| format!("{}: {e}", args.output.display()))?;
    if !to.keeps_f64() && solid.face_count() > 0 {
        // What is written is what was proven: read back and validated.
        let back = import_bytes(&args.output, &bytes, to, &ImportOptions::default())
            .map_err(|e| format!("reading back what would be written: {e}"))?;
        let again = validate_import(&back, &Options::default())
            .map_err(|e| format!("{}: {e}", args.output.display()))?;
        if !again.is_valid() {
            eprintln!(
                "error: {}: the repaired solid is not valid once rounded to the f32 of {to} ({} defects); write obj, ply, off or 3mf; nothing written",
                args.output.display(),
                again.violations.len()
            );
            return Ok(ExitCode::from(1));
        }
    }
    write_atomically(&args.output, |w| std::io::Write::write_all(w, &bytes))
        .map_err(|e| format!("{}: cannot write: {e}", args.output.display()))?;
    if args.json {
        out.write(format!(
            "{:#}\n",
            report_json(&name, Some(&args.output), &imported, &repaired, seconds)
        ))?;
    } else {
        out.write(describe(&name, &imported, &repaired, seconds))?;
        out.write(format!("  wrote {}\n", args.output.display()))?;
    }
    if let Some(warning) = written.warning(&args.output) {
        eprintln!("warning: {warning}");
    }
    out.finish()?;
    Ok(ExitCode::SUCCESS)
}

/// Where input polygon `p` is, as `line N` or a place in the file.
fn place(imported: &Import, p: usize) -> String {
    imported
        .location(p)
        .map_or_else(|| format!("polygon {p}"), |l| format!("polygon {p} ({l})"))
}

/// The text report.
fn describe(name: &str, imported: &Import, repaired: &Repaired, seconds: f64) -> String {
    let r = &repaired.report;
    let mut text = format!("{name}: repaired in {seconds:.3} s\n");
    let mut line = |s: String| {
        text.push_str("  ");
        text.push_str(&s);
        text.push('\n');
    };
    line(format!(
        "welded {} vertices (bit-identical positions)",
        r.welded + imported.weld.merged
    ));
    line(format!("dropped {} polygons", r.dropped.len()));
    for d in r.dropped.iter().take(5) {
        line(format!("  {}: {}", place(imported, d.polygon), d.reason));
    }
    line(format!(
        "turned over {} polygons{}",
        r.turned_over_count(),
        if r.non_orientable_pieces > 0 {
            format!(
                " ({} pieces cannot be oriented, left as they are)",
                r.non_orientable_pieces
            )
        } else {
            String::new()
        }
    ));
    line(format!(
        "filled {} holes ({} triangles)",
        r.filled.len(),
        r.filled.iter().map(|h| h.triangles).sum::<usize>()
    ));
    for h in r.filled.iter().take(5) {
        line(format!(
            "  {} edges, next to {}",
            h.edges,
            place(imported, h.next_to)
        ));
    }
    for (h, why) in &r.left_open {
        line(format!(
            "left open: a hole of {} edges next to {}: {}",
            h.edges,
            place(imported, h.next_to),
            match why {
                OpenReason::LargerThanLimit(n) => format!("more than --max-hole-edges {n}"),
                OpenReason::NotTriangulable => "its loop cannot be triangulated".to_string(),
            }
        ));
    }
    if r.resolved {
        line(format!(
            "resolved {} crossing or overlapping polygon pairs",
            r.crossing_pairs.len()
        ));
        for &(p, q) in r.crossing_pairs.iter().take(5) {
            line(format!(
                "  {} and {}",
                place(imported, p),
                place(imported, q)
            ));
        }
    }
    line(format!(
        "volume before {} (winding-number volume), after {}",
        measure(r.volume_before, 6),
        measure(r.volume_after, 6)
    ));
    if let Some(why) = &r.empty_because {
        line(format!("empty result: {why}"));
    }
    if let (Some(solid), Some(v)) = (&repaired.solid, &repaired.validation) {
        line(format!(
            "faces {}  vertices {}  edges {}  shells {}  {} (checked by the validator)",
            solid.face_count(),
            solid.vertex_count(),
            solid.edge_count(),
            v.shells,
            v.validity.describe()
        ));
    }
    text
}

/// The JSON report.
fn report_json(
    name: &str,
    output: Option<&Path>,
    imported: &Import,
    repaired: &Repaired,
    seconds: f64,
) -> Value {
    let r: &RepairReport = &repaired.report;
    let at = |p: usize| imported.location(p).map(|l| l.to_string());
    json!({
        "input": name,
        "output": output.map(|p| p.display().to_string()),
        "seconds": seconds,
        "stage_seconds": r.stage_seconds.iter().map(|(k, v)| (k.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
        "welded": r.welded + imported.weld.merged,
        "dropped": r.dropped.iter().map(|d| json!({
            "polygon": d.polygon, "at": at(d.polygon), "reason": d.reason.to_string(),
        })).collect::<Vec<_>>(),
        "turned_over": r.turned_over.iter().map(|t| json!({
            "polygons": t.polygons, "whole_piece": t.whole_piece,
        })).collect::<Vec<_>>(),
        "non_orientable_pieces": r.non_orientable_pieces,
        "filled": r.filled.iter().map(|h| json!({
            "edges": h.edges, "triangles": h.triangles, "next_to": h.next_to, "at": at(h.next_to),
        })).collect::<Vec<_>>(),
        "left_open": r.left_open.iter().map(|(h, why)| json!({
            "edges": h.edges, "next_to": h.next_to, "at": at(h.next_to),
            "reason": match why {
                OpenReason::LargerThanLimit(_) => "larger than --max-hole-edges",
                OpenReason::NotTriangulable => "not triangulable",
            },
        })).collect::<Vec<_>>(),
        "resolved": r.resolved,
        "crossing_pairs": r.crossing_pairs,
        "volume_before": r.volume_before,
        "volume_after": r.volume_after,
        "empty": repaired.solid.as_ref().map(|s| s.face_count() == 0),
        "empty_because": r.empty_because,
        "faces": repaired.solid.as_ref().map(|s| s.face_count()),
        "vertices": repaired.solid.as_ref().map(|s| s.vertex_count()),
        "validity": repaired.validation.as_ref().map(|v| v.validity),
        "shells": repaired.validation.as_ref().map(|v| v.shells),
    })
}
