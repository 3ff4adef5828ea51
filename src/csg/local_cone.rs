//! Points where surfaces of a tree meet at an angle (edges, corners, faces
//! of different leaves that are not recognised as coincident), decided
//! exactly by directions.
//!
//! Near a boundary point `p`, every leaf whose boundary passes through `p`
//! is, to first order, a union of cells of the arrangement of the planes of
//! its flat pieces through `p` (a box corner: three planes; a polyhedron
//! vertex: the planes of its triangles there). The combined solid near `p`
//! is then a union of cells of the arrangement of *all* those planes, and
//! `p` is
//!
//! - `Inside` when every cell is inside the combined solid,
//! - `Outside` when none is (the regularised answer: two boxes that share
//!   only a face have an empty intersection, corners included),
//! - `OnBoundary` otherwise.
//!
//! One direction `d` inside each cell suffices: every leaf answers whether
//! `p + ε d` is inside it for an infinitesimal `ε`
//! ([`Primitive::inside_along`]), and the tree combines those answers as
//! plain booleans. The cells are found without building the arrangement:
//! when the planes' normals span space, every cell is a pointed cone, so one
//! of its extreme rays is the line `ℓ` where two of the planes meet, and
//! near `ℓ` the cells are the sectors between the planes that contain `ℓ`.
//! So for each such line (both ways) and each sector around it, a direction
//! `d = ℓ̂ + δ w` is made in floating point (`w` in the sector, `δ` small
//! enough to keep the side of every other plane), and then *checked
//! exactly*: the sign of every plane at `d` must be the sign the cell has
//! (`ℓ`'s side for the planes not through `ℓ`, `w`'s side for those through
//! it, all non-zero), and the sectors found around `ℓ` must be all
//! `2 m` of them for `m` planes through `ℓ`. When any check fails (a cell
//! too thin for floating point to find), or a leaf at `p` cannot list its
//! planes (curved surfaces), the answer stays
//! `OnBoundary`, as before this analysis; no answer is ever guessed.

use crate::SetOp;
use glam::DVec3;

use super::tree::{NodeIndex, NodeKind};
use super::{Containment, Csg, Stats};
use crate::geom::Sign;
use crate::geom::dyadic::{Dyadic, det3_sign};

/// The most distinct planes through one point that the analysis takes on
/// (the work grows with the cube of their number); beyond it the point is
/// answered `OnBoundary`.
pub const MAX_PLANES_AT_A_POINT: usize = 48;

/// A plane through a boundary point, by its exact normal: the oriented
/// plane of a flat piece of a leaf's boundary (the outward side is where the
/// normal points, though only the plane itself is used here).
#[derive(Clone, Debug)]
pub struct LocalPlane {
    exact: [Dyadic; 3],
    /// The normal rounded and scaled to unit length (constructions only).
    approx: DVec3,
}

impl LocalPlane {
    /// The plane with normal `normal` (exact as given); `None` for a zero or
    /// non-finite normal.
    #[must_use]
    pub fn from_normal(normal: DVec3) -> Option<LocalPlane> {
        if !normal.is_finite() || normal == DVec3::ZERO {
            return None;
        }
        Some(LocalPlane {
            exact: [normal.x, normal.y, normal.z].map(Dyadic::of),
            approx: normal.normalize(),
        })
    }

    /// The plane of the triangle `a, b, c` (normal `(b − a) × (c − a)`,
    /// computed exactly); `None` when the corners are collinear.
    #[must_use]
    pub fn from_triangle([a, b, c]: [DVec3; 3]) -> Option<LocalPlane> {
        let e1 = [0, 1, 2].map(|k| Dyadic::difference(b[k], a[k]));
        let e2 = [0, 1, 2].map(|k| Dyadic::difference(c[k], a[k]));
        let exact = cross(&e1, &e2);
        if exact.iter().all(|x| x.sign() == Sign::Zero) {
            return None;
        }
        let approx = (b - a).cross(c - a).normalize_or_zero();
        // A normal whose rounding vanished still has exact signs; its
        // rounded direction only steers the search.
        Some(LocalPlane { exact, approx })
    }

    /// The exact sign of `n · d`.
    fn side(&self, d: DVec3) -> Sign {
        let [x, y, z] = &self.exact;
        (&(&(x * &Dyadic::of(d.x)) + &(y * &Dyadic::of(d.y))) + &(z * &Dyadic::of(d.z))).sign()
    }
}

