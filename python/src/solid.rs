//! `wingedge.Solid`: a winged-edge solid with its query accel.
//!
//! Past 600 lines on purpose: one `#[pymethods]` block per class is what
//! pyo3 allows without its `multiple-pymethods` feature (which pulls in
//! `inventory` and slows every build), and the methods are the class's
//! Python surface, each a thin call into the library.
//!
//! # Invariants
//!
//! - `soup` is the polygon soup the solid was built from (for a built-in
//!   solid, the soup read back from it), so that validation, `to_arrays` and
//!   pickling see exactly the faces and vertex order the solid has;
//!   `Solid::try_from_soup(&soup)` rebuilds an identical solid (same face
//!   order, hence the same face indices in every answer).
//! - `face_index[f]` is the position of face `f` in the solid's face order,
//!   the index every answer reports.
//! - The accel is built on first use and shared by every later query.
//! - `proof`, once set, is the validator's verdict on `solid` as a boolean
//!   operand (set at once to `Ok` for a boolean's result, which was proven
//!   valid before it was handed over).
//! - `origins`, when present (a boolean's result), has one row per face in
//!   the solid's face order: the operand's index and the face's index in
//!   that operand's face order.

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use wingedge::geom::triangulate::triangulate_3d;
use wingedge::geom::{Ray, Tolerance};
use wingedge::glam::DVec3;
use wingedge::io::{Format, ImportOptions, ObjOptions, WeldMode, export, import, import_obj};
use wingedge::mesh::{PolygonSoup, Solid, builders};
use wingedge::query::{Accel, Containment, Method, Transition};

use crate::arrays;
use crate::errors;
use crate::face_index::FaceIndex;

/// What a Python `Solid` owns.
pub(crate) struct Inner {
    pub(crate) solid: Solid,
    pub(crate) soup: PolygonSoup,
    /// The OBJ `v` line of each soup vertex, when read from a file.
    pub(crate) vertex_lines: Option<Vec<usize>>,
    /// The file it was read from, if any.
    pub(crate) path: Option<PathBuf>,
    face_index: FaceIndex,
    accel: OnceLock<Accel>,
    /// Where each face came from, for a boolean's result.
    pub(crate) origins: Option<Vec<[i64; 2]>>,
    /// Whether the solid is a valid closed solid, as booleans need: proven
    /// once, on first use as an operand.
    pub(crate) proof: OnceLock<Result<(), wingedge::boolean::BooleanError>>,
}

impl Inner {
    pub(crate) fn new(
        solid: Solid,
        soup: PolygonSoup,
        vertex_lines: Option<Vec<usize>>,
        path: Option<PathBuf>,
    ) -> Inner {
        let face_index = FaceIndex::new(&solid);
        Inner {
            solid,
            soup,
            vertex_lines,
            path,
            face_index,
            accel: OnceLock::new(),
            origins: None,
            proof: OnceLock::new(),
        }
    }

    /// The empty solid (no faces): what a boolean returns when nothing is
    /// left.
    pub(crate) fn empty() -> Inner {
        Inner::new(Solid::default(), PolygonSoup::default(), None, None)
    }

    /// The position of `face` in the solid's face order (`-1` for a face
    /// of another solid).
    pub(crate) fn face_index_of(&self, face: wingedge::mesh::FaceId) -> i64 {
        self.face_index.of(face)
    }

    fn from_soup(soup: PolygonSoup) -> PyResult<Inner> {
        let solid = Solid::try_from_soup(&soup).map_err(errors::build)?;
        Ok(Inner::new(solid, soup, None, None))
    }

    fn from_builder(solid: Solid) -> Inner {
        let soup = solid.to_soup();
        // Rebuild from the soup so that the face order is the soup's.
        match Solid::try_from_soup(&soup) {
            Ok(rebuilt) => Inner::new(rebuilt, soup, None, None),
            Err(_) => Inner::new(solid, soup, None, None),
        }
    }

    fn accel(&self) -> &Accel {
        self.accel.get_or_init(|| Accel::new(&self.solid))
    }
}

