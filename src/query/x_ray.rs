//! The exact ray along `±x` from a point through the `yz` grid: on the
//! boundary, or the signed number of crossings.

use glam::{DVec2, DVec3};

use super::Accel;
use super::accel::cell_gaps::Between;
use super::x_direction::{RayChoice, XDirection};
use super::x_ray_triangle::{Step, triangle_step};
use crate::spatial::rounding::{f32_down, f32_up, f64_below};

/// What the `+x` ray from a point found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum XRay {
    /// The point lies exactly on a triangle.
    OnBoundary,
    /// The signed number of crossings in front of the point: `+1` for each
    /// triangle whose normal has positive `x` (the ray leaves through it),
    /// `−1` for each it enters through. For a closed outward-oriented
    /// surface this is the winding number of the surface around the point.
    Winding(i32),
}

impl Accel {
    /// The `+x` ray from `p`: on the boundary, or the signed crossing count.
    pub(super) fn x_ray(&self, p: DVec3) -> XRay {
        self.x_ray_towards(p, RayChoice::Always(XDirection::Plus))
    }

    /// The ray from `p` along the direction `choice` gives: on the boundary,
    /// or the signed number of crossings *in front of* `p` (the `+x`
    /// winding) derived from the crossings that ray meets. Along
    /// [`XDirection::Minus`] that is the negated count of the crossings
    /// behind `p`: equal to the `+x` count on a closed oriented surface, and
    /// of the same parity on every closed one (see [`XDirection`]), so only
    /// parity may use it.
    pub(super) fn x_ray_towards(&self, p: DVec3, choice: RayChoice) -> XRay {
        let Some(p) = self.probe_point(p) else {
            return XRay::Winding(0);
        };
        let (g, gaps) = self.grid_and_gaps();
        let cell = g.cell_index(p.y, p.z);
        let (listed, extent) = g.cell_at(cell);
        // Parity may start from the gaps around `p` (see `CellGaps`): only
        // the triangles between them can be crossed between `p` and either
        // gap, and the gaps' counts stand for every triangle beyond. A cell
        // without gaps gives all its triangles and counts of 0.
        let between = match choice {
            RayChoice::Fewer => gaps.around(cell, listed.len(), p.x),
            RayChoice::Always(_) => Between {
                first: 0,
                end: listed.len(),
                winding_below: 0,
                winding_above: 0,
            },
        };
        let entries = &listed[between.first..between.end];
        // The triangles that can meet the ray. Towards `−x`: those with
        // smallest `x` at most `p.x`, a prefix of the cell's list. Towards
        // `+x`: those with largest `x` at least `p.x`, whose listed `x` is at
        // least `p.x − extent` (see `YzGrid`) and so at least `reach`, a
        // suffix (which may also hold triangles wholly behind `p`; the exact
        // tests reject them); `reach` is the next `f64` below the rounded
        // `p.x − extent`, so not above the exact difference (`−∞` for an
        // infinite extent: every triangle is a candidate). Both are counted
        // rather than searched (no branches), in `f32`: for an `f32` value
        // `v`, `v ≤ p.x` exactly when `v ≤ f32_down(p.x)` (the largest `f32`
        // not above `p.x`), and `v < reach` exactly when `v < f32_up(reach)`.
        // The same holds of the part between two gaps.
        let x_down = f32_down(p.x);
        let reach = f32_up(f64_below(p.x - f64::from(extent)));
        let behind = || entries.iter().filter(|e| e.x <= x_down).count();
        let before_ahead = || entries.iter().filter(|e| e.x < reach).count();
        let (direction, candidates) = match choice {
            RayChoice::Always(XDirection::Plus) => (XDirection::Plus, &entries[before_ahead()..]),
            RayChoice::Always(XDirection::Minus) => (XDirection::Minus, &entries[..behind()]),
            RayChoice::Fewer => {
                let (behind, before_ahead) = (behind(), before_ahead());
                if behind < entries.len() - before_ahead {
                    (XDirection::Minus, &entries[..behind])
                } else {
                    (XDirection::Plus, &entries[before_ahead..])
                }
            }
        };
        // The crossings in front of `p`: towards `+x`, those found plus the
        // upper gap's; towards `−x`, the lower gap's less those found
        // behind `p` (each counted negated by `triangle_step`).
        let mut winding = match direction {
            XDirection::Plus => between.winding_above,
            XDirection::Minus => between.winding_below,
        };
        let q = DVec2::new(p.y, p.z);
        for e in candidates {
            match triangle_step(&self.tris[e.record as usize], p, q, direction) {
                Step::Miss => {}
                Step::OnBoundary => return XRay::OnBoundary,
                Step::Crossing(w) => winding += w,
            }
        }
        XRay::Winding(winding)
    }