fn cross(a: &[Dyadic; 3], b: &[Dyadic; 3]) -> [Dyadic; 3] {
    [
        &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
        &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
        &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
    ]
}

/// The exact sign of `a · (b × c)`.
fn triple(a: &LocalPlane, b: &LocalPlane, c: &LocalPlane) -> Sign {
    det3_sign(&[a.exact.clone(), b.exact.clone(), c.exact.clone()])
}

/// Whether two planes through one point are the same plane (their normals
/// parallel, either way), exactly.
fn same_plane(a: &LocalPlane, b: &LocalPlane) -> bool {
    cross(&a.exact, &b.exact)
        .iter()
        .all(|x| x.sign() == Sign::Zero)
}

/// What the leaves say at the point: their containment, and for those on
/// the boundary their planes there.
struct AtPoint {
    /// Per leaf: `None` when not visited (a subtree whose bounds miss `p`).
    leaves: Vec<Option<Containment>>,
    planes: Vec<LocalPlane>,
}

/// The cells of the arrangement seen from a point, as directions: the
/// answer of the analysis for the tree.
enum Verdict {
    Inside,
    Outside,
    Boundary,
}

impl Csg {
    /// The class of a boundary point where surfaces meet at an angle, by
    /// the directions of the cells around it (see the module text); `None`
    /// when the analysis cannot decide it (the caller then answers
    /// `OnBoundary`). Counted in `stats.direction_analyses`.
    pub(crate) fn classify_by_directions(
        &self,
        p: DVec3,
        stats: &mut Stats,
    ) -> Option<Containment> {
        stats.direction_analyses += 1;
        let mut at = AtPoint {
            leaves: vec![None; self.leaves.len()],
            planes: Vec::new(),
        };
        self.gather(self.root, p, &mut at)?;
        let verdict = self.verdict(p, &at)?;
        Some(match verdict {
            Verdict::Inside => Containment::Inside,
            Verdict::Outside => Containment::Outside,
            Verdict::Boundary => Containment::OnBoundary,
        })
    }

    /// Records every reachable leaf's containment at `p`, and the distinct
    /// planes through `p` of those on their boundary. `None` when a leaf on
    /// its boundary cannot list its planes, or there are too many.
    fn gather(&self, node: NodeIndex, p: DVec3, at: &mut AtPoint) -> Option<()> {
        let n = &self.nodes[node];
        if !n.bounds.contains(p) {
            return Some(());
        }
        match n.kind {
            NodeKind::Leaf(id) => {
                let primitive = &self.leaves[id.0 as usize].primitive;
                let class = primitive.classify_point(p);
                at.leaves[id.0 as usize] = Some(class);
                if class == Containment::OnBoundary {
                    let mut planes = Vec::new();
                    if !primitive.planes_through(p, &mut planes) {
                        return None;
                    }
                    for plane in planes {
                        if !at.planes.iter().any(|q| same_plane(q, &plane)) {
                            at.planes.push(plane);
                        }
                    }
                    if at.planes.len() > MAX_PLANES_AT_A_POINT {
                        return None;
                    }
                }
                Some(())
            }
            NodeKind::Op { left, right, .. } => {
                self.gather(left, p, at)?;
                self.gather(right, p, at)
            }
        }
    }

    /// Whether `p + ε d` is inside the combined solid.
    fn inside_along(&self, node: NodeIndex, p: DVec3, d: DVec3, at: &AtPoint) -> Option<bool> {
        let n = &self.nodes[node];
        match n.kind {
            NodeKind::Leaf(id) => match at.leaves[id.0 as usize] {
                None | Some(Containment::Outside) => Some(false),
                Some(Containment::Inside) => Some(true),
                Some(Containment::OnBoundary) => {
                    self.leaves[id.0 as usize].primitive.inside_along(p, d)
                }
            },
            NodeKind::Op { op, left, right } => {
                let a = self.inside_along(left, p, d, at)?;
                let b = self.inside_along(right, p, d, at)?;
                Some(match op {
                    SetOp::Union => a || b,
                    SetOp::Intersection => a && b,
                    SetOp::Difference => a && !b,
                    SetOp::ReverseDifference => !a && b,
                })
            }
        }
    }