/// Every polygon of `soup` as triangles (flat soup vertex indices, three
/// per triangle).
fn triangulate_soup(soup: &PolygonSoup) -> PyResult<Vec<i64>> {
    let mut out = Vec::with_capacity(soup.polygons.len() * 3);
    let mut corners = Vec::new();
    for (f, polygon) in soup.polygons.iter().enumerate() {
        let vertices = &polygon.vertices;
        if vertices.len() == 3 {
            out.extend(vertices.iter().map(|&v| v as i64));
            continue;
        }
        corners.clear();
        corners.extend(vertices.iter().map(|&v| soup.positions[v]));
        let triangles = triangulate_3d(&corners, &[]).map_err(|e| {
            errors::ValidationError::new_err(format!("face {f} cannot be triangulated: {e}"))
        })?;
        out.extend(
            triangles
                .iter()
                .flat_map(|t| t.iter().map(|&k| vertices[k] as i64)),
        );
    }
    Ok(out)
}

/// A winged-edge solid: Baumgart's structure, built from a polygon soup,
/// with exact inside/outside and ray queries.
#[pyclass(name = "NativeSolid", module = "wingedge._wingedge", frozen)]
pub struct PySolid {
    pub(crate) inner: Arc<Inner>,
}

fn method_of(name: &str) -> PyResult<Method> {
    match name {
        "parity" => Ok(Method::Parity),
        "normals" => Ok(Method::Normals),
        "winding" => Ok(Method::Winding),
        other => Err(PyValueError::new_err(format!(
            "method {other:?}: expected \"parity\", \"normals\" or \"winding\""
        ))),
    }
}

/// `1` inside, `0` on the boundary, `-1` outside: the sign convention of a
/// signed distance that is positive inside (as trimesh's).
pub(crate) fn code(c: Containment) -> i8 {
    match c {
        Containment::Inside => 1,
        Containment::OnBoundary => 0,
        Containment::Outside => -1,
    }
}

#[pymethods]
impl PySolid {
    /// A solid from vertices `(n, 3)` and faces (an `(m, k)` integer array or
    /// a flat index array with per-face sizes), each face counter-clockwise
    /// seen from outside. The wrapper `Solid.from_arrays` accepts lists.
    /// `origins`, an `(m, 2)` int64 array, restores a boolean result's
    /// face origins (as pickling hands them back).
    #[staticmethod]
    #[pyo3(signature = (vertices, sizes, indices, origins=None))]
    fn _from_flat(
        py: Python<'_>,
        vertices: PyReadonlyArray2<'_, f64>,
        sizes: PyReadonlyArray1<'_, i64>,
        indices: PyReadonlyArray1<'_, i64>,
        origins: Option<PyReadonlyArray2<'_, i64>>,
    ) -> PyResult<PySolid> {
        let soup = arrays::soup(&vertices, &sizes, &indices)?;
        let origins = origins
            .map(|o| arrays::origins(&o, soup.polygons.len()))
            .transpose()?;
        let mut inner = py.detach(|| Inner::from_soup(soup))?;
        inner.origins = origins;
        Ok(PySolid {
            inner: Arc::new(inner),
        })
    }

    /// The empty solid (no vertices, no faces), with no face origins, or
    /// with an empty origins array when `origins` is true (an empty
    /// boolean result, unpickled).
    #[staticmethod]
    fn _empty(origins: bool) -> PySolid {
        let mut inner = Inner::empty();
        if origins {
            inner.origins = Some(Vec::new());
        }
        PySolid {
            inner: Arc::new(inner),
        }
    }

    /// For a boolean's result, an `(m, 2)` int64 array with a row per face
    /// in face order: the operand's index and the index of the operand's
    /// face this face is part of, in that operand's face order; `None`
    /// for any other solid.
    #[getter]
    fn face_origins<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<i64>>>> {
        let Some(origins) = &self.inner.origins else {
            return Ok(None);
        };
        let flat: Vec<i64> = origins.iter().flatten().copied().collect();
        Ok(Some(flat.into_pyarray(py).reshape([origins.len(), 2])?))
    }

    /// Vertices `(n, 3)` float64, face sizes `(m,)` int64 and the flat face
    /// index array: the soup the solid was built from.
    #[allow(clippy::type_complexity)]
    fn _to_flat<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(
        Bound<'py, PyArray2<f64>>,
        Bound<'py, PyArray1<i64>>,
        Bound<'py, PyArray1<i64>>,
    )> {
        let soup = &self.inner.soup;
        let vertices = arrays::points_out(py, &soup.positions)?;
        let sizes: Vec<i64> = soup
            .polygons
            .iter()
            .map(|p| p.vertices.len() as i64)
            .collect();
        let indices: Vec<i64> = soup
            .polygons
            .iter()
            .flat_map(|p| p.vertices.iter().map(|&v| v as i64))
            .collect();
        Ok((vertices, sizes.into_pyarray(py), indices.into_pyarray(py)))
    }

