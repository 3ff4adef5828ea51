//! numpy arrays in and out.
//!
//! The Python wrapper hands over C-contiguous `float64` arrays of shape
//! `(n, 3)` (it converts other float and integer dtypes, exactly); this file
//! checks the shape once more, so that no caller of the native module can
//! make it panic, and copies the rows into `DVec3`s.

use numpy::{
    IntoPyArray, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::mesh::PolygonSoup;

/// The rows of an `(n, 3)` array as points, copied (any memory layout).
///
/// # Errors
///
/// `ValueError` naming `what` when the array is not of shape `(n, 3)`.
pub(crate) fn points(array: &PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<Vec<DVec3>> {
    let shape = array.shape();
    if shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (n, 3), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    // The common case, a C-contiguous array, is read as one flat slice.
    if let Ok(flat) = array.as_slice() {
        return Ok(flat
            .chunks_exact(3)
            .map(|r| DVec3::new(r[0], r[1], r[2]))
            .collect());
    }
    let view = array.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| DVec3::new(r[0], r[1], r[2]))
        .collect())
}

/// Rays from an `(n, 3)` array of origins and one of directions, built in
/// one pass (no intermediate point arrays: at a million rays the copies
/// and their fresh pages cost as much as the queries' bookkeeping).
///
/// # Errors
///
/// `ValueError` when either array is not of shape `(n, 3)` or their
/// lengths differ.
pub(crate) fn rays(
    origins: &PyReadonlyArray2<'_, f64>,
    directions: &PyReadonlyArray2<'_, f64>,
) -> PyResult<Vec<Ray>> {
    for (array, what) in [(origins, "origins"), (directions, "directions")] {
        let shape = array.shape();
        if shape[1] != 3 {
            return Err(PyValueError::new_err(format!(
                "{what} must have shape (n, 3), got ({}, {})",
                shape[0], shape[1]
            )));
        }
    }
    let (n, m) = (origins.shape()[0], directions.shape()[0]);
    if n != m {
        return Err(PyValueError::new_err(format!(
            "{n} origins but {m} directions"
        )));
    }
    if let (Ok(o), Ok(d)) = (origins.as_slice(), directions.as_slice()) {
        return Ok(o
            .chunks_exact(3)
            .zip(d.chunks_exact(3))
            .map(|(o, d)| Ray::new(DVec3::new(o[0], o[1], o[2]), DVec3::new(d[0], d[1], d[2])))
            .collect());
    }
    let (o, d) = (origins.as_array(), directions.as_array());
    Ok(o.rows()
        .into_iter()
        .zip(d.rows())
        .map(|(o, d)| Ray::new(DVec3::new(o[0], o[1], o[2]), DVec3::new(d[0], d[1], d[2])))
        .collect())
}

/// Points as an `(n, 3)` float64 array.
///
/// # Errors
///
/// Never in practice (the shape always matches the data).
pub(crate) fn points_out<'py>(
    py: Python<'py>,
    points: &[DVec3],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    flat.into_pyarray(py).reshape([points.len(), 3])
}

/// A flat index array as `usize`s, refusing negative entries.
///
/// # Errors
///
/// `ValueError` naming `what` and the first negative entry.
pub(crate) fn indices(array: &PyReadonlyArray1<'_, i64>, what: &str) -> PyResult<Vec<usize>> {
    array
        .as_array()
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            usize::try_from(v).map_err(|_| {
                PyValueError::new_err(format!("{what}[{i}] is {v}: an index is never negative"))
            })
        })
        .collect()
}

/// A polygon soup from vertices `(n, 3)`, face sizes `(m,)` and the flat
/// index array of all faces in order.
///
/// # Errors
///
/// `ValueError` for a wrong shape, a negative index or size, or sizes that
/// do not add up to the number of indices.
pub(crate) fn soup(
    vertices: &PyReadonlyArray2<'_, f64>,
    sizes: &PyReadonlyArray1<'_, i64>,
    indices: &PyReadonlyArray1<'_, i64>,
) -> PyResult<PolygonSoup> {
    let positions = points(vertices, "vertices")?;
    let sizes = self::indices(sizes, "face sizes")?;
    let indices = self::indices(indices, "faces")?;
    let total: usize = sizes.iter().sum();
    if total != indices.len() {
        return Err(PyValueError::new_err(format!(
            "face sizes add up to {total} but {} indices were given",
            indices.len()
        )));
    }
    let mut polygons = Vec::with_capacity(sizes.len());
    let mut at = 0;
    for &n in &sizes {
        polygons.push(&indices[at..at + n]);
        at += n;
    }
    Ok(PolygonSoup::new(positions, polygons))
}

/// Face origins from an `(m, 2)` int64 array, one row per face
/// (`[operand, face]`), as a boolean's result carries them.
///
/// # Errors
///
/// `ValueError` when the array is not of shape `(faces, 2)`.
pub(crate) fn origins(array: &PyReadonlyArray2<'_, i64>, faces: usize) -> PyResult<Vec<[i64; 2]>> {
    let shape = array.shape();
    if shape != [faces, 2] {
        return Err(PyValueError::new_err(format!(
            "origins must have shape ({faces}, 2), one row per face, got ({}, {})",
            shape[0], shape[1]
        )));
    }
    Ok(array
        .as_array()
        .rows()
        .into_iter()
        .map(|r| [r[0], r[1]])
        .collect())
}
