//! What accuracy costs in time: the same point classifications and ray
//! crossings at four accuracy levels, on generic and on hard inputs.
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin accuracy_vs_time            # table + docs/accuracy_vs_time.svg
//! cargo run --release -p wingedge-bench --bin accuracy_vs_time -- OUT.svg
//! ```
//!
//! Levels (1–3 are written here, not in the library):
//!
//! 1. **f32**: Möller–Trumbore ray–triangle tests in `f32`, parity of the
//!    hits, no tie handling, no notion of "on the boundary".
//! 2. **f64 + ε**: the same test in `f64` with the usual fixed epsilons
//!    (`|det| < 1e-9` is "parallel", a hit with `|t| ≤ 1e-9` is "on the
//!    surface"). The epsilons are deliberate: this level shows typical
//!    practice.
//! 3. **exact, naive ties**: the library's filtered exact predicates
//!    (`orient2d`, `orient3d`, `line_side`), so every sign is right, but a
//!    ray through an edge or vertex is counted on every triangle it touches
//!    and a triangle parallel to the ray is skipped (no symbolic
//!    perturbation).
//! 4. **exact + SoS**: the library, [`Accel::classify`] and
//!    [`Accel::ray_crossings`].
//!
//! Levels 1–3 share one acceleration structure written here (a uniform `yz`
//! grid for the `+x` rays of points, a median-split BVH with `f64` boxes for
//! rays; culling in `f64` for all three), so their times differ by
//! arithmetic only. Level 4 uses the library's own accel (the same kinds of
//! structure, tuned: `x` culling in the grid, an SAH BVH with `f32` boxes),
//! so its time is not an arithmetic-only comparison. Every query runs on
//! one thread, best of `REPEATS`. The driver also prints, per scene and
//! set, how many exact-arithmetic fallbacks the library's predicates took
//! per query at levels 3 and 4.
//!
//! Meshes are built here: a 3-times subdivided icosahedron (1,280 triangles)
//! and the library's L-shaped prism, triangulated; each also offset by 1e8
//! and scaled by 1e-8. Coordinates are snapped to a dyadic grid so that
//! points on faces and edges and rays through vertices and along edges can
//! be constructed *exactly* (every float operation in their construction is
//! exact); "near" points are those moved 1–4 ulps along one axis.
//!
//! Reference: exact big-integer arithmetic that shares no code with any
//! level (`tests/common/rational_parity.rs`): a point's class is the parity
//! of an exact ray count along a direction that meets no edge or vertex (on
//! a triangle: boundary; points on the boundary by construction are checked
//! to be found there); a ray's reference is its exact crossing count, or,
//! when it meets an edge or a vertex (its count then depends on the tie
//! rule), the parity of a level's count against the origin's exact class.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use glam::{DVec2, DVec3, Vec3};
use wingedge::geom::exact::line_side_filter_scalar;
use wingedge::geom::polygon::coplanar_point_in_closed_triangle;
use wingedge::geom::{
    Ray, Sign, exact_fallbacks, line_side, orient2d, orient3d, reset_exact_fallbacks,
};
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::query::{Accel, Containment};

#[path = "../../../../tests/common/rational_parity.rs"]
mod rational_parity;
#[path = "../../../../src/test_rng.rs"]
mod test_rng;

use rational_parity::{Class, Degenerate};

/// Level 2's determinant epsilon: below it a ray is "parallel" to a
/// triangle. Deliberately inexact (typical practice), used nowhere else.
const EPS_DET: f64 = 1e-9;
/// Level 2's distance epsilon: a hit with `|t| ≤ EPS_T` (unit direction)
/// means the point is "on the surface". Deliberately inexact.
const EPS_T: f64 = 1e-9;
/// Points per point set and scene.
const POINTS: usize = 10_000;
/// Rays per ray set and scene.
const RAYS: usize = 5_000;
/// Timing repetitions (the best is kept).
const REPEATS: usize = 5;

/// The four accuracy levels, in order.
const LEVELS: [&str; 4] = ["f32", "f64 + eps", "exact, naive ties", "exact + SoS"];

/// A seeded generator (the shared xorshift64): the same inputs on every run.
struct Rng(Box<dyn FnMut() -> u64>);

impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(Box::new(test_rng::bits(seed)))
    }

    fn next_u64(&mut self) -> u64 {
        (self.0)()
    }

    /// Uniform in `[0, 1)`.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `0..n`.
    fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// Uniform integer in `lo..=hi`.
    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as i64
    }
}

/// A closed triangle mesh, outward oriented.
#[derive(Clone)]
struct TriMesh {
    positions: Vec<DVec3>,
    tris: Vec<[usize; 3]>,
}

/// Rounds `x` to a multiple of `h` (a power of two).
fn snap(x: f64, h: f64) -> f64 {
    (x / h).round() * h
}