    /// Vertices `(n, 3)` float64 (the soup's, in its order) and triangles
    /// `(t, 3)` int64: every face triangulated exactly (a triangle face is
    /// kept as it is; a larger face by `geom::triangulate_3d`, constrained to
    /// its edges, so no triangle is flipped or degenerate). Raises
    /// `ValidationError` naming the face when a face is not a simple planar
    /// polygon.
    #[allow(clippy::type_complexity)]
    fn _triangles<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<i64>>)> {
        let soup = &self.inner.soup;
        let triangles = py.detach(|| triangulate_soup(soup))?;
        let vertices = arrays::points_out(py, &soup.positions)?;
        let count = triangles.len() / 3;
        Ok((vertices, triangles.into_pyarray(py).reshape([count, 3])?))
    }

    /// Number of vertices.
    #[getter]
    fn vertex_count(&self) -> usize {
        self.inner.solid.vertex_count()
    }

    /// Number of edges.
    #[getter]
    fn edge_count(&self) -> usize {
        self.inner.solid.edge_count()
    }

    /// Number of faces.
    #[getter]
    fn face_count(&self) -> usize {
        self.inner.solid.face_count()
    }

    /// Whether every edge has two faces.
    #[getter]
    fn is_closed(&self) -> bool {
        self.inner.solid.is_closed()
    }

    /// Enclosed volume (a rounded construction; positive for an outward
    /// oriented closed surface).
    #[getter]
    fn volume(&self) -> f64 {
        self.inner.solid.volume()
    }

    /// Total face area.
    #[getter]
    fn area(&self) -> f64 {
        self.inner.solid.surface_area()
    }

    /// Summed genus of the shells, or `None` when a shell has holes.
    #[getter]
    fn genus(&self) -> Option<i64> {
        self.inner
            .solid
            .shells()
            .iter()
            .map(|s| s.genus())
            .sum::<Option<i64>>()
    }

    /// Number of connected shells.
    #[getter]
    fn shells(&self) -> usize {
        self.inner.solid.shells().len()
    }

    /// `(min, max)` corners of the bounding box.
    #[getter]
    fn bounds(&self) -> ((f64, f64, f64), (f64, f64, f64)) {
        let b = self.inner.solid.bounding_box();
        (b.min.into(), b.max.into())
    }

    /// The file the solid was read from, or `None`.
    #[getter]
    fn path(&self) -> Option<String> {
        self.inner.path.as_ref().map(|p| p.display().to_string())
    }

    /// Classifies points `(n, 3)`: int8, `1` inside, `0` on the boundary,
    /// `-1` outside (exact).
    fn _classify<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
        method: &str,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let method = method_of(method)?;
        let points = arrays::points(&points, "points")?;
        let inner = &self.inner;
        let codes = py.detach(|| {
            inner
                .accel()
                .classify_batch(&points, method)
                .map(|c| c.into_iter().map(code).collect::<Vec<i8>>())
        });
        Ok(codes.map_err(errors::query)?.into_pyarray(py))
    }

    /// Generalized winding numbers of points `(n, 3)`.
    fn _winding_number<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let points = arrays::points(&points, "points")?;
        let inner = &self.inner;
        let w = py.detach(|| inner.accel().winding_number_batch(&points));
        Ok(w.map_err(errors::query)?.into_pyarray(py))
    }

    /// First hits of rays: `t` (inf for a miss), face index (-1 for a
    /// miss), transition (`1` enter, `-1` exit, `0` miss).
    #[allow(clippy::type_complexity)]
    fn _ray_cast<'py>(
        &self,
        py: Python<'py>,
        origins: PyReadonlyArray2<'py, f64>,
        directions: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<i64>>,
        Bound<'py, PyArray1<i8>>,
    )> {
        let rays = arrays::rays(&origins, &directions)?;
        let inner = &self.inner;
        let (t, face, transition) = py
            .detach(|| {
                let hits = inner.accel().first_hit_batch(&rays)?;
                drop(rays);
                let mut t = Vec::with_capacity(hits.len());
                let mut face = Vec::with_capacity(hits.len());
                let mut transition = Vec::with_capacity(hits.len());
                for hit in hits {
                    match hit {
                        Some(c) => {
                            t.push(c.t);
                            face.push(inner.face_index.of(c.face));
                            transition.push(match c.transition {
                                Transition::Enter => 1i8,
                                Transition::Exit => -1,
                            });
                        }
                        None => {
                            t.push(f64::INFINITY);
                            face.push(-1);
                            transition.push(0);
                        }
                    }
                }
                Ok::<_, wingedge::query::QueryError>((t, face, transition))
            })
            .map_err(errors::query)?;
        Ok((
            t.into_pyarray(py),
            face.into_pyarray(py),
            transition.into_pyarray(py),
        ))
    }

    /// Every crossing of one ray: `(origin class, t, face, transition)`.
    #[allow(clippy::type_complexity)]
    fn _ray_crossings<'py>(
        &self,
        py: Python<'py>,
        origin: (f64, f64, f64),
        direction: (f64, f64, f64),
    ) -> PyResult<(
        i8,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<i64>>,
        Bound<'py, PyArray1<i8>>,
    )> {
        let ray = Ray::new(DVec3::from(origin), DVec3::from(direction));
        let crossings = self
            .inner
            .accel()
            .ray_crossings(&ray)
            .map_err(errors::query)?;
        let t: Vec<f64> = crossings.hits.iter().map(|c| c.t).collect();
        let face: Vec<i64> = crossings
            .hits
            .iter()
            .map(|c| self.inner.face_index.of(c.face))
            .collect();
        let transition: Vec<i8> = crossings
            .hits
            .iter()
            .map(|c| match c.transition {
                Transition::Enter => 1,
                Transition::Exit => -1,
            })
            .collect();
        Ok((
            code(crossings.origin),
            t.into_pyarray(py),
            face.into_pyarray(py),
            transition.into_pyarray(py),
        ))
    }

    /// Writes the solid to `path` (atomically) in `format` (default: by the
    /// extension); returns how many coordinates rounding to `f32` changed
    /// (STL and glTF; 0 for the formats that keep `f64`).
    #[pyo3(signature = (path, format=None))]
    fn _save(
        &self,
        py: Python<'_>,
        path: PathBuf,
        format: Option<&str>,
    ) -> PyResult<(usize, usize)> {
        let format = match format {
            Some(name) => parse_format(name)?,
            None => Format::from_path(&path).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "{}: cannot tell the format from the extension; pass format=\"obj\", \"stl\", \"ply\", \"off\", \"3mf\", \"gltf\" or \"glb\"",
                    path.display()
                ))
            })?,
        };
        let solid = &self.inner.solid;
        let report = py
            .detach(|| export(solid, &path, format))
            .map_err(|e| errors::FormatError::new_err(e.to_string()))?;
        Ok((report.rounded, report.coordinates))
    }

    fn __repr__(&self) -> String {
        let s = &self.inner.solid;
        format!(
            "<wingedge.Solid: {} vertices, {} edges, {} faces{}>",
            s.vertex_count(),
            s.edge_count(),
            s.face_count(),
            if s.is_closed() { "" } else { ", open" }
        )
    }
}

