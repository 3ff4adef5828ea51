//! Solids made from profiles and curves as scene leaves: `sweep`, `revolve`
//! and `loft`. Each is built by the mesh layer's builder, checked by the
//! validator (a leaf the validator refuses is refused here, with its
//! verdict), and made a [`Polyhedron`] leaf, so it takes part in CSG,
//! renders and volumes like a mesh read from a file.
//!
//! ```text
//! {"sweep":   {"profile": [[x,y], ...], "holes": [[[x,y], ...], ...], "path": CURVE, "tolerance": t}}
//! {"revolve": {"profile": [[x,y], ...] | CURVE, "origin": [x,y,z], "axis": [x,y,z],
//!              "radial": [x,y,z], "angle_deg": a, "segments": n | "tolerance": t}}
//! {"loft":    {"sections": [[[x,y,z], ...], ...]}}
//! CURVE := {"degree": p, "points": [[x,y,z], ...], "knots": [...], "weights": [...]}
//! ```
//!
//! Defaults: `tolerance` [`DEFAULT_TOLERANCE`] (a fraction of the curve's
//! or solid's size), `origin` the origin, `axis` `+z`, `radial` `+x`,
//! `angle_deg` 360 (a full turn); a curve without `knots` is open uniform
//! (it starts and ends at its end control points); with `weights` it is a
//! NURBS curve.

use std::sync::Arc;

use glam::{DVec2, DVec3};
use serde_json::{Map, Value};

use super::SceneError;
use super::json::{bad, fields, number, positive, req, vec3, vec3_or};
use crate::csg::{Polyhedron, Primitive};
use crate::curve::{BSpline, CurveError, KnotVector, Nurbs};
use crate::io::JsonError;
use crate::mesh::Solid;
use crate::shape::{
    RevolveAxis, Segments, SweepError, try_loft, try_revolve, try_revolve_curve,
    try_sweep_with_holes,
};

/// The chord tolerance when a leaf gives none: a fraction of the size of
/// the curve (sweeps, curve profiles) or of the solid (turns).
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// A curve of a scene file: polynomial or rational.
enum SceneCurve {
    Polynomial(BSpline),
    Rational(Nurbs),
}

/// A `sweep` leaf: a 2-D profile swept along a curve.
pub(super) fn sweep(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(
        body,
        here,
        &["profile", "holes", "path", "tolerance"],
        "profile, holes, path, tolerance",
    )?;
    let profile = points_2d(req(o, here, "profile")?, &format!("{here}.profile"))?;
    let holes = match o.get("holes") {
        None => Vec::new(),
        Some(Value::Array(items)) => items
            .iter()
            .enumerate()
            .map(|(k, h)| points_2d(h, &format!("{here}.holes[{k}]")))
            .collect::<Result<Vec<_>, _>>()?,
        Some(v) => return Err(bad(&format!("{here}.holes"), "an array of polygons", v)),
    };
    let path = curve(req(o, here, "path")?, &format!("{here}.path"))?;
    let tolerance = tolerance_of(o, here)?;
    let solid = match &path {
        SceneCurve::Polynomial(c) => try_sweep_with_holes(&profile, &holes, c, tolerance),
        SceneCurve::Rational(c) => try_sweep_with_holes(&profile, &holes, c, tolerance),
    };
    leaf(solid, here)
}

/// A `revolve` leaf: a 2-D profile (points or a curve in its `z = 0`
/// plane) turned about an axis.
pub(super) fn revolve(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(
        body,
        here,
        &[
            "profile",
            "origin",
            "axis",
            "radial",
            "angle_deg",
            "segments",
            "tolerance",
        ],
        "profile, origin, axis, radial, angle_deg, segments, tolerance",
    )?;
    let axis = RevolveAxis {
        origin: vec3_or(o, here, "origin", DVec3::ZERO)?,
        direction: vec3_or(o, here, "axis", DVec3::Z)?,
        radial: vec3_or(o, here, "radial", DVec3::X)?,
    };
    let angle = match o.get("angle_deg") {
        Some(v) => {
            let at = format!("{here}.angle_deg");
            let degrees = positive(v, &at)?;
            if degrees > 360.0 {
                return Err(bad(&at, "an angle in (0, 360] degrees", v));
            }
            if degrees == 360.0 {
                std::f64::consts::TAU
            } else {
                degrees.to_radians()
            }
        }
        None => std::f64::consts::TAU,
    };
    let profile_at = format!("{here}.profile");
    let profile = req(o, here, "profile")?;
    let solid = if profile.is_object() {
        if o.contains_key("segments") {
            return Err(SceneError::Json(JsonError::Value {
                at: format!("{here}.segments"),
                message: "a curve profile is divided by \"tolerance\", not \"segments\"".into(),
            }));
        }
        let tolerance = tolerance_of(o, here)?;
        match curve(profile, &profile_at)? {
            SceneCurve::Polynomial(c) => try_revolve_curve(&c, &axis, angle, tolerance),
            SceneCurve::Rational(c) => try_revolve_curve(&c, &axis, angle, tolerance),
        }
    } else {
        let points = points_2d(profile, &profile_at)?;
        let segments = match (o.get("segments"), o.get("tolerance")) {
            (Some(_), Some(_)) => {
                return Err(SceneError::Json(JsonError::Value {
                    at: here.to_string(),
                    message: "give \"segments\" or \"tolerance\", not both".into(),
                }));
            }
            (Some(v), None) => Segments::Count(count(v, &format!("{here}.segments"))?),
            _ => Segments::Tolerance(tolerance_of(o, here)?),
        };
        try_revolve(&points, &axis, angle, segments)
    };
    leaf(solid, here)
}