/// The icosahedron subdivided `levels` times, vertices on the unit sphere
/// snapped to multiples of 2⁻²⁰.
fn icosphere(levels: usize) -> TriMesh {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let mut positions = Vec::new();
    for (a, b) in [(1.0, phi), (-1.0, phi), (1.0, -phi), (-1.0, -phi)] {
        positions.push(DVec3::new(0.0, a, b));
        positions.push(DVec3::new(a, b, 0.0));
        positions.push(DVec3::new(b, 0.0, a));
    }
    // Faces: the triples at pairwise distance 2, wound outward.
    let mut tris = Vec::new();
    for i in 0..12 {
        for j in i + 1..12 {
            for k in j + 1..12 {
                let (a, b, c) = (positions[i], positions[j], positions[k]);
                let close = |p: DVec3, q: DVec3| (p.distance(q) - 2.0).abs() < 1e-6;
                if close(a, b) && close(b, c) && close(a, c) {
                    let n = (b - a).cross(c - a);
                    tris.push(if n.dot(a + b + c) > 0.0 {
                        [i, j, k]
                    } else {
                        [i, k, j]
                    });
                }
            }
        }
    }
    let mut positions: Vec<DVec3> = positions.iter().map(|p| p.normalize()).collect();
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(tris.len() * 4);
        let mut midpoint = |i: usize, j: usize, positions: &mut Vec<DVec3>| {
            *mid.entry((i.min(j), i.max(j))).or_insert_with(|| {
                positions.push((positions[i] + positions[j]).normalize());
                positions.len() - 1
            })
        };
        for &[a, b, c] in &tris {
            let ab = midpoint(a, b, &mut positions);
            let bc = midpoint(b, c, &mut positions);
            let ca = midpoint(c, a, &mut positions);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        tris = next;
    }
    let h = 2f64.powi(-20);
    let positions = positions.iter().map(|p| p.map(|x| snap(x, h))).collect();
    TriMesh { positions, tris }
}

/// The library's L-shaped prism (`builders::l_prism`), triangulated and
/// moved off the coordinate planes by `(0.5, 0.25, 0.125)`.
fn l_prism() -> TriMesh {
    let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)];
    let shift = DVec3::new(0.5, 0.25, 0.125);
    let mut positions: Vec<DVec3> = Vec::new();
    for z in [0.0, 1.0] {
        positions.extend(l.iter().map(|&(x, y)| DVec3::new(x, y, z) + shift));
    }
    let mut tris = Vec::new();
    // Caps: fans from corner 0 (every fan triangle of the L is convex).
    for k in 1..5 {
        tris.push([0, k + 1, k]); // bottom, facing −z
        tris.push([6, 6 + k, 7 + k]); // top, facing +z
    }
    for i in 0..6 {
        let j = (i + 1) % 6;
        tris.push([i, j, 6 + j]);
        tris.push([i, 6 + j, 6 + i]);
    }
    TriMesh { positions, tris }
}

/// `mesh` scaled by `scale` then offset by `offset`, snapped to the dyadic
/// grid `h` (so that constructions below stay exact).
fn transform(mesh: &TriMesh, scale: f64, offset: f64, h: f64) -> TriMesh {
    TriMesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| p.map(|x| snap(x * scale, h) + offset))
            .collect(),
        tris: mesh.tris.clone(),
    }
}

/// A median-split BVH over triangles with padded `f64` boxes, shared by
/// levels 1–3. Leaves hold up to four triangles.
struct Bvh {
    nodes: Vec<BvhNode>,
    /// Triangle indices in leaf order.
    order: Vec<usize>,
}

/// One BVH node: its box; a leaf lists `count > 0` triangles from `first`,
/// an inner node has `count = 0`, its first child next and its second at
/// `first`.
struct BvhNode {
    lo: DVec3,
    hi: DVec3,
    first: usize,
    count: usize,
}

impl Bvh {
    fn new(corners: &[[DVec3; 3]]) -> Bvh {
        let mut order: Vec<usize> = (0..corners.len()).collect();
        let mut nodes = Vec::new();
        Bvh::build(corners, &mut order, 0, corners.len(), &mut nodes);
        Bvh { nodes, order }
    }

    fn build(
        corners: &[[DVec3; 3]],
        order: &mut [usize],
        start: usize,
        end: usize,
        nodes: &mut Vec<BvhNode>,
    ) -> usize {
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for &i in &order[start..end] {
            for p in corners[i] {
                lo = lo.min(p);
                hi = hi.max(p);
            }
        }
        // Padding so that rounding in the slab test never loses a triangle.
        let pad = lo.abs().max(hi.abs()).max_element() * 1e-12;
        let index = nodes.len();
        nodes.push(BvhNode {
            lo: lo - pad,
            hi: hi + pad,
            first: start,
            count: end - start,
        });
        if end - start <= 4 {
            return index;
        }
        let axis = (hi - lo).max_position();
        let centre = |i: usize| (corners[i][0] + corners[i][1] + corners[i][2])[axis];
        let mid = (start + end) / 2;
        order[start..end]
            .select_nth_unstable_by(mid - start, |&a, &b| centre(a).total_cmp(&centre(b)));
        Bvh::build(corners, order, start, mid, nodes);
        let second = Bvh::build(corners, order, mid, end, nodes);
        nodes[index].first = second;
        nodes[index].count = 0;
        index
    }

