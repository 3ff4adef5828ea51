//! `wingedge csg`: a scene's CSG tree evaluated by exact booleans into a
//! validated solid, written as OBJ.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use wingedge::csg::{EvaluateError, EvaluateOptions, evaluate};
use wingedge::io::{ImportOptions, write_obj};
use wingedge::scene::Scene;

use crate::output::{Out, Outcome, measure};

/// Evaluates the scene at `scene` and writes the solid to `output`. Exit 0
/// for a valid solid, 1 when a boolean's result could not be made valid
/// (the defect located, nothing written), 2 for a scene that cannot be read
/// or has leaves that cannot be evaluated. Leaves may also resolve inside
/// `allowed.allowed_roots`.
pub fn run(
    scene: &Path,
    output: &Path,
    tolerance: Option<f64>,
    one_pass: bool,
    json: bool,
    allowed: &ImportOptions,
) -> Outcome {
    let name = scene.display();
    let loaded = Scene::from_file_with(scene, allowed).map_err(|e| e.to_string())?;
    let options = EvaluateOptions {
        tolerance: tolerance.unwrap_or(EvaluateOptions::default().tolerance),
        by_structure: !one_pass,
    };
    let start = Instant::now();
    let evaluated = match evaluate(&loaded.csg, &options) {
        Ok(e) => e,
        Err(e @ EvaluateError::Boolean { .. }) => {
            let leaves: Vec<serde_json::Value> = match &e {
                EvaluateError::Boolean { leaves, .. } => leaves
                    .iter()
                    .map(|(k, label)| serde_json::json!({"operand": k, "leaf": label}))
                    .collect(),
                _ => Vec::new(),
            };
            // Exit 1: the scene was read, the result could not be made
            // valid; nothing is written. With --json, still one object.
            if json {
                let mut out = Out::new();
                let value = serde_json::json!({
                    "scene": name.to_string(),
                    "output": serde_json::Value::Null,
                    "validity": "invalid",
                    "error": format!("{name}: {e}"),
                    "leaves": leaves,
                });
                out.write(format!("{value:#}\n"))?;
                out.finish()?;
            }
            eprintln!("error: {name}: {e}; {} not written", output.display());
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(format!("{name}: {e}")),
    };
    let seconds = start.elapsed().as_secs_f64();
    let solid = &evaluated.solid;
    write_obj(solid, output).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    let report = &evaluated.report;
    let s = &evaluated.stats;
    let mut out = Out::new();
    if json {
        let seconds_by_stage: serde_json::Map<String, serde_json::Value> = [
            ("total", seconds),
            ("tessellate", evaluated.tessellate_seconds),
        ]
        .into_iter()
        .chain(s.stages())
        .map(|(name, t)| (name.to_string(), serde_json::json!(t)))
        .collect();
        let value = serde_json::json!({
            "scene": name.to_string(),
            "output": output.display().to_string(),
            "tolerance": options.tolerance,
            "booleans": evaluated.booleans,
            "faces": solid.face_count(),
            "vertices": solid.vertex_count(),
            "edges": solid.edge_count(),
            "rings": solid.ring_count(),
            "shells": report.shells,
            "genus": report.genus,
            "volume": solid.volume() + 0.0,
            "empty": solid.face_count() == 0,
            "validity": report.validity,
            "seconds": seconds_by_stage,
            "structure": {
                "by_structure": options.by_structure,
                "booleans": evaluated.structure.booleans,
                "exact": evaluated.structure.exact,
                "set_aside": evaluated.structure.set_aside,
                "by_boxes": evaluated.structure.by_boxes,
                "root_operands": evaluated.structure.root_operands,
            },
            "output_work": s
                .output
                .counts()
                .into_iter()
                .map(|(name, n)| (name.to_string(), serde_json::json!(n)))
                .collect::<serde_json::Map<_, _>>(),
        });
        out.write(format!("{value:#}\n"))?;
    } else {
        let genus = report
            .genus
            .map_or_else(|| "-".to_string(), |g| g.to_string());
        out.write(format!(
            "{name}: {} boolean{} (chord tolerance {})\n  \
             faces {}  rings {}  vertices {}  edges {}  shells {}  genus {genus}  volume {}\n  \
             {} (checked by the validator)\n  \
             writing: {}\n  \
             {seconds:.3} s: tessellate {:.3}, {}\n  wrote {}\n",
            evaluated.booleans,
            if evaluated.booleans == 1 { "" } else { "s" },
            options.tolerance,
            solid.face_count(),
            solid.ring_count(),
            solid.vertex_count(),
            solid.edge_count(),
            report.shells,
            measure(solid.volume(), 6),
            report.validity.describe(),
            s.output.describe(),
            evaluated.tessellate_seconds,
            s.stages_text(),
            output.display(),
        ))?;
    }
    out.finish()?;
    Ok(ExitCode::SUCCESS)
}
