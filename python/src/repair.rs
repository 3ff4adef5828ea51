//! `wingedge.repair`: a mesh that is no solid made a valid solid
//! (`wingedge::repair::repair`), with what changed as a dictionary.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::{PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use wingedge::io::{ImportOptions, import};
use wingedge::mesh::PolygonSoup;
use wingedge::repair::{OpenReason, RepairOptions, Repaired, repair};

use crate::arrays;
use crate::boolean::result_inner;
use crate::errors;
use crate::report::validity_name;
use crate::solid::{PySolid, parse_format, weld_mode};

/// The repaired solid (`None` when holes were left open) and the report.
type Answer = (Option<PySolid>, Py<PyDict>);

/// Repairs the mesh file at `path` (any format the readers take).
#[pyfunction]
#[pyo3(signature = (path, max_hole_edges=None, weld=None, format=None))]
pub(crate) fn repair_path(
    py: Python<'_>,
    path: PathBuf,
    max_hole_edges: Option<usize>,
    weld: Option<&Bound<'_, PyAny>>,
    format: Option<&str>,
) -> PyResult<Answer> {
    let options = ImportOptions {
        weld: weld_mode(weld)?,
        format: format.map(parse_format).transpose()?,
        ..ImportOptions::default()
    };
    let (repaired, welded) = py.detach(|| -> PyResult<(Repaired, usize)> {
        let imported = import(&path, &options).map_err(errors::import)?;
        let repaired = run(&imported.soup, max_hole_edges)?;
        Ok((repaired, imported.weld.merged))
    })?;
    answer(py, repaired, welded)
}

/// Repairs the soup of vertices `(n, 3)`, face sizes and flat indices.
#[pyfunction]
#[pyo3(signature = (vertices, sizes, indices, max_hole_edges=None))]
pub(crate) fn repair_flat(
    py: Python<'_>,
    vertices: PyReadonlyArray2<'_, f64>,
    sizes: PyReadonlyArray1<'_, i64>,
    indices: PyReadonlyArray1<'_, i64>,
    max_hole_edges: Option<usize>,
) -> PyResult<Answer> {
    let soup = arrays::soup(&vertices, &sizes, &indices)?;
    let repaired = py.detach(|| run(&soup, max_hole_edges))?;
    answer(py, repaired, 0)
}

fn run(soup: &PolygonSoup, max_hole_edges: Option<usize>) -> PyResult<Repaired> {
    let options = RepairOptions {
        max_hole_edges,
        ..RepairOptions::default()
    };
    repair(soup, &options).map_err(|e| errors::ValidationError::new_err(e.to_string()))
}

/// The solid handed over as a Python `Solid`, and the report as a dict
/// (`welded` counts the reader's merges too).
fn answer(py: Python<'_>, repaired: Repaired, welded: usize) -> PyResult<Answer> {
    let solid = match &repaired.solid {
        Some(s) => Some(PySolid {
            inner: Arc::new(result_inner(s, None)?),
        }),
        None => None,
    };
    let r = &repaired.report;
    let report = PyDict::new(py);
    report.set_item("welded", r.welded + welded)?;
    let dropped: Vec<(usize, String)> = r
        .dropped
        .iter()
        .map(|d| (d.polygon, d.reason.to_string()))
        .collect();
    report.set_item("dropped", dropped)?;
    let turned: Vec<Vec<usize>> = r.turned_over.iter().map(|t| t.polygons.clone()).collect();
    report.set_item("turned_over", turned)?;
    let filled: Vec<(usize, usize)> = r.filled.iter().map(|h| (h.edges, h.triangles)).collect();
    report.set_item("filled", filled)?;
    let open: Vec<(usize, &str)> = r
        .left_open
        .iter()
        .map(|(h, why)| {
            let why = match why {
                OpenReason::LargerThanLimit(_) => "larger than max_hole_edges",
                OpenReason::NotTriangulable => "not triangulable",
            };
            (h.edges, why)
        })
        .collect();
    report.set_item("left_open", open)?;
    report.set_item("crossing_pairs", r.crossing_pairs.len())?;
    report.set_item("resolved", r.resolved)?;
    report.set_item("volume_before", r.volume_before)?;
    report.set_item("volume_after", r.volume_after)?;
    report.set_item("empty_because", r.empty_because.clone())?;
    report.set_item(
        "validity",
        repaired
            .validation
            .as_ref()
            .map(|v| validity_name(v.validity)),
    )?;
    Ok((solid, report.unbind()))
}
