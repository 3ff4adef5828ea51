//! Counters that make "only the work a query needs" checkable.

use std::ops::AddAssign;

/// Work counters of CSG queries.
///
/// Every query takes a `&mut Stats` and adds to it, so a caller can sum the
/// work of many queries (threads each keep their own and add them up).
/// Tests assert these counts on scenes where culling must happen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Rays cast into the tree (camera, shadow, volume or user rays).
    pub rays: u64,
    /// Calls of [`Primitive::intersect_ray`](super::Primitive::intersect_ray).
    pub primitive_ray_tests: u64,
    /// Calls of [`Primitive::classify_point`](super::Primitive::classify_point).
    pub primitive_point_tests: u64,
    /// Calls of [`Primitive::cell_relation`](super::Primitive::cell_relation)
    /// (octree cells against a leaf).
    pub primitive_cell_tests: u64,
    /// Bounding-box tests of tree nodes (cheap; each guards a subtree).
    pub bounds_tests: u64,
    /// Subtrees never visited because the ray (or point) missed their bounds.
    pub culled_subtrees: u64,
    /// Right sides of ∪, ∩ and − never evaluated because the left side
    /// already fixed the answer along the ray (empty for ∩ and −, everything
    /// for ∪).
    pub skipped_right_sides: u64,
    /// First-hit merges stopped as soon as the first boundary was known.
    pub early_stops: u64,
    /// Exact-arithmetic fallbacks of the predicates (the difference of
    /// [`exact_fallbacks`](crate::geom::exact_fallbacks) around the query).
    pub exact_fallbacks: u64,
    /// Ties decided by symbolic perturbation: a ray lying exactly in a face
    /// plane of a box or half-space, and inside polyhedral leaves a ray
    /// through an edge or a vertex or a point whose parity ray grazes one
    /// (the difference of [`tie_breaks`](crate::geom::tie_breaks) around the
    /// query).
    pub tie_breaks: u64,
    /// Surface normals computed (only images need them).
    pub normals: u64,
    /// Shadow rays cast (only when the scene asks for shadows).
    pub shadow_rays: u64,
    /// Boundary points where surfaces meet at an angle, decided by one
    /// direction per cell of the planes there (see
    /// [`Csg::classify_point`](super::Csg::classify_point)).
    pub direction_analyses: u64,
    /// Crossings of different leaves whose rounded `t` were too close to
    /// order, ordered exactly by the planes crossed.
    pub exact_orders: u64,
}

impl AddAssign for Stats {
    fn add_assign(&mut self, o: Stats) {
        self.rays += o.rays;
        self.primitive_ray_tests += o.primitive_ray_tests;
        self.primitive_point_tests += o.primitive_point_tests;
        self.primitive_cell_tests += o.primitive_cell_tests;
        self.bounds_tests += o.bounds_tests;
        self.culled_subtrees += o.culled_subtrees;
        self.skipped_right_sides += o.skipped_right_sides;
        self.early_stops += o.early_stops;
        self.exact_fallbacks += o.exact_fallbacks;
        self.tie_breaks += o.tie_breaks;
        self.normals += o.normals;
        self.shadow_rays += o.shadow_rays;
        self.direction_analyses += o.direction_analyses;
        self.exact_orders += o.exact_orders;
    }
}

impl std::fmt::Display for Stats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "rays {}  primitive ray tests {}  primitive point tests {}  primitive cell tests {}  bounds tests {}  culled subtrees {}  skipped right sides {}  early stops {}  exact fallbacks {}  tie-breaks {}  normals {}  shadow rays {}  direction analyses {}  exact orders {}",
            self.rays,
            self.primitive_ray_tests,
            self.primitive_point_tests,
            self.primitive_cell_tests,
            self.bounds_tests,
            self.culled_subtrees,
            self.skipped_right_sides,
            self.early_stops,
            self.exact_fallbacks,
            self.tie_breaks,
            self.normals,
            self.shadow_rays,
            self.direction_analyses,
            self.exact_orders
        )
    }
}

/// Adds the exact-arithmetic fallbacks and the symbolic-perturbation
/// tie-breaks taken on this thread while `work` runs (inside polyhedra, by
/// the predicates) to `stats.exact_fallbacks` and `stats.tie_breaks`.
pub(crate) fn counting_fallbacks<T>(stats: &mut Stats, work: impl FnOnce(&mut Stats) -> T) -> T {
    let fallbacks = crate::geom::exact_fallbacks();
    let ties = crate::geom::tie_breaks();
    let out = work(stats);
    stats.exact_fallbacks += crate::geom::exact_fallbacks().saturating_sub(fallbacks);
    stats.tie_breaks += crate::geom::tie_breaks().saturating_sub(ties);
    out
}