    /// Walks one direction per cell; stops as soon as one cell inside and
    /// one outside are seen.
    fn verdict(&self, p: DVec3, at: &AtPoint) -> Option<Verdict> {
        let (mut seen_in, mut seen_out) = (false, false);
        let mut visit = |d: DVec3| -> Option<bool> {
            if self.inside_along(self.root, p, d, at)? {
                seen_in = true;
            } else {
                seen_out = true;
            }
            // Stop early: both kinds seen.
            Some(seen_in && seen_out)
        };
        for_each_cell(&at.planes, &mut visit)?;
        Some(match (seen_in, seen_out) {
            (true, false) => Verdict::Inside,
            (false, true) => Verdict::Outside,
            (true, true) => Verdict::Boundary,
            // No plane at all: the point is on no leaf's boundary.
            (false, false) => return None,
        })
    }
}

/// Calls `visit(d)` with a direction inside every full-dimensional cell of
/// the arrangement of `planes` (all through one point; pairwise distinct),
/// each checked exactly, until `visit` returns `Some(true)` (stop). Returns
/// `None` when a check fails or `visit` does; `Some(stopped)` otherwise.
fn for_each_cell(
    planes: &[LocalPlane],
    visit: &mut impl FnMut(DVec3) -> Option<bool>,
) -> Option<bool> {
    match planes.len() {
        0 => return Some(false),
        1 => {
            let n = planes[0].approx;
            for d in [n, -n] {
                if planes[0].side(d) == Sign::Zero {
                    return None;
                }
                if visit(d)? {
                    return Some(true);
                }
            }
            return Some(false);
        }
        _ => {}
    }
    for i in 0..planes.len() {
        for j in i + 1..planes.len() {
            // The planes through the line ℓ = nᵢ × nⱼ; the line is taken
            // once, from its two first planes.
            let sides: Vec<Sign> = planes
                .iter()
                .enumerate()
                .map(|(k, plane)| {
                    if k == i || k == j {
                        Sign::Zero
                    } else {
                        triple(plane, &planes[i], &planes[j])
                    }
                })
                .collect();
            let through: Vec<usize> = (0..planes.len())
                .filter(|&k| sides[k] == Sign::Zero)
                .collect();
            if through[..2] != [i, j] {
                continue;
            }
            for way in [Sign::Positive, Sign::Negative] {
                if around_line(planes, (i, j), way, &sides, &through, visit)? {
                    return Some(true);
                }
            }
        }
    }
    Some(false)
}

