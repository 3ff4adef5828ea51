//! A pinhole camera.

use glam::DVec3;

use crate::geom::{Aabb, Ray};
use crate::scene::CameraSpec;

/// A pinhole camera: an eye, an orthonormal frame and a field of view.
///
/// # Invariants
///
/// `right`, `up` and `forward` are unit length and mutually orthogonal
/// (up to rounding); `tan_half_fov > 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// The eye point.
    pub eye: DVec3,
    /// Unit vector along the view.
    pub forward: DVec3,
    /// Unit vector to the image's right.
    pub right: DVec3,
    /// Unit vector to the image's top.
    pub up: DVec3,
    /// `tan(fov / 2)` of the vertical field of view.
    pub tan_half_fov: f64,
    /// Distance from the eye to the point looked at (the scene's scale).
    pub distance: f64,
}

impl Camera {
    /// The camera a scene file describes (its values were checked on load:
    /// eye ≠ look_at, up not parallel to the view).
    #[must_use]
    pub fn from_spec(spec: &CameraSpec) -> Camera {
        let view = spec.look_at - spec.eye;
        let forward = view.normalize_or(DVec3::Y);
        let right = forward.cross(spec.up).normalize_or(DVec3::X);
        let up = right.cross(forward);
        Camera {
            eye: spec.eye,
            forward,
            right,
            up,
            tan_half_fov: (spec.fov_deg.to_radians() * 0.5).tan(),
            distance: view.length(),
        }
    }

    /// A camera that sees all of `bounds` from the front-right, above, with
    /// +z up; for unbounded or empty bounds it looks at the unit box.
    #[must_use]
    pub fn framing(bounds: Aabb) -> Camera {
        let bounds = if bounds.is_empty() || !bounds.min.is_finite() || !bounds.max.is_finite() {
            Aabb {
                min: DVec3::splat(-1.0),
                max: DVec3::ONE,
            }
        } else {
            bounds
        };
        let centre = bounds.center();
        let radius = 0.5 * bounds.diagonal().max(f64::MIN_POSITIVE);
        let fov_deg: f64 = 35.0;
        let distance = radius / (fov_deg.to_radians() * 0.5).sin() * 1.05;
        let direction = DVec3::new(1.0, -1.6, 1.1).normalize();
        Camera::from_spec(&CameraSpec {
            eye: centre + direction * distance,
            look_at: centre,
            up: DVec3::Z,
            fov_deg,
        })
    }

    /// The ray through pixel `(x, y)` (`y` down from the top row) of a
    /// `width × height` image, through the pixel's centre; unit direction.
    #[must_use]
    pub fn pixel_ray(&self, x: u32, y: u32, width: u32, height: u32) -> Ray {
        let aspect = f64::from(width) / f64::from(height.max(1));
        let u = ((f64::from(x) + 0.5) / f64::from(width.max(1)) * 2.0 - 1.0) * aspect;
        let v = 1.0 - (f64::from(y) + 0.5) / f64::from(height.max(1)) * 2.0;
        let direction =
            self.forward + self.right * (u * self.tan_half_fov) + self.up * (v * self.tan_half_fov);
        Ray::new(self.eye, direction.normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_centre_pixel_looks_at_the_target() {
        let c = Camera::from_spec(&CameraSpec {
            eye: DVec3::new(0., -10., 0.),
            look_at: DVec3::ZERO,
            up: DVec3::Z,
            fov_deg: 40.0,
        });
        let r = c.pixel_ray(50, 50, 101, 101);
        assert!((r.direction - DVec3::Y).length() < 1e-12);
        assert!(c.pixel_ray(0, 0, 101, 101).direction.z > 0.0);
        assert!(c.pixel_ray(0, 0, 101, 101).direction.x < 0.0);
    }
}
