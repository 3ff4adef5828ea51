//! `wingedge.render_defects`: the picture `wingedge validate --image`
//! draws, as a `(height, width, 3)` uint8 numpy array: the mesh with the
//! defects of its report marked and a legend of the count per rule.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArray3, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use wingedge::io::{ImportOptions, import};
use wingedge::mesh::PolygonSoup;
use wingedge::render::{DefectImageOptions, render_defects};
use wingedge::validate::{Violation, validate_import, validate_soup};

use crate::errors::ValidationError;
use crate::report::{PyReport, options};
use crate::solid::{PySolid, parse_format, weld_mode};

/// The picture of `soup` with `violations` marked, as an array.
fn picture<'py>(
    py: Python<'py>,
    soup: &PolygonSoup,
    violations: &[Violation],
    width: u32,
    height: u32,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let image = py
        .detach(|| render_defects(soup, violations, &DefectImageOptions { width, height }))
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    image
        .rgb_bytes()
        .to_vec()
        .into_pyarray(py)
        .reshape([height as usize, width as usize, 3])
}

/// The defect picture of a mesh file of any format: of `report` when it
/// is given (a report of this file, read with the same weld), else of the
/// file's own validation.
#[pyfunction]
#[pyo3(signature = (path, width=800, height=600, report=None, weld=None, planarity=None, format=None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_defects_path<'py>(
    py: Python<'py>,
    path: PathBuf,
    width: u32,
    height: u32,
    report: Option<&PyReport>,
    weld: Option<&Bound<'_, PyAny>>,
    planarity: Option<f64>,
    format: Option<&str>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let weld = weld_mode(weld)?;
    let format = format.map(parse_format).transpose()?;
    let options = options(planarity)?;
    let given = report.map(PyReport::core_violations).transpose()?;
    let (soup, violations) = py.detach(|| {
        let import = import(
            &path,
            &ImportOptions {
                weld,
                format,
                ..ImportOptions::default()
            },
        )
        .map_err(crate::errors::import)?;
        let violations = match given {
            Some(v) => v,
            None => {
                validate_import(&import, &options)
                    .map_err(|e| ValidationError::new_err(format!("{}: {e}", path.display())))?
                    .violations
            }
        };
        Ok::<_, PyErr>((import.soup, violations))
    })?;
    picture(py, &soup, &violations, width, height)
}

/// The defect picture of a solid's source soup: of `report` when it is
/// given, else of the soup's own validation.
#[pyfunction]
#[pyo3(signature = (solid, width=800, height=600, report=None, planarity=None))]
pub(crate) fn render_defects_solid<'py>(
    py: Python<'py>,
    solid: &PySolid,
    width: u32,
    height: u32,
    report: Option<&PyReport>,
    planarity: Option<f64>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let options = options(planarity)?;
    let inner = &solid.inner;
    let soup = &inner.soup;
    let violations = match report {
        Some(report) => report.core_violations()?,
        None => py.detach(|| {
            validate_soup(soup, inner.vertex_lines.as_deref(), &options)
                .map(|r| r.violations)
                .map_err(|e| ValidationError::new_err(e.to_string()))
        })?,
    };
    picture(py, soup, &violations, width, height)
}