    /// The point a ray from `p` is cast from, or `None` when no ray from `p`
    /// along `±x` meets the solid's boundary in front of `p` (outside the
    /// projected box, or right of the box: winding 0, not on the boundary).
    ///
    /// Left of the box every triangle the line meets is in front of `p`,
    /// wherever `p` is, and `p` is on none: every such point is moved to
    /// one fixed `x` next to the box, so that the exact predicates see
    /// coordinates of the model's magnitude and decide the same (a point at
    /// `x = −1e308` overflows their arithmetic; one at `x = −5e-324` beside
    /// a face at `x = 0` underflows it, and `orient3d` called it on that
    /// face — found by the queries fuzz target once parity could look
    /// along `−x` and see no such face).
    #[inline]
    pub(super) fn probe_point(&self, p: DVec3) -> Option<DVec3> {
        let g = self.grid();
        if !(p.y >= g.y0 && p.y <= g.y1 && p.z >= g.z0 && p.z <= g.z1) || p.x > self.bounds.max.x {
            return None;
        }
        if p.x < self.bounds.min.x {
            let beside = self.bounds.min.x - (1.0 + self.bounds.min.x.abs());
            return Some(DVec3::new(beside, p.y, p.z));
        }
        Some(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::stress_points::{closed_solids, stress_points};

    #[test]
    fn minus_x_rays_answer_as_plus_x_rays_on_closed_solids() {
        for (k, solid) in closed_solids().iter().enumerate() {
            let accel = Accel::new(solid);
            for p in stress_points(solid, 11 + k as u64) {
                let plus = accel.x_ray_towards(p, RayChoice::Always(XDirection::Plus));
                let minus = accel.x_ray_towards(p, RayChoice::Always(XDirection::Minus));
                let fewer = accel.x_ray_towards(p, RayChoice::Fewer);
                // Oriented closed solids: even the signed counts agree.
                assert_eq!(plus, minus, "solid {k}, {p}");
                assert_eq!(plus, fewer, "solid {k}, {p}");
            }
        }
    }

    #[test]
    fn boundary_points_are_found_from_either_side() {
        let accel = Accel::new(&builders::cube());
        let mut points = Vec::new();
        for a in [-1.0, -0.5, 0.0, 0.5, 1.0] {
            for b in [-1.0, -0.25, 0.0, 0.75, 1.0] {
                for side in [-1.0, 1.0] {
                    points.push(DVec3::new(side, a, b));
                    points.push(DVec3::new(a, side, b));
                    points.push(DVec3::new(a, b, side));
                }
            }
        }
        for p in points {
            for choice in [
                RayChoice::Always(XDirection::Plus),
                RayChoice::Always(XDirection::Minus),
                RayChoice::Fewer,
            ] {
                assert_eq!(accel.x_ray_towards(p, choice), XRay::OnBoundary, "{p}");
            }
        }
    }

    #[test]
    fn cell_prefix_and_suffix_hold_every_triangle_a_ray_can_meet() {
        let solid = builders::sphere(24);
        let accel = Accel::new(&solid);
        let g = accel.grid();
        let mut u = crate::test_rng::uniform(5);
        for _ in 0..4000 {
            let b = accel.bounds();
            let p = b.min + DVec3::new(u(), u(), u()) * (b.max - b.min);
            let (entries, extent) = g.cell_at(g.cell_index(p.y, p.z));
            let reach = f32_up(f64_below(p.x - f64::from(extent)));
            for (i, e) in entries.iter().enumerate() {
                let t = &accel.tris[e.record as usize];
                assert!(f64::from(e.x) <= t.x[0].min(t.x[1]).min(t.x[2]));
                if i > 0 {
                    assert!(entries[i - 1].x <= e.x);
                }
                // Every triangle reaching `p.x` from `+x` is in the suffix.
                if t.x[0].max(t.x[1]).max(t.x[2]) >= p.x {
                    assert!(e.x >= reach, "{p}");
                }
            }
        }
    }
}
