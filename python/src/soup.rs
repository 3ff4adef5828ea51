//! `wingedge.SoupWinding`: the winding number of a polygon soup that need
//! not be a solid (an edge of three faces, faces wound against their
//! neighbours), from its fanned polygons (`query::SoupWinding`).

use std::path::PathBuf;
use std::sync::Arc;

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use wingedge::io::{ObjOptions, import_obj};
use wingedge::mesh::PolygonSoup;
use wingedge::query::SoupWinding;

use crate::arrays;
use crate::errors;
use crate::solid::{code, weld_mode};

/// A polygon soup's triangles and their accel, answering the winding
/// number.
#[pyclass(name = "NativeSoupWinding", module = "wingedge._wingedge", frozen)]
pub struct PySoupWinding {
    inner: Arc<SoupWinding>,
}

fn built(soup: &PolygonSoup) -> PyResult<PySoupWinding> {
    let inner = SoupWinding::try_new(soup).map_err(errors::build)?;
    Ok(PySoupWinding {
        inner: Arc::new(inner),
    })
}

#[pymethods]
impl PySoupWinding {
    /// From vertices `(n, 3)`, face sizes `(m,)` and the flat face index
    /// array; raises `ValidationError` for no face, a face of fewer than
    /// three corners, an index out of range or a non-finite position.
    #[staticmethod]
    fn _from_flat(
        py: Python<'_>,
        vertices: PyReadonlyArray2<'_, f64>,
        sizes: PyReadonlyArray1<'_, i64>,
        indices: PyReadonlyArray1<'_, i64>,
    ) -> PyResult<PySoupWinding> {
        let soup = arrays::soup(&vertices, &sizes, &indices)?;
        py.detach(|| built(&soup))
    }

    /// Reads an OBJ file (welded as `load_obj` welds) into a soup.
    #[staticmethod]
    #[pyo3(signature = (path, weld=None))]
    fn load_obj(
        py: Python<'_>,
        path: PathBuf,
        weld: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<PySoupWinding> {
        let options = ObjOptions {
            weld: weld_mode(weld)?,
            ..ObjOptions::default()
        };
        py.detach(|| {
            let import = import_obj(&path, &options)
                .map_err(|e| errors::ObjError::new_err(e.to_string()))?;
            built(&import.soup)
                .map_err(|e| errors::ValidationError::new_err(format!("{}: {e}", path.display())))
        })
    }

    /// Number of polygons.
    #[getter]
    fn polygon_count(&self) -> usize {
        self.inner.polygon_count()
    }

    /// Edges run more often one way than the other (0: a closed cycle,
    /// answered by the exact crossing count).
    #[getter]
    fn open_edges(&self) -> usize {
        self.inner.open_edges()
    }

    /// `1` inside, `0` on a triangle, `-1` outside, per point `(n, 3)`.
    fn _classify<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let points = arrays::points(&points, "points")?;
        let inner = &self.inner;
        let codes = py.detach(|| {
            inner
                .classify_batch(&points)
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
        let w = py.detach(|| inner.winding_number_batch(&points));
        Ok(w.map_err(errors::query)?.into_pyarray(py))
    }

    fn __repr__(&self) -> String {
        format!(
            "<wingedge.SoupWinding: {} polygons, {} open edges>",
            self.inner.polygon_count(),
            self.inner.open_edges()
        )
    }
}