    /// Calls `visit(k)` for every triangle (position `k` in leaf order)
    /// whose box the ray `o + t d`, `t ≥ 0`, may touch, until it returns
    /// `false`.
    #[inline]
    fn traverse(&self, o: DVec3, d: DVec3, mut visit: impl FnMut(usize) -> bool) {
        let inv = DVec3::ONE / d;
        let mut stack = [0usize; 64];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let index = stack[top];
            let node = &self.nodes[index];
            let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
            for a in 0..3 {
                let tn = (node.lo[a] - o[a]) * inv[a];
                let tf = (node.hi[a] - o[a]) * inv[a];
                let (near, far) = if inv[a] < 0.0 { (tf, tn) } else { (tn, tf) };
                // NaN (origin on a slab plane of a parallel ray) is ignored.
                if near > t0 {
                    t0 = near;
                }
                if far < t1 {
                    t1 = far;
                }
            }
            if t0 > t1 {
                continue;
            }
            if node.count > 0 {
                for k in node.first..node.first + node.count {
                    if !visit(k) {
                        return;
                    }
                }
            } else {
                stack[top] = index + 1;
                stack[top + 1] = node.first;
                top += 2;
            }
        }
    }
}

/// A uniform grid over the `yz` projection, shared by levels 1–3 for the
/// `+x` rays of point classification (the strategy of the library's
/// accel, written plainly): each cell lists the triangles whose projected
/// box overlaps it, about one cell per triangle.
struct YzGrid {
    lo: DVec2,
    hi: DVec2,
    inv_h: DVec2,
    n: [usize; 2],
    /// Cell `c` lists `items[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    items: Vec<usize>,
}

impl YzGrid {
    fn new(corners: &[[DVec3; 3]]) -> YzGrid {
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for p in corners.iter().flatten() {
            lo = lo.min(yz(*p));
            hi = hi.max(yz(*p));
        }
        let size = (hi - lo).max(DVec2::splat(f64::MIN_POSITIVE));
        let cells = corners.len().max(1) as f64;
        let ny = ((cells * size.x / size.y).sqrt().ceil() as usize).clamp(1, 1024);
        let nz = ((cells / ny as f64).ceil() as usize).clamp(1, 1024);
        let mut grid = YzGrid {
            lo,
            hi,
            inv_h: DVec2::new(ny as f64, nz as f64) / size,
            n: [ny, nz],
            start: vec![0; ny * nz + 1],
            items: Vec::new(),
        };
        let ranges: Vec<[usize; 4]> = corners
            .iter()
            .map(|t| {
                let (a, b) = (
                    yz(t[0]).min(yz(t[1])).min(yz(t[2])),
                    yz(t[0]).max(yz(t[1])).max(yz(t[2])),
                );
                let (c0, r0) = grid.cell(a);
                let (c1, r1) = grid.cell(b);
                [c0, c1, r0, r1]
            })
            .collect();
        for &[c0, c1, r0, r1] in &ranges {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    grid.start[r * ny + c + 1] += 1;
                }
            }
        }
        for c in 0..ny * nz {
            grid.start[c + 1] += grid.start[c];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; grid.start[ny * nz]];
        for (k, &[c0, c1, r0, r1]) in ranges.iter().enumerate() {
            for r in r0..=r1 {
                for c in c0..=c1 {
                    grid.items[fill[r * ny + c]] = k;
                    fill[r * ny + c] += 1;
                }
            }
        }
        grid
    }

    /// Column and row of `q` (monotone in each coordinate, clamped).
    fn cell(&self, q: DVec2) -> (usize, usize) {
        let f = (q - self.lo) * self.inv_h;
        (
            (f.x.max(0.0) as usize).min(self.n[0] - 1),
            (f.y.max(0.0) as usize).min(self.n[1] - 1),
        )
    }

    /// The triangles whose projected box may contain `q`.
    #[inline]
    fn candidates(&self, q: DVec2) -> &[usize] {
        if !(q.x >= self.lo.x && q.x <= self.hi.x && q.y >= self.lo.y && q.y <= self.hi.y) {
            return &[];
        }
        let (c, r) = self.cell(q);
        let i = r * self.n[0] + c;
        &self.items[self.start[i]..self.start[i + 1]]
    }
}

/// Levels 1–3 on one mesh: the BVH and each level's triangle data, in BVH
/// leaf order.
struct Naive {
    bvh: Bvh,
    grid: YzGrid,
    /// Level 1: `v0`, `e1 = v1 − v0`, `e2 = v2 − v0`, all in `f32`.
    f32_tris: Vec<[Vec3; 3]>,
    /// Level 2: `v0`, `e1`, `e2` in `f64`.
    f64_tris: Vec<[DVec3; 3]>,
    /// Level 3: the exact corners and the sign of their `yz` projection.
    exact_tris: Vec<([DVec3; 3], Sign)>,
}

fn yz(p: DVec3) -> DVec2 {
    DVec2::new(p.y, p.z)
}

impl Naive {
    fn new(mesh: &TriMesh) -> Naive {
        let corners: Vec<[DVec3; 3]> = mesh
            .tris
            .iter()
            .map(|t| t.map(|i| mesh.positions[i]))
            .collect();
        let bvh = Bvh::new(&corners);
        let sorted: Vec<[DVec3; 3]> = bvh.order.iter().map(|&i| corners[i]).collect();
        let grid = YzGrid::new(&sorted);
        let f32_tris = sorted
            .iter()
            .map(|&[a, b, c]| {
                let (a, b, c) = (a.as_vec3(), b.as_vec3(), c.as_vec3());
                [a, b - a, c - a]
            })
            .collect();
        let f64_tris = sorted.iter().map(|&[a, b, c]| [a, b - a, c - a]).collect();
        let exact_tris = sorted
            .iter()
            .map(|&[a, b, c]| ([a, b, c], orient2d(yz(a), yz(b), yz(c))))
            .collect();
        Naive {
            bvh,
            grid,
            f32_tris,
            f64_tris,
            exact_tris,
        }
    }

