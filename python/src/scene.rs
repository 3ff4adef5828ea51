//! `wingedge.Scene`: a CSG tree from the JSON scene format, answered by ray
//! casting (Roth's method): point classes, first hits, spans, volume and
//! images; or evaluated to a solid by exact booleans.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;
use wingedge::csg::{EvaluateError, EvaluateOptions, Stats, VolumeError, evaluate};
use wingedge::geom::Ray;
use wingedge::geom::Readable;
use wingedge::glam::DVec3;
use wingedge::io::ImportOptions;
use wingedge::query::QueryError as CoreQueryError;
use wingedge::render::{RenderOptions, render};
use wingedge::scene::Scene;

use crate::arrays;
use crate::boolean::result_inner;
use crate::errors::{self, WingedgeError};
use crate::solid::{PySolid, code};

create_exception!(
    wingedge,
    SceneError,
    WingedgeError,
    "A scene file or JSON text that cannot be used: the message names the \
     file, the JSON position or the JSON path."
);

/// Import options whose only setting is the folders a scene's leaves may
/// also resolve into.
fn allowing(allow_paths: Option<Vec<PathBuf>>) -> ImportOptions {
    ImportOptions {
        allowed_roots: allow_paths.unwrap_or_default(),
        ..ImportOptions::default()
    }
}

/// A scene loaded from a file or from JSON text.
#[pyclass(name = "NativeScene", module = "wingedge._wingedge", frozen)]
pub struct PyScene {
    scene: Arc<Scene>,
}

#[pymethods]
impl PyScene {
    /// Reads a scene file (mesh paths relative to its folder); leaves must
    /// resolve inside its folder, the working directory or a folder of
    /// `allow_paths`.
    #[staticmethod]
    #[pyo3(signature = (path, allow_paths = None))]
    fn load(py: Python<'_>, path: PathBuf, allow_paths: Option<Vec<PathBuf>>) -> PyResult<PyScene> {
        let options = allowing(allow_paths);
        let scene = py
            .detach(|| Scene::from_file_with(&path, &options))
            .map_err(|e| SceneError::new_err(e.to_string()))?;
        Ok(PyScene {
            scene: Arc::new(scene),
        })
    }

    /// Parses scene text; `base` is the folder mesh paths are relative to,
    /// and leaves must resolve inside it, the working directory or a folder
    /// of `allow_paths`.
    #[staticmethod]
    #[pyo3(signature = (text, base, allow_paths = None))]
    fn from_json(
        py: Python<'_>,
        text: &str,
        base: PathBuf,
        allow_paths: Option<Vec<PathBuf>>,
    ) -> PyResult<PyScene> {
        let options = allowing(allow_paths);
        let scene = py
            .detach(|| Scene::from_json_with(text, "<json>", &base, &options))
            .map_err(|e| SceneError::new_err(e.to_string()))?;
        Ok(PyScene {
            scene: Arc::new(scene),
        })
    }

    /// `(min, max)` corners of the tree's bounds (may be infinite).
    #[getter]
    fn bounds(&self) -> ((f64, f64, f64), (f64, f64, f64)) {
        let b = self.scene.csg.bounds();
        (b.min.into(), b.max.into())
    }

    /// Number of leaves.
    #[getter]
    fn leaf_count(&self) -> usize {
        self.scene.csg.leaves().len()
    }

