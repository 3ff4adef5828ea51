//! What ray queries answer: crossings, their transitions, a ray's crossings
//! with the origin's containment, and the work a traversal did.

use crate::geom::Sign;
use crate::mesh::FaceId;

use super::Containment;

/// Whether the ray enters or leaves the solid at a crossing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Transition {
    /// The ray goes from outside to inside (against the face's outward
    /// normal).
    Enter,
    /// The ray goes from inside to outside (along the outward normal).
    Exit,
}

/// One crossing of a ray with a solid's boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The ray parameter, `origin + t · direction`; a rounded construction,
    /// always `> 0`.
    pub t: f64,
    /// The face crossed (for a ray through an edge or a vertex: the one face
    /// the perturbed ray crosses).
    pub face: FaceId,
    /// Entering or leaving, decided exactly (from the face's orientation).
    pub transition: Transition,
    /// Which triangle of the accel's fan triangulation was crossed (its
    /// plane gives `t` exactly; see `Accel::triangle`).
    pub triangle: u32,
}

/// A ray's answer from one solid: whether its origin is inside, and where it
/// crosses the boundary.
///
/// # Invariants
///
/// `hits` is sorted by ascending `t`, every `t > 0`; crossings with equal
/// rounded `t` (a ray grazing a vertex or an edge) are listed in the order the
/// perturbed ray meets them. On a valid closed solid
/// the transitions alternate, starting with `Exit` when `origin` is
/// `Inside` and `Enter` when it is `Outside`; the list ends with an `Exit`
/// (the ray ends outside). When `origin` is `OnBoundary`, crossings at the
/// origin itself are not listed, and the first transition tells whether the
/// ray runs inside (`Exit` first) or outside (`Enter` first) just after
/// leaving the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct RayCrossings {
    /// Where the ray's origin is.
    pub origin: Containment,
    /// The crossings with `t > 0`, ascending.
    pub hits: Vec<Crossing>,
}

/// What one ray's traversal touched: the work counts behind its time, so
/// that culling can be checked by counting rather than by timing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalStats {
    /// BVH nodes whose child boxes were tested.
    pub nodes: u64,
    /// Triangles the ray was tested against (by the leaves' `f32` miss
    /// filter).
    pub triangles: u64,
    /// Of those, the triangles the filter could not prove missed, which
    /// went on to the exact test.
    pub exact_tests: u64,
}

/// Where a traversal reports its work: nowhere (the queries) or into a
/// [`TraversalStats`] (the traced forms).
pub(super) trait Tally {
    /// A BVH node was opened.
    fn node(&mut self);
    /// A triangle went through the leaves' `f32` filter.
    fn triangle(&mut self);
    /// A triangle went on to the exact test.
    fn exact_test(&mut self);
}

impl Tally for () {
    #[inline(always)]
    fn node(&mut self) {}
    #[inline(always)]
    fn triangle(&mut self) {}
    #[inline(always)]
    fn exact_test(&mut self) {}
}

impl Tally for TraversalStats {
    #[inline(always)]
    fn node(&mut self) {
        self.nodes += 1;
    }
    #[inline(always)]
    fn triangle(&mut self) {
        self.triangles += 1;
    }
    #[inline(always)]
    fn exact_test(&mut self) {
        self.exact_tests += 1;
    }
}

/// The best crossing of a first-hit query so far: rounded `t`, triangle,
/// and the sign of its crossing (`+` for an exit).
pub(super) type BestHit = Option<(f64, u32, Sign)>;

/// The nearest crossing a first-hit walk has found so far: its rounded `t`
/// with a bound on that rounding's error (`+∞` when none is known), its
/// triangle and sign. Crossings whose `t` intervals overlap are ordered
/// exactly by the first-hit walk.
#[derive(Clone, Copy, Debug)]
pub(super) struct Nearest {
    /// The rounded `t` (clamped to the smallest positive `f64`).
    pub t: f64,
    /// `|t − exact t|` is at most this.
    pub error: f64,
    /// The triangle.
    pub triangle: u32,
    /// `+` for an exit.
    pub sign: Sign,
}
