//! `wingedge.validate`, `wingedge.Report` and `wingedge.Violation`: what
//! validation found, as immutable typed objects built from the crate's
//! `validate::Report`.
//!
//! A `Report` holds the content of the element `wingedge validate --json`
//! prints for one file, field for field: measures that overflow `f64` are
//! `None` there as they are `null` in the JSON. `to_json` writes that element
//! (by serde, from these fields), and pickling goes through it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyType};
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use wingedge::geom::Tolerance;
use wingedge::io::{ImportOptions, WeldMode, WeldReport, import};
use wingedge::validate::{
    self, Options, Rule, ShellSummary, Validity, validate_import, validate_soup,
};

use crate::errors::ValidationError;
use crate::solid::{PySolid, weld_mode};

/// A measure as the JSON report has it: `None` when it does not fit in `f64`.
fn finite(value: f64) -> Option<f64> {
    value.is_finite().then_some(value)
}

/// One broken rule, located: `line` is the OBJ line of the first element
/// named, `lines` those of all of them, `vertices` and `faces` 0-based
/// element ids (vertices after welding). Immutable, compared by value,
/// picklable.
#[pyclass(frozen, eq, get_all, name = "Violation", module = "wingedge")]
#[derive(PartialEq, Serialize, Deserialize)]
pub(crate) struct PyViolation {
    /// The rule broken, by its snake-case name (a key of `Report.counts`).
    rule: String,
    /// A sentence saying what is wrong and where.
    message: String,
    /// The OBJ line of the defect, where it has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    line: Option<usize>,
    /// The OBJ lines of every element involved.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    lines: Vec<usize>,
    /// The vertices involved (for an edge: its two ends, in the direction
    /// that matters).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    vertices: Vec<usize>,
    /// The faces involved.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    faces: Vec<usize>,
    /// A measured quantity, where the rule has one (a non-planar face's
    /// deviation, a shell's signed volume, a vertex's edge count); None
    /// when it overflows `f64` (the printed JSON has `null` there).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    value: Option<f64>,
}

impl PyViolation {
    fn new(violation: &validate::Violation) -> PyViolation {
        PyViolation {
            rule: violation.rule.name().to_string(),
            message: violation.message.clone(),
            line: violation.line,
            lines: violation.lines.clone(),
            vertices: violation.vertices.clone(),
            faces: violation.faces.clone(),
            value: violation.value.and_then(finite),
        }
    }
}

#[pymethods]
impl PyViolation {
    /// The violation as the JSON object in `wingedge validate --json`.
    fn to_json(&self) -> PyResult<String> {
        to_json(self)
    }

    /// A violation from the text of :meth:`to_json` (how it unpickles).
    #[classmethod]
    fn _from_json(_cls: &Bound<'_, PyType>, text: &str) -> PyResult<PyViolation> {
        from_json(text)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        reduce(slf)
    }

    fn __repr__(&self) -> String {
        let line = self.line.map(|l| format!(", line={l}")).unwrap_or_default();
        format!(
            "Violation(rule={:?}{line}, message={:?})",
            self.rule, self.message
        )
    }
}

/// One connected component of the surface: a dict in `Report.shell_details`
/// with the fields of the crate's `ShellSummary` (measures that overflow
/// `f64` are None).
#[derive(Clone, PartialEq, Serialize, Deserialize, IntoPyObject)]
struct Shell {
    faces: usize,
    vertices: usize,
    edges: usize,
    boundary_edges: usize,
    euler_characteristic: i64,
    genus: Option<i64>,
    volume: Option<f64>,
    area: Option<f64>,
    closed: bool,
    depth: Option<usize>,
    parent: Option<usize>,
    first_line: Option<usize>,
}

impl Shell {
    fn new(shell: &ShellSummary) -> Shell {
        Shell {
            faces: shell.faces,
            vertices: shell.vertices,
            edges: shell.edges,
            boundary_edges: shell.boundary_edges,
            euler_characteristic: shell.euler_characteristic,
            genus: shell.genus,
            volume: finite(shell.volume),
            area: finite(shell.area),
            closed: shell.closed,
            depth: shell.depth,
            parent: shell.parent,
            first_line: shell.first_line,
        }
    }
}

/// What the weld of a file did: a dict in `Report.weld`.
#[derive(Clone, PartialEq, Serialize, Deserialize, IntoPyObject)]
struct Weld {
    /// `"none"`, `"exact"` or `"within <tolerance>"`.
    mode: String,
    /// Vertices merged into others.
    merged: usize,
    /// The merges refused, each with its reason.
    refused: Vec<String>,
}