    /// Point classes: int8, `1` inside, `0` on the boundary, `-1` outside.
    fn _classify<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let points = arrays::points(&points, "points")?;
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
            return Err(errors::query(CoreQueryError::NonFinitePoint {
                index,
                point: points[index],
            }));
        }
        let csg = &self.scene.csg;
        let codes: Vec<i8> = py.detach(|| {
            points
                .par_iter()
                .with_min_len(256)
                .map_init(Stats::default, |stats, &p| {
                    code(csg.classify_point(p, stats))
                })
                .collect()
        });
        Ok(codes.into_pyarray(py))
    }

    /// First hits: `t` (inf for a miss) and the leaf hit (-1 for a miss).
    #[allow(clippy::type_complexity)]
    fn _first_hit<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray2<'py, f64>,
        directions: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<i64>>)> {
        let rays = arrays::rays(&origins, &directions)?;
        let csg = &self.scene.csg;
        // The rays users give: checked and scaled (`Csg::try_first_hit`);
        // the first refusal, by index, is the error.
        let hits: Vec<Result<(f64, i64), CoreQueryError>> = py.detach(|| {
            rays.par_iter()
                .enumerate()
                .with_min_len(64)
                .map_init(Stats::default, |stats, (index, ray)| {
                    csg.try_first_hit_at(index, ray, stats)
                        .map(|hit| hit.map_or((f64::INFINITY, -1), |h| (h.t, i64::from(h.leaf.0))))
                })
                .collect()
        });
        let (t, leaf): (Vec<f64>, Vec<i64>) = hits
            .into_iter()
            .collect::<Result<Vec<_>, _>>()
            .map_err(errors::query)?
            .into_iter()
            .unzip();
        Ok((t.into_pyarray(py), leaf.into_pyarray(py)))
    }

    /// The spans of one ray inside the solid, as an `(n, 2)` array of
    /// `[t_enter, t_leave]` (`t_enter` 0 when the origin is inside).
    fn _spans<'py>(
        &self,
        py: Python<'py>,
        origin: (f64, f64, f64),
        direction: (f64, f64, f64),
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let ray = Ray::new(DVec3::from(origin), DVec3::from(direction));
        let spans = self
            .scene
            .csg
            .try_spans(&ray, &mut Stats::default())
            .map_err(errors::query)?;
        let intervals = spans.intervals();
        let flat: Vec<f64> = intervals.iter().flat_map(|&(a, b)| [a, b]).collect();
        flat.into_pyarray(py).reshape([intervals.len(), 2])
    }

    /// Volume by ray integration on a grid of spacing `spacing` (`None`:
    /// the default grid, fine enough for every leaf that adds volume):
    /// `(volume, spacing used, rays cast, closed form or None, warning or
    /// None)`; the warning names a leaf narrower than a cell.
    #[pyo3(signature = (spacing=None))]
    #[allow(clippy::type_complexity)]
    fn volume(
        &self,
        py: Python<'_>,
        spacing: Option<f64>,
    ) -> PyResult<(f64, f64, u64, Option<f64>, Option<String>)> {
        let csg = &self.scene.csg;
        let estimate = py
            .detach(|| match spacing {
                Some(h) => csg.try_volume(h),
                None => csg.try_default_volume(),
            })
            .map_err(|e| match e {
                VolumeError::BadSpacing { .. } => PyValueError::new_err(format!("spacing: {e}")),
                other => PyValueError::new_err(other.to_string()),
            })?;
        let warning = estimate.unresolved.map(|u| {
            let label = csg
                .leaf(u.narrowest)
                .map_or("a leaf", |l| l.label.as_str());
            format!(
                "{} leaf(s) narrower than a grid cell may be missed: {label} is {} wide along {} (cells of {}); give a smaller spacing",
                u.count,
                Readable(u.width),
                ["x", "y"][u.axis],
                Readable(estimate.spacing)
            )
        });
        Ok((
            estimate.volume,
            estimate.spacing,
            estimate.rays,
            estimate.exact,
            warning,
        ))
    }

    /// A ray-cast image, `(height, width, 3)` uint8.
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: u32,
        height: u32,
    ) -> PyResult<Bound<'py, PyArray3<u8>>> {
        const MAX_PIXELS: u64 = 1 << 26;
        if width == 0 || height == 0 || u64::from(width) * u64::from(height) > MAX_PIXELS {
            return Err(PyValueError::new_err(format!(
                "image size {width}x{height}: both sides at least 1, at most {MAX_PIXELS} pixels"
            )));
        }
        let options = RenderOptions {
            width,
            height,
            ..RenderOptions::default()
        };
        let scene = &self.scene;
        let image = py.detach(|| render(scene, &options, &|_| {}).0);
        image
            .rgb_bytes()
            .to_vec()
            .into_pyarray(py)
            .reshape([height as usize, width as usize, 3])
    }

    /// The tree evaluated to one valid solid by exact booleans (boundary
    /// evaluation in one pass over all leaves); spheres and cylinders are
    /// inscribed polyhedra within `tolerance` of their radius (the crate's
    /// default when `None`). The interpreter lock is released meanwhile.
    #[pyo3(signature = (tolerance=None))]
    fn evaluate(&self, py: Python<'_>, tolerance: Option<f64>) -> PyResult<PySolid> {
        let mut options = EvaluateOptions::default();
        if let Some(tolerance) = tolerance {
            options.tolerance = tolerance;
        }
        let csg = &self.scene.csg;
        let inner = py.detach(|| {
            let evaluated = evaluate(csg, &options).map_err(|e| match e {
                EvaluateError::Leaf { .. } => SceneError::new_err(e.to_string()),
                other => errors::BooleanError::new_err(other.to_string()),
            })?;
            // Each face's origin: the leaf (in the scene's leaf order) and
            // the face of the leaf's polyhedron.
            let origin = |face: wingedge::mesh::FaceId| -> [i64; 2] {
                evaluated
                    .solid
                    .face(face)
                    .attributes
                    .source_index
                    .and_then(|i| evaluated.origins.get(i))
                    .map_or([-1, -1], |o| [i64::from(o.leaf.0), o.face as i64])
            };
            result_inner(&evaluated.solid, Some(&origin))
        })?;
        Ok(PySolid {
            inner: Arc::new(inner),
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "<wingedge.Scene: {} leaves, {} operators>",
            self.scene.csg.leaves().len(),
            self.scene.csg.operator_count()
        )
    }
}

/// Adds the scene's exception class to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add_class::<PyScene>()
}
