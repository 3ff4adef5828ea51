//! Leaves made into polyhedra for boundary evaluation: boxes and
//! polyhedra exactly as they are, spheres and cylinders inscribed to a
//! chord tolerance, half-spaces as a slab clipped to the tree's bounds,
//! transformed leaves by mapping the child's vertices.

use glam::{DAffine3, DVec3};
use thiserror::Error;

use crate::geom::Aabb;
use crate::mesh::{PolygonSoup, Solid, builders};

/// Why a leaf could not be made a polyhedron.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TessellateError {
    /// The kind of leaf has no boundary representation (fields).
    #[error(
        "a {kind} leaf has no polyhedral boundary; boundary evaluation needs polyhedral leaves"
    )]
    Unsupported {
        /// The kind of primitive.
        kind: &'static str,
    },
    /// The tolerance is not a positive fraction below 1.
    #[error("the chord tolerance must be in (0, 1), got {}", crate::geom::Readable(*.0))]
    Tolerance(f64),
    /// The tessellation would need more facets than [`MAX_SEGMENTS`]
    /// around.
    #[error(
        "a chord tolerance of {} needs {segments} segments around, more than {MAX_SEGMENTS}",
        crate::geom::Readable(*.tolerance)
    )]
    TooFine {
        /// The tolerance asked for.
        tolerance: f64,
        /// The segments it needs.
        segments: usize,
    },
    /// The polyhedron could not be built (a degenerate shape after
    /// rounding, such as a transform that flattens it).
    #[error("the tessellated leaf is not a solid: {0}")]
    Build(String),
}

/// The most segments around a circle a tessellation may use.
pub const MAX_SEGMENTS: usize = 4096;

/// The chord tolerance used when the caller gives none: the largest
/// distance between a curved surface and its inscribed polyhedron, as a
/// fraction of the primitive's radius.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;

/// The number of segments around a circle whose inscribed polygon stays
/// within `tolerance × radius` of it: the sagitta `r (1 − cos(π / n))`.
///
/// # Errors
///
/// [`TessellateError::Tolerance`] and [`TessellateError::TooFine`].
pub fn segments_for(tolerance: f64) -> Result<usize, TessellateError> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(TessellateError::Tolerance(tolerance));
    }
    let step = (1.0 - tolerance).acos();
    let segments = ((std::f64::consts::PI / step).ceil() as usize).max(3);
    if segments > MAX_SEGMENTS {
        return Err(TessellateError::TooFine {
            tolerance,
            segments,
        });
    }
    Ok(segments)
}

/// A UV sphere inscribed in the sphere of `center` and `radius`, every
/// face within `tolerance × radius` of the sphere: a face spans `π / n` in
/// both directions, so its plane is at least `r cos²(π / n)` from the
/// centre, and `n` is chosen for a sagitta of `1 − √(1 − tolerance)`.
pub(crate) fn sphere(center: DVec3, radius: f64, tolerance: f64) -> Result<Solid, TessellateError> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(TessellateError::Tolerance(tolerance));
    }
    let rings = segments_for(1.0 - (1.0 - tolerance).sqrt())?
        .div_ceil(2)
        .max(2);
    let mut soup = builders::sphere_soup(rings);
    for p in &mut soup.positions {
        *p = center + radius * *p;
    }
    build(&soup)
}

/// A prism inscribed in the cylinder from `base` along `axis`.
pub(crate) fn cylinder(
    base: DVec3,
    axis: DVec3,
    radius: f64,
    tolerance: f64,
) -> Result<Solid, TessellateError> {
    let n = segments_for(tolerance)?;
    let (u, v) = axis.normalize().any_orthonormal_pair();
    let profile: Vec<DVec3> = (0..n)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / n as f64;
            base + radius * (angle.cos() * u + angle.sin() * v)
        })
        .collect();
    builders::prism(&profile, axis).map_err(|e| TessellateError::Build(e.to_string()))
}

/// The half-space `(p − point) · normal ≤ 0` within `clip`: a square slab
/// lying on the plane and reaching past `clip` inward. Its top corners are
/// the plane's points rounded to `f64`.
pub(crate) fn half_space(
    point: DVec3,
    normal: DVec3,
    clip: &Aabb,
) -> Result<Solid, TessellateError> {
    let n = normal.normalize();
    let reach = 2.0 * clip.diagonal().max(f64::MIN_POSITIVE) + clip.center().distance(point);
    let centre = clip.center() - (clip.center() - point).dot(n) * n;
    let (u, v) = n.any_orthonormal_pair();
    let square: Vec<DVec3> = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(a, b)| centre + reach * (a * u + b * v))
        .collect();
    // The prism sweeps its profile along the vector; its cap at the start
    // faces against it, so the slab is swept inward.
    builders::prism(&square, -2.0 * reach * n).map_err(|e| TessellateError::Build(e.to_string()))
}

/// `solid` moved by `map` (vertices rounded once), turned inside out back
/// again when the map mirrors.
pub(crate) fn mapped(mut solid: Solid, map: DAffine3) -> Result<Solid, TessellateError> {
    if solid.move_by(map) {
        return Ok(solid);
    }
    let mut soup = solid.to_soup();
    for p in &mut soup.positions {
        *p = map.transform_point3(*p);
    }
    if map.matrix3.determinant() < 0.0 {
        for polygon in &mut soup.polygons {
            polygon.vertices.reverse();
        }
    }
    build(&soup)
}

fn build(soup: &PolygonSoup) -> Result<Solid, TessellateError> {
    Solid::try_from_soup(soup).map_err(|e| TessellateError::Build(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_keep_the_sagitta_within_the_tolerance() {
        for tolerance in [0.5, 0.1, 1e-3, 1e-5] {
            let n = segments_for(tolerance).unwrap();
            let sagitta = 1.0 - (std::f64::consts::PI / n as f64).cos();
            assert!(sagitta <= tolerance * (1.0 + 1e-12), "{tolerance}: {n}");
            let coarser = 1.0 - (std::f64::consts::PI / (n - 1) as f64).cos();
            assert!(
                n == 3 || coarser > tolerance,
                "{tolerance}: {n} is not the fewest"
            );
        }
        assert!(segments_for(0.0).is_err());
        assert!(segments_for(f64::NAN).is_err());
        assert!(matches!(
            segments_for(1e-12),
            Err(TessellateError::TooFine { .. })
        ));
    }

    #[test]
    fn leaves_become_valid_solids_of_the_right_volume() {
        let s = sphere(DVec3::new(1.0, 2.0, 3.0), 2.0, 1e-3).unwrap();
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!(s.volume() < exact && s.volume() > exact * (1.0 - 3e-3));
        let c = cylinder(DVec3::ZERO, DVec3::new(0.0, 0.0, 3.0), 0.5, 1e-3).unwrap();
        let exact = std::f64::consts::PI * 0.25 * 3.0;
        assert!(
            c.volume() < exact && c.volume() > exact * (1.0 - 3e-3),
            "{}",
            c.volume()
        );
        let clip = Aabb::from_points([DVec3::splat(-1.0), DVec3::splat(1.0)]);
        let h = half_space(DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0), &clip).unwrap();
        assert!(h.volume() > 0.0);
        let mirrored = mapped(c.clone(), DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0))).unwrap();
        assert!((mirrored.volume() - c.volume()).abs() < 1e-12);
    }
}
