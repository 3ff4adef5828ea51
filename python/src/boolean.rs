//! Booleans from Python: `boolean(a, b, operation)` behind `Solid.union`,
//! `intersection`, `difference` and the operators `|`, `&`, `-`;
//! `combine(solids, expression)` for a whole set expression in one exact
//! pass; and the conversion of a result into what a Python `Solid` owns,
//! which `Scene.evaluate` shares.
//!
//! Each operand is proven a valid closed solid once, on its first use, and
//! the verdict is kept with it (a result counts as proven: it was before it
//! was returned), so a solid used in many booleans, or a chain `a | b | c`,
//! is validated once rather than in every call.
//!
//! A result face with rings (a face with a hole, such as the top of a
//! drilled block) has no place in a polygon soup, which is what a Python
//! `Solid` keeps (for `to_arrays`, pickling and validation): it is handed
//! over as the triangles of its exact constrained triangulation, the way
//! OBJ output writes it, each triangle keeping the face's origin. Every
//! other face stays the polygon the boolean made.

use std::sync::Arc;
use wingedge::SetOp;

use pyo3::prelude::*;
use rayon::prelude::*;
use slotmap::SecondaryMap;
use wingedge::boolean::{BooleanError as CoreError, BooleanOptions, Expression};
use wingedge::mesh::{FaceId, Polygon, PolygonSoup, Solid, VertexId};

use crate::errors::{self, BooleanError};
use crate::expression;
use crate::solid::{Inner, PySolid};

/// `a op b` for `operation` one of `"union"`, `"intersection"`,
/// `"difference"`, exact; the interpreter lock is released while it runs.
#[pyfunction]
#[pyo3(signature = (a, b, operation, resolve=false))]
pub(crate) fn boolean(
    py: Python<'_>,
    a: PyRef<'_, PySolid>,
    b: PyRef<'_, PySolid>,
    operation: &str,
    resolve: bool,
) -> PyResult<PySolid> {
    let operation = match operation {
        "union" => SetOp::Union,
        "intersection" => SetOp::Intersection,
        "difference" => SetOp::Difference,
        other => {
            return Err(BooleanError::new_err(format!(
                "operation {other:?}: expected \"union\", \"intersection\" or \"difference\""
            )));
        }
    };
    let expression = Expression::of(operation, Expression::Operand(0), Expression::Operand(1));
    run(
        py,
        vec![a.inner.clone(), b.inner.clone()],
        &expression,
        resolve,
    )
}

/// The set `expression` (nested tuples over indices into `solids`, see
/// `expression.rs`) in one exact pass.
#[pyfunction]
#[pyo3(signature = (solids, expression, resolve=false))]
pub(crate) fn combine(
    py: Python<'_>,
    solids: Vec<PyRef<'_, PySolid>>,
    expression: &Bound<'_, PyAny>,
    resolve: bool,
) -> PyResult<PySolid> {
    let expression = expression::parse(expression, solids.len()).map_err(BooleanError::new_err)?;
    let operands = solids.iter().map(|s| s.inner.clone()).collect();
    run(py, operands, &expression, resolve)
}

/// Runs `combine` on the operands' solids without the interpreter lock and
/// hands the result over with its face origins. With `resolve`, an operand
/// that is not a valid solid is taken by its winding number
/// (`BooleanOptions::resolve_operands`), and `combine` checks the operands
/// itself.
fn run(
    py: Python<'_>,
    operands: Vec<Arc<Inner>>,
    expression: &Expression,
    resolve: bool,
) -> PyResult<PySolid> {
    let inner = py.detach(|| {
        if !resolve {
            prove_operands(&operands, expression).map_err(errors::boolean)?;
        }
        let solids: Vec<&Solid> = operands.iter().map(|o| &o.solid).collect();
        // Every operand named was proven above, unless resolving.
        let options = BooleanOptions {
            check_operands: resolve,
            resolve_operands: resolve,
            ..BooleanOptions::default()
        };
        let result =
            wingedge::boolean::combine(&solids, expression, options).map_err(errors::boolean)?;
        // Each face's origin: the operand, and the operand face's index in
        // that operand's face order (what its ray casts report). Every face
        // of a result has one; `[-1, -1]` would mark a face without.
        let origin = |face: FaceId| -> [i64; 2] {
            result
                .solid
                .face(face)
                .attributes
                .source_index
                .and_then(|i| result.origins.get(i))
                .and_then(|o| {
                    let operand = operands.get(o.operand)?;
                    Some([o.operand as i64, operand.face_index_of(o.face)])
                })
                .unwrap_or([-1, -1])
        };
        result_inner(&result.solid, Some(&origin))
    })?;
    Ok(PySolid {
        inner: Arc::new(inner),
    })
}