impl Weld {
    fn new(weld: &WeldReport) -> Weld {
        Weld {
            mode: match weld.mode {
                WeldMode::None => "none".to_string(),
                WeldMode::Exact => "exact".to_string(),
                WeldMode::Within(t) => format!("within {}", t.weld),
            },
            merged: weld.merged,
            refused: weld.refused.iter().map(ToString::to_string).collect(),
        }
    }
}

/// The report's violations, made Python objects once: every read of
/// `Report.violations` lists the same objects.
struct Violations(Vec<Py<PyViolation>>);

impl PartialEq for Violations {
    fn eq(&self, other: &Violations) -> bool {
        self.0.len() == other.0.len()
            && self.0.iter().zip(&other.0).all(|(a, b)| a.get() == b.get())
    }
}

impl Serialize for Violations {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(self.0.iter().map(Py::get))
    }
}

impl<'de> Deserialize<'de> for Violations {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Violations, D::Error> {
        let violations = Vec::<PyViolation>::deserialize(deserializer)?;
        Python::attach(|py| {
            violations
                .into_iter()
                .map(|v| Py::new(py, v))
                .collect::<PyResult<_>>()
        })
        .map(Violations)
        .map_err(D::Error::custom)
    }
}

impl<'py> IntoPyObject<'py> for &Violations {
    type Target = PyList;
    type Output = Bound<'py, PyList>;
    type Error = PyErr;

    fn into_pyobject(self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        PyList::new(py, &self.0)
    }
}

/// What validation found: the content of `wingedge validate --json` for
/// one file, as typed fields. Immutable, compared by value, picklable.
#[pyclass(frozen, eq, get_all, name = "Report", module = "wingedge")]
#[derive(PartialEq, Serialize, Deserialize)]
pub(crate) struct PyReport {
    /// Whether the input is a valid closed solid.
    valid: bool,
    /// The grade reached, in words (`"valid closed solid"`).
    verdict: String,
    /// The grade reached, by name: `"not_a_surface"`, `"manifold_surface"`,
    /// `"oriented_surface"`, `"closed_oriented_surface"` or `"valid_solid"`.
    validity: String,
    /// Vertices (after welding; unreferenced ones included).
    vertices: usize,
    /// Distinct edges.
    edges: usize,
    /// Faces.
    faces: usize,
    /// Connected components of the surface.
    shells: usize,
    /// Holes: loops of edges with one face.
    holes: usize,
    /// Summed genus of the shells when every shell is closed, else None.
    genus: Option<i64>,
    /// Enclosed volume when the solid was built and every shell is closed;
    /// None otherwise or when it overflows (see `overflow`).
    volume: Option<f64>,
    /// Total face area; None when it overflows (see `overflow`).
    area: Option<f64>,
    /// Why the winged-edge solid could not be built, if it could not.
    not_built: Option<String>,
    /// Violations per rule, every rule named.
    counts: BTreeMap<String, usize>,
    /// Every violation found, grouped by rule.
    violations: Violations,
    /// Per-shell measures, a dict each (empty when the solid could not be
    /// built).
    shell_details: Vec<Shell>,
    /// The file validated, if it was read from one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    file: Option<String>,
    /// What the weld did, for a file: its `mode` (`"none"`, `"exact"` or
    /// `"within <tolerance>"`), the vertices `merged`, the `refused` merges.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    weld: Option<Weld>,
    /// The measures too large for `f64` (`"volume"`, `"area"`,
    /// `"shell volume"`), reported as None.
    overflow: Vec<String>,
}

impl PyReport {
    /// The violations as the crate's type (how they are drawn).
    ///
    /// # Errors
    ///
    /// `ValueError` for a rule name the crate does not have (a report
    /// unpickled from edited JSON).
    pub(crate) fn core_violations(&self) -> PyResult<Vec<validate::Violation>> {
        self.violations
            .0
            .iter()
            .map(|v| {
                let v = v.get();
                let rule = Rule::ALL
                    .into_iter()
                    .find(|r| r.name() == v.rule)
                    .ok_or_else(|| PyValueError::new_err(format!("no rule named {:?}", v.rule)))?;
                Ok(validate::Violation {
                    rule,
                    message: v.message.clone(),
                    line: v.line,
                    lines: v.lines.clone(),
                    vertices: v.vertices.clone(),
                    faces: v.faces.clone(),
                    value: v.value,
                })
            })
            .collect()
    }