/// The cells around the ray `way · ℓ` (`ℓ = nᵢ × nⱼ`): one direction per
/// sector of the planes `through` it. `sides[k]` is the sign of `nₖ · ℓ`.
fn around_line(
    planes: &[LocalPlane],
    (i, j): (usize, usize),
    way: Sign,
    sides: &[Sign],
    through: &[usize],
    visit: &mut impl FnMut(DVec3) -> Option<bool>,
) -> Option<bool> {
    let flip = |s: Sign| {
        if way == Sign::Negative {
            s.reversed()
        } else {
            s
        }
    };
    let mut u = planes[i].approx.cross(planes[j].approx).normalize_or_zero();
    if way == Sign::Negative {
        u = -u;
    }
    if u == DVec3::ZERO || !u.is_finite() {
        return None;
    }
    // The sector boundaries: in each plane through ℓ, the two rays
    // perpendicular to ℓ, by angle in a basis of the plane ⊥ u.
    let e1 = u.cross(planes[through[0]].approx).normalize_or_zero();
    let e2 = u.cross(e1);
    let mut angles: Vec<f64> = through
        .iter()
        .flat_map(|&k| {
            let r = u.cross(planes[k].approx);
            let a = r.dot(e2).atan2(r.dot(e1));
            [a, a + std::f64::consts::PI]
        })
        .map(|a| a.rem_euclid(std::f64::consts::TAU))
        .collect();
    angles.sort_by(f64::total_cmp);
    // How far off ℓ a direction may go and keep the side of every plane
    // not through ℓ (unit normals; |n · w| ≤ 1).
    let margin = (0..planes.len())
        .filter(|k| !through.contains(k))
        .map(|k| planes[k].approx.dot(u).abs())
        .fold(1.0_f64, f64::min);
    let delta = 0.5 * margin;
    let mut sectors: Vec<Vec<Sign>> = Vec::with_capacity(angles.len());
    for s in 0..angles.len() {
        let (a0, a1) = (angles[s], angles[(s + 1) % angles.len()]);
        let span = if s + 1 == angles.len() {
            a1 + std::f64::consts::TAU - a0
        } else {
            a1 - a0
        };
        let mid = a0 + 0.5 * span;
        let w = e1 * mid.cos() + e2 * mid.sin();
        let d = u + delta * w;
        // The cell this direction is meant for: ℓ's side of the planes not
        // through ℓ, w's side of those through it; all non-zero, and d
        // must have exactly those signs.
        let mut signs = Vec::with_capacity(through.len());
        for (k, plane) in planes.iter().enumerate() {
            let want = if through.contains(&k) {
                let s = plane.side(w);
                signs.push(s);
                s
            } else {
                flip(sides[k])
            };
            if want == Sign::Zero || plane.side(d) != want {
                return None;
            }
        }
        if !sectors.contains(&signs) {
            sectors.push(signs);
        }
        if visit(d)? {
            return Some(true);
        }
    }
    // Every sector around ℓ was met: 2 m of them for m planes.
    (sectors.len() == 2 * through.len()).then_some(false)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn axis_planes() -> Vec<LocalPlane> {
        [DVec3::X, DVec3::Y, DVec3::Z]
            .into_iter()
            .filter_map(LocalPlane::from_normal)
            .collect()
    }

    /// The sign pattern of a direction against the planes.
    fn pattern(planes: &[LocalPlane], d: DVec3) -> Vec<Sign> {
        planes.iter().map(|p| p.side(d)).collect()
    }

    fn cells(planes: &[LocalPlane]) -> Vec<Vec<Sign>> {
        let mut found = Vec::new();
        let stopped = for_each_cell(planes, &mut |d| {
            let s = pattern(planes, d);
            assert!(s.iter().all(|&x| x != Sign::Zero), "{d:?}");
            if !found.contains(&s) {
                found.push(s);
            }
            Some(false)
        });
        assert_eq!(stopped, Some(false));
        found
    }

    #[test]
    fn three_axis_planes_have_eight_octants() {
        assert_eq!(cells(&axis_planes()).len(), 8);
    }

    #[test]
    fn one_plane_has_two_sides_and_a_pencil_has_its_wedges() {
        assert_eq!(cells(&axis_planes()[..1]).len(), 2);
        // x = 0, y = 0 and x = y all contain the z axis: six wedges.
        let mut pencil = axis_planes()[..2].to_vec();
        pencil.push(LocalPlane::from_normal(DVec3::new(1.0, -1.0, 0.0)).unwrap());
        assert_eq!(cells(&pencil).len(), 6);
    }

    #[test]
    fn four_planes_in_general_position_have_fourteen_cells() {
        // A central arrangement of n planes in general position has
        // n(n − 1) + 2 cells.
        let mut planes = axis_planes();
        planes.push(LocalPlane::from_normal(DVec3::new(1.0, 1.0, 1.0)).unwrap());
        assert_eq!(cells(&planes).len(), 14);
        planes.push(LocalPlane::from_normal(DVec3::new(1.0, -2.0, 3.0)).unwrap());
        assert_eq!(cells(&planes).len(), 22);
    }

    #[test]
    fn triangle_planes_are_exact() {
        let t = [
            DVec3::ZERO,
            DVec3::new(0.1, 0.0, 0.0),
            DVec3::new(0.0, 0.3, 0.7),
        ];
        let plane = LocalPlane::from_triangle(t).unwrap();
        // (0.3, 0.7)·… : the normal is (0, −0.07, 0.03) up to rounding;
        // a direction in the plane has sign zero exactly.
        assert_eq!(plane.side(DVec3::new(0.0, 0.3, 0.7)), Sign::Zero);
        assert_eq!(
            plane.side(DVec3::new(0.0, 0.3, 0.7_f64.next_up())),
            Sign::Positive
        );
        assert!(LocalPlane::from_triangle([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]).is_none());
        assert!(LocalPlane::from_normal(DVec3::ZERO).is_none());
    }
}