    /// Visits the candidate triangles of a ray: the `yz` grid cell of the
    /// origin for a `+x` ray (point classification), the BVH otherwise;
    /// `f` returns `false` to stop.
    #[inline]
    fn visit(&self, o: DVec3, d: DVec3, mut f: impl FnMut(usize) -> bool) {
        if d == DVec3::X {
            for &k in self.grid.candidates(yz(o)) {
                if !f(k) {
                    return;
                }
            }
        } else {
            self.bvh.traverse(o, d, f);
        }
    }

    /// Level 1: the number of Möller–Trumbore hits with `t > 0`, in `f32`.
    fn hits_f32(&self, o: DVec3, d: DVec3) -> usize {
        let (of, df) = (o.as_vec3(), d.as_vec3());
        let mut count = 0;
        self.visit(o, d, |k| {
            let [v0, e1, e2] = self.f32_tris[k];
            let p = df.cross(e2);
            let det = e1.dot(p);
            if det == 0.0 {
                return true;
            }
            let inv = 1.0 / det;
            let s = of - v0;
            let u = s.dot(p) * inv;
            if !(0.0..=1.0).contains(&u) {
                return true;
            }
            let q = s.cross(e1);
            let v = df.dot(q) * inv;
            if v < 0.0 || u + v > 1.0 {
                return true;
            }
            if e2.dot(q) * inv > 0.0 {
                count += 1;
            }
            true
        });
        count
    }

    /// Level 2: the Möller–Trumbore hits in `f64` with fixed epsilons: the
    /// number with `t > EPS_T`, and whether one had `|t| ≤ EPS_T`.
    fn hits_f64_eps(&self, o: DVec3, d: DVec3) -> (usize, bool) {
        let mut count = 0;
        let mut surface = false;
        self.visit(o, d, |k| {
            let [v0, e1, e2] = self.f64_tris[k];
            let p = d.cross(e2);
            let det = e1.dot(p);
            if det.abs() < EPS_DET {
                return true;
            }
            let inv = 1.0 / det;
            let s = o - v0;
            let u = s.dot(p) * inv;
            if !(0.0..=1.0).contains(&u) {
                return true;
            }
            let q = s.cross(e1);
            let v = d.dot(q) * inv;
            if v < 0.0 || u + v > 1.0 {
                return true;
            }
            let t = e2.dot(q) * inv;
            if t > EPS_T {
                count += 1;
            } else if t.abs() <= EPS_T {
                surface = true;
                return false;
            }
            true
        });
        (count, surface)
    }

    /// Level 3 for rays: exact signs, ties counted on every triangle
    /// touched, triangles coplanar with the ray skipped.
    fn hits_exact_naive(&self, o: DVec3, d: DVec3) -> usize {
        let mut count = 0;
        let dd = d.to_array();
        self.visit(o, d, |k| {
            let ([a, b, c], _) = self.exact_tris[k];
            let (u, v, w) = ((a - o).to_array(), (b - o).to_array(), (c - o).to_array());
            let signs = [
                line_side_filter_scalar(dd, u, v).unwrap_or_else(|| line_side(o, d, a, b)),
                line_side_filter_scalar(dd, v, w).unwrap_or_else(|| line_side(o, d, b, c)),
                line_side_filter_scalar(dd, w, u).unwrap_or_else(|| line_side(o, d, c, a)),
            ];
            let pos = signs.contains(&Sign::Positive);
            let neg = signs.contains(&Sign::Negative);
            if pos == neg {
                return true; // a miss, or the ray lies in the triangle's plane
            }
            let s = if pos { Sign::Positive } else { Sign::Negative };
            if orient3d(a, b, c, o) == -s {
                count += 1;
            }
            true
        });
        count
    }

    fn classify_f32(&self, p: DVec3) -> Containment {
        parity(self.hits_f32(p, DVec3::X))
    }

    fn classify_f64_eps(&self, p: DVec3) -> Containment {
        match self.hits_f64_eps(p, DVec3::X) {
            (_, true) => Containment::OnBoundary,
            (n, false) => parity(n),
        }
    }

    /// Level 3 for points: the library's `+x` parity test without its
    /// symbolic perturbation: a projected point on a projected edge or vertex
    /// counts for every triangle touching it.
    fn classify_exact_naive(&self, p: DVec3) -> Containment {
        let q = yz(p);
        let mut count = 0;
        let mut on = false;
        self.visit(p, DVec3::X, |k| {
            let ([a, b, c], sigma) = self.exact_tris[k];
            if sigma == Sign::Zero {
                if orient3d(a, b, c, p) == Sign::Zero
                    && coplanar_point_in_closed_triangle(a, b, c, p)
                {
                    on = true;
                    return false;
                }
                return true;
            }
            let (ya, yb, yc) = (yz(a), yz(b), yz(c));
            if orient2d(ya, yb, q) == -sigma
                || orient2d(yb, yc, q) == -sigma
                || orient2d(yc, ya, q) == -sigma
            {
                return true;
            }
            match orient3d(a, b, c, p) {
                Sign::Zero => {
                    on = true;
                    return false;
                }
                side if side == -sigma => count += 1,
                _ => {}
            }
            true
        });
        if on {
            Containment::OnBoundary
        } else {
            parity(count)
        }
    }
}

