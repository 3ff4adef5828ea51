//! `wingedge.validate`: the report of `wingedge validate --json`, as JSON
//! text that the Python wrapper turns into a `Report` object.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use wingedge::geom::Tolerance;
use wingedge::io::{ObjOptions, import_obj};
use wingedge::validate::{Options, report_json, validate_import, validate_soup};

use crate::errors::{ObjError, ValidationError};
use crate::solid::{PySolid, weld_mode};

fn options(planarity: Option<f64>) -> PyResult<Options> {
    let mut tolerance = Tolerance::default();
    if let Some(p) = planarity {
        if !(p.is_finite() && p >= 0.0) {
            return Err(PyValueError::new_err(format!(
                "planarity {p}: a tolerance is a finite fraction of the bounding-box diagonal, at least 0"
            )));
        }
        tolerance.planarity = p;
    }
    Ok(Options {
        tolerance,
        ..Options::default()
    })
}

/// Validates an OBJ file: the JSON object `validate --json` prints for it.
#[pyfunction]
#[pyo3(signature = (path, weld=None, planarity=None))]
pub(crate) fn validate_path(
    py: Python<'_>,
    path: PathBuf,
    weld: Option<&Bound<'_, PyAny>>,
    planarity: Option<f64>,
) -> PyResult<String> {
    let weld = weld_mode(weld)?;
    let options = options(planarity)?;
    py.detach(|| {
        let import = import_obj(
            &path,
            &ObjOptions {
                weld,
                ..ObjOptions::default()
            },
        )
        .map_err(|e| ObjError::new_err(e.to_string()))?;
        let report = validate_import(&import, &options)
            .map_err(|e| ValidationError::new_err(format!("{}: {e}", path.display())))?;
        Ok(report_json(&report, Some(&path), Some(&import.weld)).to_string())
    })
}

/// Validates a solid (its source soup, with OBJ lines when it was read from
/// a file): the same JSON object.
#[pyfunction]
#[pyo3(signature = (solid, planarity=None))]
pub(crate) fn validate_solid(
    py: Python<'_>,
    solid: &PySolid,
    planarity: Option<f64>,
) -> PyResult<String> {
    let options = options(planarity)?;
    let inner = &solid.inner;
    py.detach(|| {
        let report = validate_soup(&inner.soup, inner.vertex_lines.as_deref(), &options)
            .map_err(|e| ValidationError::new_err(e.to_string()))?;
        Ok(report_json(&report, inner.path.as_deref(), None).to_string())
    })
}