    fn new(
        py: Python<'_>,
        report: &validate::Report,
        file: Option<&Path>,
        weld: Option<&WeldReport>,
    ) -> PyResult<PyReport> {
        Ok(PyReport {
            valid: report.is_valid(),
            verdict: report.validity.describe().to_string(),
            validity: validity_name(report.validity),
            vertices: report.vertices,
            edges: report.edges,
            faces: report.faces,
            shells: report.shells,
            holes: report.holes,
            genus: report.genus,
            volume: report.volume.and_then(finite),
            area: finite(report.area),
            not_built: report.not_built.clone(),
            counts: Rule::ALL
                .iter()
                .map(|&rule| (rule.name().to_string(), report.count(rule)))
                .collect(),
            violations: Violations(
                report
                    .violations
                    .iter()
                    .map(|v| Py::new(py, PyViolation::new(v)))
                    .collect::<PyResult<_>>()?,
            ),
            shell_details: report.shell_details.iter().map(Shell::new).collect(),
            file: file.map(|f| f.display().to_string()),
            weld: weld.map(Weld::new),
            overflow: report
                .overflowing_measures()
                .into_iter()
                .map(String::from)
                .collect(),
        })
    }
}

/// A grade's snake-case name, as the JSON report writes it.
pub(crate) fn validity_name(validity: Validity) -> String {
    match serde_json::to_value(validity) {
        Ok(serde_json::Value::String(name)) => name,
        _ => unreachable!("a validity serialises as its name"),
    }
}

fn to_json<T: Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// An object from the text of its `to_json` (how it unpickles). Floats
/// read back exactly: `serde_json`'s `float_roundtrip`.
fn from_json<'de, T: Deserialize<'de>>(text: &'de str) -> PyResult<T> {
    serde_json::from_str(text).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Pickles as `(type(obj)._from_json, (obj.to_json(),))`.
fn reduce<'py, T>(slf: &Bound<'py, T>) -> PyResult<(Bound<'py, PyAny>, (String,))>
where
    T: pyo3::PyClass<Frozen = pyo3::pyclass::boolean_struct::True> + Serialize + Sync,
{
    Ok((
        slf.as_any().get_type().getattr("_from_json")?,
        (to_json(slf.get())?,),
    ))
}

#[pymethods]
impl PyReport {
    /// The report as the element `wingedge validate --json` prints for the
    /// file (compact JSON text).
    fn to_json(&self) -> PyResult<String> {
        to_json(self)
    }

    /// The report as Python objects: `json.loads(report.to_json())`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        py.import("json")?.call_method1("loads", (self.to_json()?,))
    }

    /// A report from the text of :meth:`to_json` (how it unpickles).
    #[classmethod]
    fn _from_json(_cls: &Bound<'_, PyType>, text: &str) -> PyResult<PyReport> {
        from_json(text)
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        reduce(slf)
    }

    fn __repr__(&self) -> String {
        let broken: Vec<String> = self
            .counts
            .iter()
            .filter(|&(_, &n)| n > 0)
            .map(|(rule, n)| format!("'{rule}': {n}"))
            .collect();
        let file = self
            .file
            .as_ref()
            .map(|f| format!(", file={f:?}"))
            .unwrap_or_default();
        format!(
            "Report(verdict={:?}, vertices={}, edges={}, faces={}, violations={{{}}}{file})",
            self.verdict,
            self.vertices,
            self.edges,
            self.faces,
            broken.join(", ")
        )
    }
}

/// The validation options of a `planarity` argument.
pub(crate) fn options(planarity: Option<f64>) -> PyResult<Options> {
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

/// Validates a mesh file of any format: the report `validate --json`
/// prints for it.
#[pyfunction]
#[pyo3(signature = (path, weld=None, planarity=None, format=None))]
pub(crate) fn validate_path(
    py: Python<'_>,
    path: PathBuf,
    weld: Option<&Bound<'_, PyAny>>,
    planarity: Option<f64>,
    format: Option<&str>,
) -> PyResult<PyReport> {
    let weld = weld_mode(weld)?;
    let format = format.map(crate::solid::parse_format).transpose()?;
    let options = options(planarity)?;
    let (report, weld) = py.detach(|| {
        let import = import(
            &path,
            &ImportOptions {
                weld,
                format,
                ..ImportOptions::default()
            },
        )
        .map_err(crate::errors::import)?;
        let report = validate_import(&import, &options)
            .map_err(|e| ValidationError::new_err(format!("{}: {e}", path.display())))?;
        Ok::<_, PyErr>((report, import.weld))
    })?;
    PyReport::new(py, &report, Some(&path), Some(&weld))
}

/// Validates a solid (its source soup, with OBJ lines when it was read from
/// a file): the same report.
#[pyfunction]
#[pyo3(signature = (solid, planarity=None))]
pub(crate) fn validate_solid(
    py: Python<'_>,
    solid: &PySolid,
    planarity: Option<f64>,
) -> PyResult<PyReport> {
    let options = options(planarity)?;
    let inner = &solid.inner;
    let report = py.detach(|| {
        validate_soup(&inner.soup, inner.vertex_lines.as_deref(), &options)
            .map_err(|e| ValidationError::new_err(e.to_string()))
    })?;
    PyReport::new(py, &report, inner.path.as_deref(), None)
}