/// Proves every operand the expression names a valid closed solid (the
/// check `combine` makes with `check_operands`), each at most once in its
/// life, in parallel.
///
/// # Errors
///
/// `InvalidOperand` for the first operand, by index, that is not one, with
/// the validator's located defects.
fn prove_operands(operands: &[Arc<Inner>], expression: &Expression) -> Result<(), CoreError> {
    let named: Vec<usize> = expression
        .operands()
        .into_iter()
        .filter(|&k| k < operands.len())
        .collect();
    let verdicts: Vec<Result<(), CoreError>> = named
        .par_iter()
        .map(|&k| {
            let inner = &operands[k];
            let verdict = inner
                .proof
                .get_or_init(|| wingedge::boolean::prove(&inner.solid).map(|_| ()));
            match verdict {
                Ok(()) => Ok(()),
                Err(CoreError::InvalidResult {
                    validity, report, ..
                }) => Err(CoreError::InvalidOperand {
                    operand: k,
                    validity: validity.clone(),
                    report: report.clone(),
                }),
                Err(other) => Err(other.clone()),
            }
        })
        .collect();
    verdicts.into_iter().collect()
}

/// What a Python `Solid` owns for a solid a boolean (or a tree's
/// evaluation) made: its soup, faces with rings as their exact
/// triangulations, the solid rebuilt from that soup so that face indices
/// are soup positions, and each face's origin when `origin` is given.
///
/// # Errors
///
/// `BooleanError` when a face with rings cannot be triangulated or the
/// soup does not rebuild: neither happens to a result the validator
/// proved, so the message says it is a wingedge defect.
pub(crate) fn result_inner(
    solid: &Solid,
    origin: Option<&dyn Fn(FaceId) -> [i64; 2]>,
) -> PyResult<Inner> {
    if solid.face_count() == 0 {
        let mut inner = Inner::empty();
        inner.origins = origin.map(|_| Vec::new());
        return Ok(inner);
    }
    let defect = |what: String| {
        BooleanError::new_err(format!(
            "the result cannot be handed over (a wingedge defect, please report it): {what}"
        ))
    };
    let mut index: SecondaryMap<VertexId, usize> =
        SecondaryMap::with_capacity(solid.vertex_count());
    let positions = solid
        .vertices()
        .enumerate()
        .map(|(i, (v, vertex))| {
            index.insert(v, i);
            vertex.position
        })
        .collect();
    let mut polygons = Vec::with_capacity(solid.face_count());
    let mut origins = Vec::new();
    for (f, face) in solid.faces() {
        let before = polygons.len();
        if face.rings.is_empty() {
            polygons.push(Polygon::new(solid.face_outer_vertices(f).map(|v| index[v])));
        } else {
            let triangles = solid
                .try_triangulate_face(f)
                .map_err(|e| defect(format!("a face with rings: {e}")))?;
            polygons.extend(
                triangles
                    .iter()
                    .map(|t| Polygon::new(t.iter().map(|&v| index[v]))),
            );
        }
        if let Some(origin) = origin {
            let o = origin(f);
            origins.extend(std::iter::repeat_n(o, polygons.len() - before));
        }
    }
    let soup = PolygonSoup {
        positions,
        polygons,
    };
    let rebuilt = Solid::try_from_soup(&soup).map_err(|e| defect(e.to_string()))?;
    let mut inner = Inner::new(rebuilt, soup, None, None);
    inner.origins = origin.map(|_| origins);
    // Proven valid by the boolean: the same vertices, and the same faces
    // but for those with rings, now the exact triangulations the proof
    // itself checked.
    let _ = inner.proof.set(Ok(()));
    Ok(inner)
}