/// Reads an OBJ file into a solid.
#[pyfunction]
#[pyo3(signature = (path, weld=None, max_face_corners=None))]
pub(crate) fn load_obj(
    py: Python<'_>,
    path: PathBuf,
    weld: Option<&Bound<'_, PyAny>>,
    max_face_corners: Option<usize>,
) -> PyResult<PySolid> {
    let weld = weld_mode(weld)?;
    let mut options = ObjOptions {
        weld,
        ..ObjOptions::default()
    };
    if let Some(n) = max_face_corners {
        options.max_face_corners = n;
    }
    let inner = py.detach(|| -> PyResult<Inner> {
        let import = import_obj(&path, &options)
            .map_err(|e| crate::errors::ObjError::new_err(e.to_string()))?;
        let solid = Solid::try_from_soup(&import.soup).map_err(|e| errors::build_in(&path, e))?;
        Ok(Inner::new(
            solid,
            import.soup,
            Some(import.vertex_lines),
            Some(path.clone()),
        ))
    })?;
    Ok(PySolid {
        inner: Arc::new(inner),
    })
}

/// Reads a mesh file of any format into a solid.
#[pyfunction]
#[pyo3(signature = (path, weld=None, max_face_corners=None, format=None))]
pub(crate) fn load(
    py: Python<'_>,
    path: PathBuf,
    weld: Option<&Bound<'_, PyAny>>,
    max_face_corners: Option<usize>,
    format: Option<&str>,
) -> PyResult<PySolid> {
    let mut options = ImportOptions {
        weld: weld_mode(weld)?,
        format: format.map(parse_format).transpose()?,
        ..ImportOptions::default()
    };
    if let Some(n) = max_face_corners {
        options.max_face_corners = n;
    }
    let inner = py.detach(|| -> PyResult<Inner> {
        let import = import(&path, &options).map_err(errors::import)?;
        let solid = Solid::try_from_soup(&import.soup).map_err(|e| errors::build_in(&path, e))?;
        let lines = (!import.vertex_lines.is_empty()).then_some(import.vertex_lines);
        Ok(Inner::new(solid, import.soup, lines, Some(path.clone())))
    })?;
    Ok(PySolid {
        inner: Arc::new(inner),
    })
}