/// A `loft` leaf: a solid through planar sections with equal vertex counts.
pub(super) fn loft(body: &Value, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let o = fields(body, here, &["sections"], "sections")?;
    let at = format!("{here}.sections");
    let value = req(o, here, "sections")?;
    let Value::Array(items) = value else {
        return Err(bad(&at, "an array of sections", value));
    };
    let sections = items
        .iter()
        .enumerate()
        .map(|(i, s)| points_3d(s, &format!("{at}[{i}]")))
        .collect::<Result<Vec<_>, _>>()?;
    leaf(try_loft(&sections), here)
}

/// The leaf of a built solid: validated, then a [`Polyhedron`]. A builder's
/// refusal is placed at `here` with its message.
fn leaf(solid: Result<Solid, SweepError>, here: &str) -> Result<Arc<dyn Primitive>, SceneError> {
    let refused = |message: String| {
        SceneError::Json(JsonError::Value {
            at: here.to_string(),
            message,
        })
    };
    let solid = solid.map_err(|e| refused(e.to_string()))?;
    // The validator on the exact triangulation of the faces (rings
    // included), as every built solid is checked.
    crate::boolean::prove(&solid)
        .map_err(|e| refused(format!("the built solid is not valid: {e}")))?;
    let polyhedron = Polyhedron::try_new(solid).map_err(|e| refused(e.to_string()))?;
    Ok(Arc::new(polyhedron))
}

/// `tolerance` of `o`, or [`DEFAULT_TOLERANCE`].
fn tolerance_of(o: &Map<String, Value>, here: &str) -> Result<f64, SceneError> {
    o.get("tolerance").map_or(Ok(DEFAULT_TOLERANCE), |v| {
        positive(v, &format!("{here}.tolerance"))
    })
}

/// A whole number of at least 1.
fn count(value: &Value, at: &str) -> Result<usize, SceneError> {
    value
        .as_u64()
        .filter(|&n| n >= 1)
        .and_then(|n| usize::try_from(n).ok())
        .ok_or_else(|| bad(at, "a whole number of at least 1", value))
}

/// A `CURVE` object.
fn curve(value: &Value, at: &str) -> Result<SceneCurve, SceneError> {
    let o = fields(
        value,
        at,
        &["degree", "points", "knots", "weights"],
        "degree, points, knots, weights",
    )?;
    let degree_at = format!("{at}.degree");
    let degree = req(o, at, "degree")?;
    let degree = degree
        .as_u64()
        .filter(|&d| d >= 1)
        .and_then(|d| usize::try_from(d).ok())
        .ok_or_else(|| bad(&degree_at, "a whole number of at least 1", degree))?;
    let points = points_3d(req(o, at, "points")?, &format!("{at}.points"))?;
    let knots_at = format!("{at}.knots");
    let knots = match o.get("knots") {
        Some(v) => KnotVector::try_new(numbers(v, &knots_at)?, degree),
        None => KnotVector::try_open_uniform(points.len(), degree),
    }
    .map_err(|e| {
        SceneError::Json(JsonError::Value {
            at: knots_at.clone(),
            message: e.to_string(),
        })
    })?;
    let refused = |at: String, e: crate::curve::CurveError| {
        SceneError::Json(JsonError::Value {
            at,
            message: e.to_string(),
        })
    };
    match o.get("weights") {
        Some(v) => {
            let weights_at = format!("{at}.weights");
            let weights = numbers(v, &weights_at)?;
            Nurbs::try_new(points, weights, knots)
                .map(SceneCurve::Rational)
                .map_err(|e| match e {
                    // The path of the weight at fault.
                    CurveError::BadWeight { index, .. }
                    | CurveError::WeightOutOfRange { index, .. } => {
                        refused(format!("{weights_at}[{index}]"), e)
                    }
                    _ => refused(weights_at, e),
                })
        }
        None => BSpline::try_new(points, knots)
            .map(SceneCurve::Polynomial)
            .map_err(|e| refused(format!("{at}.points"), e)),
    }
}

/// An array of finite numbers.
fn numbers(value: &Value, at: &str) -> Result<Vec<f64>, SceneError> {
    let Value::Array(items) = value else {
        return Err(bad(at, "an array of numbers", value));
    };
    items
        .iter()
        .enumerate()
        .map(|(i, x)| number(x, &format!("{at}[{i}]")))
        .collect()
}

/// An array of `[x, y]` points.
fn points_2d(value: &Value, at: &str) -> Result<Vec<DVec2>, SceneError> {
    let Value::Array(items) = value else {
        return Err(bad(at, "an array of [x, y] points", value));
    };
    items
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let here = format!("{at}[{i}]");
            match p.as_array() {
                Some(xy) if xy.len() == 2 => Ok(DVec2::new(
                    number(&xy[0], &format!("{here}[0]"))?,
                    number(&xy[1], &format!("{here}[1]"))?,
                )),
                _ => Err(bad(&here, "an array of two numbers", p)),
            }
        })
        .collect()
}

/// An array of `[x, y, z]` points.
fn points_3d(value: &Value, at: &str) -> Result<Vec<DVec3>, SceneError> {
    let Value::Array(items) = value else {
        return Err(bad(at, "an array of [x, y, z] points", value));
    };
    items
        .iter()
        .enumerate()
        .map(|(i, p)| vec3(p, &format!("{at}[{i}]")))
        .collect()
}
