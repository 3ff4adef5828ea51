//! The fan triangles as every query reads them: exact corners by
//! coordinate, with the sign of their `yz` projection.

use glam::{DVec2, DVec3};

use crate::geom::orient2d;

/// One fan triangle as the queries need it: its exact corners split by
/// coordinate and the sign of its `yz` projection (80 bytes). Stored in BVH
/// leaf order; the grid and the BVH both index this one array.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub(crate) struct YzTri {
    /// `x` of the three corners.
    pub x: [f64; 3],
    /// `y` of the three corners.
    pub y: [f64; 3],
    /// `z` of the three corners.
    pub z: [f64; 3],
    /// `orient2d` of the projected corners: the sign of the normal's `x`.
    pub sigma: i8,
}

impl YzTri {
    /// The corners as points.
    #[inline]
    pub fn corners(&self) -> [DVec3; 3] {
        [0, 1, 2].map(|k| DVec3::new(self.x[k], self.y[k], self.z[k]))
    }

    /// The largest `x` of the corners.
    pub(in crate::query) fn max_x(&self) -> f64 {
        self.x[0].max(self.x[1]).max(self.x[2])
    }

    /// The smallest `x` of the corners.
    pub(in crate::query) fn min_x(&self) -> f64 {
        self.x[0].min(self.x[1]).min(self.x[2])
    }
}

/// The record of the triangle with corners `t`.
pub(in crate::query) fn yz_tri(t: &[DVec3; 3]) -> YzTri {
    let p = |v: DVec3| DVec2::new(v.y, v.z);
    YzTri {
        x: [t[0].x, t[1].x, t[2].x],
        y: [t[0].y, t[1].y, t[2].y],
        z: [t[0].z, t[1].z, t[2].z],
        sigma: orient2d(p(t[0]), p(t[1]), p(t[2])).as_i32() as i8,
    }
}