/// A format by its name (`stl`, `.ply`, any case).
pub(crate) fn parse_format(name: &str) -> PyResult<Format> {
    name.parse::<Format>()
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// `None` / `"exact"`: bit-identical positions merged where that closes
/// open edges (the default); `"none"`: nothing merged; a number: a weld
/// tolerance as a fraction of the bounding-box diagonal.
pub(crate) fn weld_mode(weld: Option<&Bound<'_, PyAny>>) -> PyResult<WeldMode> {
    let Some(weld) = weld else {
        return Ok(WeldMode::Exact);
    };
    if let Ok(word) = weld.extract::<String>() {
        return match word.as_str() {
            "exact" => Ok(WeldMode::Exact),
            "none" => Ok(WeldMode::None),
            other => Err(PyValueError::new_err(format!(
                "weld {other:?}: expected \"exact\", \"none\" or a tolerance"
            ))),
        };
    }
    let t: f64 = weld.extract()?;
    if !(t.is_finite() && t >= 0.0) {
        return Err(PyValueError::new_err(format!(
            "weld {t}: a tolerance is a finite fraction of the bounding-box diagonal, at least 0"
        )));
    }
    Ok(WeldMode::Within(Tolerance {
        weld: t,
        ..Tolerance::default()
    }))
}

/// A built-in solid by name (`tetrahedron`, `cube`, `octahedron`,
/// `dodecahedron`, `icosahedron`, `prism`).
#[pyfunction]
pub(crate) fn builtin(name: &str) -> PyResult<PySolid> {
    let solid = builders::by_name(name).ok_or_else(|| {
        PyValueError::new_err(format!(
            "no built-in solid {name:?}; there are {}",
            builders::NAMES.join(", ")
        ))
    })?;
    Ok(PySolid {
        inner: Arc::new(Inner::from_builder(solid)),
    })
}

/// The axis-aligned box between two corners.
#[pyfunction]
pub(crate) fn cuboid(min: (f64, f64, f64), max: (f64, f64, f64)) -> PyResult<PySolid> {
    let solid = builders::cuboid(min.into(), max.into()).map_err(errors::build)?;
    Ok(PySolid {
        inner: Arc::new(Inner::from_builder(solid)),
    })
}

/// A planar polygon `(n, 3)` (counter-clockwise seen from the side `sweep`
/// points away from) swept along the vector `sweep`.
#[pyfunction]
pub(crate) fn prism(
    profile: PyReadonlyArray2<'_, f64>,
    sweep: (f64, f64, f64),
) -> PyResult<PySolid> {
    let profile = arrays::points(&profile, "profile")?;
    let solid = builders::prism(&profile, sweep.into()).map_err(errors::build)?;
    Ok(PySolid {
        inner: Arc::new(Inner::from_builder(solid)),
    })
}

/// A triangulated UV sphere of radius 1: `rings` bands of latitude,
/// `2 · rings` segments, `4 · rings · (rings − 1)` triangles.
#[pyfunction]
pub(crate) fn sphere(py: Python<'_>, rings: usize) -> PyResult<PySolid> {
    if !(2..=MAX_SPHERE_RINGS).contains(&rings) {
        return Err(PyValueError::new_err(format!(
            "rings {rings}: between 2 and {MAX_SPHERE_RINGS}"
        )));
    }
    let inner = py.detach(|| Inner::from_soup(builders::sphere_soup(rings)))?;
    Ok(PySolid {
        inner: Arc::new(inner),
    })
}

/// The most rings `sphere` makes: about 16.8 million triangles.
const MAX_SPHERE_RINGS: usize = 2048;
