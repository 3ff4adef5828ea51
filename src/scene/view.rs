//! How a scene is seen: the camera and the light of its image, read from
//! the scene file's `camera` and `light` objects.

use glam::DVec3;
use serde_json::Value;

use super::SceneError;
use super::json::{bad, fields, positive, req, vec3, vec3_or};
use crate::io::JsonError;

/// Where the camera is and what it looks at.
///
/// # Invariants
///
/// When read from a scene file: `eye != look_at`, `up` is not zero nor
/// parallel to `look_at - eye`, and `0 < fov_deg < 180`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSpec {
    /// The eye point.
    pub eye: DVec3,
    /// The point at the centre of the image.
    pub look_at: DVec3,
    /// Which way is up in the image (default +z).
    pub up: DVec3,
    /// The vertical field of view in degrees (default 40).
    pub fov_deg: f64,
}

/// The light of a Lambert-shaded image.
///
/// # Invariants
///
/// When read from a scene file: `ambient` is in `[0, 1]` and a direction
/// is not zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSpec {
    /// A light at infinity in `direction` (from the scene towards the
    /// light).
    Directional {
        /// Towards the light.
        direction: DVec3,
        /// Ambient fraction in `[0, 1]`.
        ambient: f64,
    },
    /// A point light.
    Point {
        /// Where it is.
        position: DVec3,
        /// Ambient fraction in `[0, 1]`.
        ambient: f64,
    },
}

/// The default ambient fraction of a light.
pub const DEFAULT_AMBIENT: f64 = 0.15;

/// The default vertical field of view, degrees.
const DEFAULT_FOV_DEG: f64 = 40.0;

/// Reads a `camera` object at `at`.
pub(super) fn camera(value: &Value, at: &str) -> Result<CameraSpec, SceneError> {
    let o = fields(
        value,
        at,
        &["eye", "look_at", "up", "fov_deg"],
        "eye, look_at, up, fov_deg",
    )?;
    let eye = vec3(req(o, at, "eye")?, &format!("{at}.eye"))?;
    let look_at = vec3(req(o, at, "look_at")?, &format!("{at}.look_at"))?;
    if eye == look_at {
        return Err(SceneError::Json(JsonError::Value {
            at: format!("{at}.look_at"),
            message: "the camera looks at its own eye point".into(),
        }));
    }
    let up = vec3_or(o, at, "up", DVec3::Z)?;
    let fov_at = format!("{at}.fov_deg");
    let fov_deg = o
        .get("fov_deg")
        .map(|v| positive(v, &fov_at))
        .transpose()?
        .unwrap_or(DEFAULT_FOV_DEG);
    if fov_deg >= 180.0 {
        return Err(SceneError::Json(JsonError::Value {
            at: fov_at,
            message: format!(
                "field of view {} must be below 180 degrees",
                crate::geom::Readable(fov_deg)
            ),
        }));
    }
    let forward = look_at - eye;
    if up == DVec3::ZERO || forward.cross(up) == DVec3::ZERO {
        return Err(SceneError::Json(JsonError::Value {
            at: format!("{at}.up"),
            message: "up must not be zero or parallel to the view direction".into(),
        }));
    }
    Ok(CameraSpec {
        eye,
        look_at,
        up,
        fov_deg,
    })
}

/// Reads a `light` object at `at`.
pub(super) fn light(value: &Value, at: &str) -> Result<LightSpec, SceneError> {
    let o = fields(
        value,
        at,
        &["direction", "position", "ambient"],
        "direction or position, ambient",
    )?;
    let a_at = format!("{at}.ambient");
    let ambient = match o.get("ambient") {
        None => DEFAULT_AMBIENT,
        Some(v) => match v.as_f64() {
            Some(a) if (0.0..=1.0).contains(&a) => a,
            _ => return Err(bad(&a_at, "a number from 0 to 1", v)),
        },
    };
    match (o.get("direction"), o.get("position")) {
        (Some(d), None) => {
            let d_at = format!("{at}.direction");
            let direction = vec3(d, &d_at)?;
            if direction == DVec3::ZERO {
                return Err(SceneError::Json(JsonError::Value {
                    at: d_at,
                    message: "the light direction must not be zero".into(),
                }));
            }
            Ok(LightSpec::Directional { direction, ambient })
        }
        (None, Some(p)) => Ok(LightSpec::Point {
            position: vec3(p, &format!("{at}.position"))?,
            ambient,
        }),
        _ => Err(SceneError::Json(JsonError::Value {
            at: at.to_string(),
            message: "give exactly one of \"direction\" and \"position\"".into(),
        })),
    }
}