fn parity(crossings: usize) -> Containment {
    if crossings % 2 == 1 {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

/// One scene: a mesh with its library accel and its levels 1–3.
struct Scene {
    mesh: TriMesh,
    /// The mesh's triangles by their corners, for the exact reference.
    triangles: Vec<[DVec3; 3]>,
    accel: Accel,
    naive: Naive,
    /// The dyadic grid every coordinate is a multiple of.
    h: f64,
}

impl Scene {
    fn new(mesh: TriMesh, h: f64) -> Scene {
        let soup = PolygonSoup::new(mesh.positions.clone(), mesh.tris.clone());
        let solid = Solid::try_from_soup(&soup).expect("the generated mesh is a valid solid");
        let accel = Accel::new(&solid);
        assert!(accel.is_closed());
        let naive = Naive::new(&mesh);
        let triangles = mesh
            .tris
            .iter()
            .map(|t| t.map(|i| mesh.positions[i]))
            .collect();
        Scene {
            mesh,
            triangles,
            accel,
            naive,
            h,
        }
    }

    fn bounds(&self) -> (DVec3, DVec3) {
        let b = self.accel.bounds();
        (b.min, b.max)
    }

    /// The undirected edges of the triangles (fan diagonals included).
    fn edges(&self) -> Vec<(usize, usize)> {
        let mut e: Vec<(usize, usize)> = self
            .mesh
            .tris
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        e.sort_unstable();
        e.dedup();
        e
    }
}

/// A query point and, when it is on the boundary by construction, that fact.
#[derive(Clone, Copy)]
struct PointQuery {
    p: DVec3,
    on_by_construction: bool,
}

/// `x` moved by `k` ulps (`k ≠ 0`).
fn nudge(mut x: f64, k: i64) -> f64 {
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

/// `n` points exactly as made (on the boundary), and `n` of them moved 1–4
/// ulps along one random axis.
fn on_and_near(
    rng: &mut Rng,
    n: usize,
    mut make: impl FnMut(&mut Rng) -> DVec3,
) -> (Vec<PointQuery>, Vec<PointQuery>) {
    let on: Vec<PointQuery> = (0..n)
        .map(|_| PointQuery {
            p: make(rng),
            on_by_construction: true,
        })
        .collect();
    let near = on
        .iter()
        .map(|q| {
            let mut p = q.p;
            let axis = rng.below(3);
            let k = rng.int(1, 4) * if rng.below(2) == 0 { 1 } else { -1 };
            p[axis] = nudge(p[axis], k);
            PointQuery {
                p,
                on_by_construction: false,
            }
        })
        .collect();
    (on, near)
}

/// The point sets of a scene: generic; on, and 1–4 ulps off, faces, edges
/// and vertices.
fn point_sets(scene: &Scene, rng: &mut Rng) -> Vec<(&'static str, Vec<PointQuery>)> {
    let (lo, hi) = scene.bounds();
    let margin = (hi - lo) * 0.1;
    let generic = (0..POINTS)
        .map(|_| PointQuery {
            p: lo - margin
                + (hi - lo + 2.0 * margin) * DVec3::new(rng.unit(), rng.unit(), rng.unit()),
            on_by_construction: false,
        })
        .collect();
    let pos = &scene.mesh.positions;
    let tris = &scene.mesh.tris;
    // a + (b − a)·i/16 + (c − a)·j/16: every operation exact on the grid.
    let (on_faces, near_faces) = on_and_near(rng, POINTS / 2, |rng| {
        let [a, b, c] = tris[rng.below(tris.len())].map(|i| pos[i]);
        let i = rng.int(1, 14);
        let j = rng.int(1, 15 - i);
        a + ((b - a) * (i as f64 / 16.0) + (c - a) * (j as f64 / 16.0))
    });
    let edges = scene.edges();
    let (on_edges, near_edges) = on_and_near(rng, POINTS / 2, |rng| {
        let (a, b) = edges[rng.below(edges.len())];
        pos[a] + (pos[b] - pos[a]) * (rng.int(1, 15) as f64 / 16.0)
    });
    let (on_vertices, near_vertices) =
        on_and_near(rng, POINTS / 2, |rng| pos[rng.below(pos.len())]);
    vec![
        ("points: generic", generic),
        ("points: on faces", on_faces),
        ("points: 1-4 ulps off faces", near_faces),
        ("points: on edges", on_edges),
        ("points: 1-4 ulps off edges", near_edges),
        ("points: on vertices", on_vertices),
        ("points: 1-4 ulps off vertices", near_vertices),
    ]
}

/// The ray sets of a scene: generic, through vertices, along edges.
fn ray_sets(scene: &Scene, rng: &mut Rng) -> Vec<(&'static str, Vec<Ray>)> {
    let (lo, hi) = scene.bounds();
    let centre = (lo + hi) * 0.5;
    let radius = (hi - lo).length() * 0.5;
    let generic = (0..RAYS)
        .map(|_| {
            let dir = loop {
                let v = DVec3::new(rng.unit(), rng.unit(), rng.unit()) * 2.0 - 1.0;
                if v.length_squared() > 0.01 && v.length_squared() <= 1.0 {
                    break v.normalize();
                }
            };
            let origin = centre + dir * (2.5 * radius);
            let target = lo + (hi - lo) * DVec3::new(rng.unit(), rng.unit(), rng.unit());
            Ray::new(origin, target - origin)
        })
        .collect();
    // Directions with components that are multiples of `step` (a multiple of
    // the grid `h`): origin = v − 4d is exact, and the ray meets v at t = 4.
    let step = 2f64.powi(radius.log2().floor() as i32 - 6).max(scene.h);
    let pos = &scene.mesh.positions;
    let through_vertices = (0..RAYS)
        .map(|_| {
            let v = pos[rng.below(pos.len())];
            let d = loop {
                let d = DVec3::new(
                    rng.int(-64, 64) as f64,
                    rng.int(-64, 64) as f64,
                    rng.int(-64, 64) as f64,
                );
                if d != DVec3::ZERO {
                    break d * step;
                }
            };
            Ray::new(v - d * 4.0, d)
        })
        .collect();
    let edges = scene.edges();
    let along_edges = (0..RAYS)
        .map(|_| {
            let (mut a, mut b) = edges[rng.below(edges.len())];
            if rng.below(2) == 0 {
                std::mem::swap(&mut a, &mut b);
            }
            let d = pos[b] - pos[a];
            Ray::new(pos[a] - d * 2.0, d)
        })
        .collect();
    vec![
        ("rays: generic", generic),
        ("rays: through vertices", through_vertices),
        ("rays: along edges", along_edges),
    ]
}

/// One row of the table: wrong answers and time per query at each level.
#[derive(Clone)]
struct Row {
    name: String,
    queries: usize,
    wrong: [usize; 4],
    /// Nanoseconds per query.
    ns: [f64; 4],
}

impl Row {
    fn new(name: &str) -> Row {
        Row {
            name: name.to_string(),
            queries: 0,
            wrong: [0; 4],
            ns: [0.0; 4],
        }
    }

    /// Adds another batch (times weighted by query count).
    fn add(&mut self, queries: usize, wrong: [usize; 4], seconds: [f64; 4]) {
        for l in 0..4 {
            let total = self.ns[l] * self.queries as f64 + seconds[l] * 1e9;
            self.wrong[l] += wrong[l];
            self.ns[l] = total / (self.queries + queries) as f64;
        }
        self.queries += queries;
    }
}

/// Best-of-`REPEATS` wall time of `f` over all `items`, and its answers.
fn timed<T: Copy, A>(items: &[T], mut f: impl FnMut(T) -> A) -> (f64, Vec<A>) {
    let mut best = f64::INFINITY;
    let mut answers = Vec::new();
    for _ in 0..REPEATS {
        let start = Instant::now();
        answers = items.iter().map(|&x| black_box(f(black_box(x)))).collect();
        best = best.min(start.elapsed().as_secs_f64());
    }
    (best, answers)
}

/// Counts of reference checks: points on the boundary by construction the
/// reference did not call boundary (a check of the reference itself), and
/// how many rays had an exact crossing count of their own versus a tie
/// (judged by parity).
#[derive(Default)]
struct Checks {
    boundary_points: usize,
    boundary_mismatch: usize,
    rays_counted: usize,
    rays_tied: usize,
}

/// The reference class of a point: exact big-integer ray parity
/// (`tests/common/rational_parity.rs`), which shares no code with the
/// library.
fn reference_class(scene: &Scene, p: DVec3) -> Containment {
    match rational_parity::classify(&scene.triangles, p) {
        Class::Inside => Containment::Inside,
        Class::Outside => Containment::Outside,
        Class::Boundary => Containment::OnBoundary,
    }
}

/// What one set gave on one scene.
struct Batch {
    /// Wrong answers per level.
    wrong: [usize; 4],
    /// Best wall time over the set per level.
    seconds: [f64; 4],
    /// Exact-arithmetic fallbacks of the library's predicates per query, at
    /// levels 3 and 4.
    fallbacks: [f64; 2],
}

fn run_points(scene: &Scene, queries: &[PointQuery], checks: &mut Checks) -> Batch {
    let n = &scene.naive;
    let (t1, a1) = timed(queries, |q| n.classify_f32(q.p));
    let (t2, a2) = timed(queries, |q| n.classify_f64_eps(q.p));
    reset_exact_fallbacks();
    let (t3, a3) = timed(queries, |q| n.classify_exact_naive(q.p));
    let f3 = exact_fallbacks();
    reset_exact_fallbacks();
    let (t4, a4) = timed(queries, |q| {
        scene.accel.classify(q.p).expect("closed, finite")
    });
    let f4 = exact_fallbacks();
    let mut wrong = [0; 4];
    for (i, q) in queries.iter().enumerate() {
        let reference = reference_class(scene, q.p);
        if q.on_by_construction {
            checks.boundary_points += 1;
            if reference != Containment::OnBoundary {
                checks.boundary_mismatch += 1;
            }
        }
        for (l, a) in [a1[i], a2[i], a3[i], a4[i]].into_iter().enumerate() {
            wrong[l] += usize::from(a != reference);
        }
    }
    let per_query = |f: u64| f as f64 / (REPEATS * a4.len()) as f64;
    Batch {
        wrong,
        seconds: [t1, t2, t3, t4],
        fallbacks: [per_query(f3), per_query(f4)],
    }
}

fn run_rays(scene: &Scene, rays: &[Ray], checks: &mut Checks) -> Batch {
    let n = &scene.naive;
    let (t1, a1) = timed(rays, |r| n.hits_f32(r.origin, r.direction));
    let (t2, a2) = timed(rays, |r| n.hits_f64_eps(r.origin, r.direction).0);
    reset_exact_fallbacks();
    let (t3, a3) = timed(rays, |r| n.hits_exact_naive(r.origin, r.direction));
    let f3 = exact_fallbacks();
    reset_exact_fallbacks();
    let (t4, a4) = timed(rays, |r| {
        scene
            .accel
            .ray_crossings(&r)
            .expect("closed, valid ray")
            .hits
            .len()
    });
    let f4 = exact_fallbacks();
    let mut wrong = [0; 4];
    for (i, r) in rays.iter().enumerate() {
        // The exact count when the ray meets no edge or vertex; otherwise
        // the count depends on the tie rule and only its parity is judged,
        // against the origin's exact class.
        let judge: Box<dyn Fn(usize) -> bool> =
            match rational_parity::crossings(&scene.triangles, r.origin, r.direction) {
                Ok(count) => {
                    checks.rays_counted += 1;
                    Box::new(move |a| a != count)
                }
                Err(Degenerate::Tie | Degenerate::OnBoundary) => {
                    checks.rays_tied += 1;
                    let origin = reference_class(scene, r.origin);
                    Box::new(move |a| origin != Containment::OnBoundary && parity(a) != origin)
                }
            };
        for (l, a) in [a1[i], a2[i], a3[i], a4[i]].into_iter().enumerate() {
            wrong[l] += usize::from(judge(a));
        }
    }
    let per_query = |f: u64| f as f64 / (REPEATS * a4.len()) as f64;
    Batch {
        wrong,
        seconds: [t1, t2, t3, t4],
        fallbacks: [per_query(f3), per_query(f4)],
    }
}

/// The table as Markdown.
fn table(rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = write!(s, "| set | queries |");
    for l in LEVELS {
        let _ = write!(s, " {l}: wrong | ns/query |");
    }
    let _ = writeln!(s);
    let _ = writeln!(s, "|---|---:|{}", "---:|---:|".repeat(4));
    for r in rows {
        let _ = write!(s, "| {} | {} |", r.name, r.queries);
        for l in 0..4 {
            let pct = 100.0 * r.wrong[l] as f64 / r.queries as f64;
            let _ = write!(s, " {} ({pct:.1} %) | {:.0} |", r.wrong[l], r.ns[l]);
        }
        let _ = writeln!(s);
    }
    s
}

/// A two-panel horizontal bar chart: wrong answers (%) and ns per query
/// (log scale), one group of four bars (levels) per set.
fn svg(rows: &[Row]) -> String {
    const COLOURS: [&str; 4] = ["#d62728", "#ff7f0e", "#1f77b4", "#2ca02c"];
    let (label_w, panel_w, gap, bar_h, group_gap, top) = (210.0, 330.0, 60.0, 6.0, 10.0, 60.0);
    let group_h = 4.0 * bar_h + group_gap;
    let height = top + rows.len() as f64 * group_h + 60.0;
    let width = label_w + 2.0 * panel_w + gap + 20.0;
    let x_wrong = label_w;
    let x_time = label_w + panel_w + gap;
    let (log_lo, log_hi) = (1.0f64, 5.0f64); // 10 ns … 100 µs
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="11">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{x_wrong}" y="20" font-size="13" font-weight="bold">wrong answers (% of queries)</text>"#
    );
    let _ = writeln!(
        s,
        r#"<text x="{x_time}" y="20" font-size="13" font-weight="bold">time per query (ns, log scale, 1 thread)</text>"#
    );
    let _ = writeln!(
        s,
        r##"<text x="{x_wrong}" y="38" fill="#555">reference: exact big-integer ray parity and crossing counts, independent of every level</text>"##
    );
    // Grid lines and axis labels.
    let axis_y = top + rows.len() as f64 * group_h;
    for k in 0..=4 {
        let x = x_wrong + panel_w * f64::from(k) / 4.0;
        let _ = writeln!(
            s,
            r##"<line x1="{x}" y1="{}" x2="{x}" y2="{axis_y}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">{}</text>"##,
            top - 5.0,
            axis_y + 14.0,
            25 * k
        );
    }
    for e in 1..=5 {
        let x = x_time + panel_w * (f64::from(e) - log_lo) / (log_hi - log_lo);
        let _ = writeln!(
            s,
            r##"<line x1="{x}" y1="{}" x2="{x}" y2="{axis_y}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">1e{e}</text>"##,
            top - 5.0,
            axis_y + 14.0
        );
    }
    for (g, r) in rows.iter().enumerate() {
        let y0 = top + g as f64 * group_h;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="end">{}</text>"#,
            label_w - 8.0,
            y0 + 2.0 * bar_h + 4.0,
            r.name
        );
        for (l, colour) in COLOURS.iter().enumerate() {
            let y = y0 + l as f64 * bar_h;
            let pct = 100.0 * r.wrong[l] as f64 / r.queries as f64;
            let w = panel_w * pct / 100.0;
            let _ = writeln!(
                s,
                r#"<rect x="{x_wrong}" y="{y}" width="{w:.2}" height="{}" fill="{}"/>"#,
                bar_h - 1.0,
                colour
            );
            if pct > 0.0 {
                let _ = writeln!(
                    s,
                    r#"<text x="{:.2}" y="{}" font-size="7">{pct:.2}</text>"#,
                    x_wrong + w + 2.0,
                    y + bar_h - 1.0
                );
            }
            let lt = r.ns[l].max(10.0).log10().clamp(log_lo, log_hi);
            let w = panel_w * (lt - log_lo) / (log_hi - log_lo);
            let _ = writeln!(
                s,
                r#"<rect x="{x_time}" y="{y}" width="{w:.2}" height="{}" fill="{}"/><text x="{:.2}" y="{}" font-size="7">{:.0}</text>"#,
                bar_h - 1.0,
                colour,
                x_time + w + 2.0,
                y + bar_h - 1.0,
                r.ns[l]
            );
        }
    }
    // Legend.
    for (l, name) in LEVELS.iter().enumerate() {
        let x = label_w + l as f64 * 170.0;
        let y = axis_y + 32.0;
        let _ = writeln!(
            s,
            r#"<rect x="{x}" y="{}" width="12" height="10" fill="{}"/><text x="{}" y="{y}">{}. {name}</text>"#,
            y - 9.0,
            COLOURS[l],
            x + 16.0,
            l + 1
        );
    }
    let _ = writeln!(s, "</svg>");
    s
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/accuracy_vs_time.svg".to_string());
    let started = Instant::now();
    let sphere = icosphere(3);
    let prism = l_prism();
    // (label, scale, offset, grid h): the grid keeps constructions exact.
    let variants: [(&str, f64, f64, f64); 3] = [
        ("", 1.0, 0.0, 2f64.powi(-20)),
        ("offset 1e8", 1.0, 1e8, 2f64.powi(-20)),
        ("scaled 1e-8", 1e-8, 0.0, 2f64.powi(-47)),
    ];
    let mut rows: Vec<Row> = Vec::new();
    let mut checks = Checks::default();
    let mut detail = String::from(
        "| scene | set | queries | L1 wrong | ns | L2 wrong | ns | L3 wrong | ns | L4 wrong | ns | L3 exact fallbacks/query | L4 exact fallbacks/query |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    let mut rng = Rng::new(0x5EED_0006);
    for (label, scale, offset, h) in variants {
        let mut point_row = Row::new(&format!("points: all sets, {label}"));
        let mut ray_row = Row::new(&format!("rays: all sets, {label}"));
        for (mesh_name, base) in [("icosphere", &sphere), ("L-prism", &prism)] {
            let scene = Scene::new(transform(base, scale, offset, h), h);
            let mut batches: Vec<(&str, usize, Batch)> = Vec::new();
            for (name, q) in point_sets(&scene, &mut rng) {
                batches.push((name, q.len(), run_points(&scene, &q, &mut checks)));
            }
            for (name, r) in ray_sets(&scene, &mut rng) {
                batches.push((name, r.len(), run_rays(&scene, &r, &mut checks)));
            }
            for (name, n, batch) in batches {
                let _ = write!(
                    detail,
                    "| {} | {name} | {n} |",
                    format!("{mesh_name} {label}").trim()
                );
                for l in 0..4 {
                    let ns = batch.seconds[l] * 1e9 / n as f64;
                    let _ = write!(detail, " {} | {ns:.0} |", batch.wrong[l]);
                }
                let _ = writeln!(
                    detail,
                    " {:.2} | {:.2} |",
                    batch.fallbacks[0], batch.fallbacks[1]
                );
                let row = if !label.is_empty() && name.starts_with("points") {
                    &mut point_row
                } else if !label.is_empty() {
                    &mut ray_row
                } else {
                    row_mut(&mut rows, name)
                };
                row.add(n, batch.wrong, batch.seconds);
            }
        }
        if !label.is_empty() {
            rows.push(point_row);
            rows.push(ray_row);
        }
    }
    println!(
        "accuracy vs time: icosphere (1,280 triangles) and L-prism (20 triangles), \
         each as is, offset by 1e8 and scaled by 1e-8; one thread, best of {REPEATS}"
    );
    println!(
        "wrong = answer differs from the reference: exact big-integer ray parity for points, the exact \
         crossing count for rays (for a ray through an edge or vertex, whose count depends on the tie \
         rule: the count's parity against the origin's exact class); the reference shares no code \
         with the levels\n"
    );
    print!("{}", table(&rows));
    println!("\nper scene and set (L1–L4 = levels 1–4):\n");
    print!("{detail}");
    println!(
        "\nreference checks: the reference says boundary for {}/{} points on the boundary by construction; \
         {} rays had an exact crossing count, {} met an edge or a vertex (judged by parity)",
        checks.boundary_points - checks.boundary_mismatch,
        checks.boundary_points,
        checks.rays_counted,
        checks.rays_tied
    );
    if let Some(dir) = std::path::Path::new(&out).parent()
        && !dir.as_os_str().is_empty()
    {
        std::fs::create_dir_all(dir).expect("create the plot's directory");
    }
    std::fs::write(&out, svg(&rows)).expect("write the plot");
    println!(
        "plot written to {out}; total {:.1} s",
        started.elapsed().as_secs_f64()
    );
}

/// The row named `name`, appended if new.
fn row_mut<'a>(rows: &'a mut Vec<Row>, name: &str) -> &'a mut Row {
    if let Some(i) = rows.iter().position(|r| r.name == name) {
        &mut rows[i]
    } else {
        rows.push(Row::new(name));
        rows.last_mut().expect("just pushed")
    }
}
