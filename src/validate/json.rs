//! A report as JSON: the element `wingedge validate --json` prints for one
//! file, shared by the command line and the Python binding.

use std::path::Path;

use serde_json::{Map, Value, json};

use crate::io::{WeldMode, WeldReport};

use super::{Report, Rule};

/// The report's fields (as serialised) plus `file`, `valid`, `verdict`,
/// `counts` (violations per rule, every rule named), `overflow` (the
/// measures too large for `f64`, see [`Report::overflowing_measures`]; their
/// values are `null`) and, when the input was
/// welded, `weld` (mode, vertices merged, merges refused).
#[must_use]
pub fn report_json(report: &Report, file: Option<&Path>, weld: Option<&WeldReport>) -> Value {
    let mut map = match serde_json::to_value(report) {
        Ok(Value::Object(map)) => map,
        _ => Map::new(),
    };
    let counts: Map<String, Value> = Rule::ALL
        .iter()
        .map(|&r| (r.name().to_string(), json!(report.count(r))))
        .collect();
    if let Some(file) = file {
        map.insert("file".into(), json!(file.display().to_string()));
    }
    map.insert("valid".into(), json!(report.is_valid()));
    map.insert("verdict".into(), json!(report.validity.describe()));
    map.insert("counts".into(), Value::Object(counts));
    // Non-finite measures serialise as null; say which, and why.
    map.insert("overflow".into(), json!(report.overflowing_measures()));
    if let Some(weld) = weld {
        map.insert(
            "weld".into(),
            json!({
                "mode": match weld.mode {
                    WeldMode::None => "none".to_string(),
                    WeldMode::Exact => "exact".to_string(),
                    WeldMode::Within(t) => format!("within {}", t.weld),
                },
                "merged": weld.merged,
                "refused": weld.refused.iter().map(ToString::to_string).collect::<Vec<_>>(),
            }),
        );
    }
    Value::Object(map)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::mesh::PolygonSoup;
    use crate::validate::{Options, validate_soup};

    fn unit_cube(faces: usize) -> PolygonSoup {
        let positions = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, (i >> 1 & 1) as f64, (i >> 2) as f64))
            .collect();
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [3, 2, 6, 7],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        PolygonSoup::new(positions, quads.iter().take(faces))
    }

    #[test]
    fn a_valid_cube_is_valid_with_every_rule_counted() {
        let report = validate_soup(&unit_cube(6), None, &Options::default()).unwrap();
        let value = report_json(&report, Some(Path::new("cube.obj")), None);
        assert_eq!(value["file"], "cube.obj");
        assert_eq!(value["valid"], true);
        assert_eq!(value["verdict"], "valid closed solid");
        // The volume is a rounded construction: within an ulp of 1.
        let volume = value["volume"].as_f64().unwrap();
        assert!((volume - 1.0).abs() <= f64::EPSILON, "{volume}");
        let counts = value["counts"].as_object().unwrap();
        assert_eq!(counts.len(), Rule::ALL.len());
        assert!(counts.values().all(|c| c == 0));
        assert!(value.get("weld").is_none());
    }

    #[test]
    fn a_cube_without_its_last_face_counts_its_open_edges() {
        let report = validate_soup(&unit_cube(5), None, &Options::default()).unwrap();
        let value = report_json(&report, None, None);
        assert_eq!(value["valid"], false);
        assert!(value.get("file").is_none());
        assert_eq!(value["counts"][Rule::EdgeInOneFace.name()], 4);
        assert_eq!(
            value["violations"].as_array().unwrap().len(),
            report.violations.len()
        );
    }
}
