//! Near-degenerate boolean cases, seeded: pairs of valid solids that meet
//! where rounding and merging are hardest — slits along faces, copies
//! turned by 1e-15 to 1e-9 rad, prisms whose vertices or edges lie exactly
//! on a box's faces, faces 0 to 2 ulps apart — each also moved far from the
//! origin. Shared by the stress test and the stress driver; each case is
//! reproducible from its family and seed alone.
#![allow(dead_code)]

use glam::{DAffine3, DQuat, DVec3};
use wingedge::mesh::{Solid, builders};

/// A pair of operands and how they were made.
pub struct Case {
    /// The family and its parameters, for a failure message.
    pub name: String,
    /// The first operand.
    pub a: Solid,
    /// The second operand.
    pub b: Solid,
}

/// The families, by name: `case(k, seed)` makes one of family `k`.
pub const FAMILIES: [&str; 5] = ["slit", "turned", "prism_on_faces", "ulps_apart", "far"];

/// One case of family `family` (an index into [`FAMILIES`]) from `seed`.
pub fn case(family: usize, seed: u64) -> Case {
    let mut rng = Rng::new(seed);
    match family % FAMILIES.len() {
        0 => slit(&mut rng),
        1 => turned(&mut rng),
        2 => prism_on_faces(&mut rng),
        3 => ulps_apart(&mut rng),
        _ => far(&mut rng),
    }
}

/// xorshift64 with a few helpers (the tests' generator, kept here so the
/// cases do not depend on how a test crate includes `test_rng`).
pub struct Rng(u64);

impl Rng {
    /// A generator from `seed` (any: zero is replaced).
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next(&mut self) -> u64 {
        let mut s = self.0;
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        self.0 = s;
        s
    }
    /// Uniform in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `lo..hi` (integers).
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + (self.next() % (hi - lo) as u64) as i64
    }
    /// One of `items`.
    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[self.int(0, items.len() as i64) as usize]
    }
    /// A multiple of 1/8 in `[lo, hi]`: exact, so points built from it lie
    /// exactly where they are meant to.
    pub fn eighth(&mut self, lo: f64, hi: f64) -> f64 {
        let (a, b) = ((lo * 8.0).ceil() as i64, (hi * 8.0).floor() as i64);
        self.int(a, b + 1) as f64 / 8.0
    }
    /// A uniformly random unit vector.
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                2.0 * self.unit() - 1.0,
                2.0 * self.unit() - 1.0,
                2.0 * self.unit() - 1.0,
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

fn cuboid(min: DVec3, max: DVec3) -> Solid {
    builders::cuboid(min, max).expect("a cuboid")
}

/// `s` with every vertex mapped by `map` (rounded); mirrors are built from
/// the soup with the polygons turned.
pub fn moved(s: &Solid, map: DAffine3) -> Solid {
    let mut out = s.clone();
    if out.move_by(map) {
        return out;
    }
    let mut soup = s.to_soup();
    for p in &mut soup.positions {
        *p = map.transform_point3(*p);
    }
    if map.matrix3.determinant() < 0.0 {
        for polygon in &mut soup.polygons {
            polygon.vertices.reverse();
        }
    }
    Solid::try_from_soup(&soup).expect("a moved solid")
}

/// One of the 48 symmetries of the cube `[0, s]³` (axes permuted and
/// reflected), exact: a case built against one face is moved onto any.
fn cube_symmetry(rng: &mut Rng, s: f64) -> DAffine3 {
    let perm = rng.pick(&[
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ]);
    let mut cols = [DVec3::ZERO; 3];
    let mut shift = DVec3::ZERO;
    for (from, &to) in perm.iter().enumerate() {
        let flip = rng.int(0, 2) == 1;
        let mut c = DVec3::ZERO;
        c[to] = if flip { -1.0 } else { 1.0 };
        if flip {
            shift[to] = s;
        }
        cols[from] = c;
    }
    DAffine3::from_cols(cols[0], cols[1], cols[2], shift)
}

/// A triangular prism whose edge `p → q` lies in the plane `z = top`, its
/// body on the side `side` (−1 below, +1 above), `width` and `depth` its
/// cross-section's half base and height.
fn edge_prism(p: DVec3, q: DVec3, width: f64, depth: f64, side: f64) -> Solid {
    let d = q - p;
    let across = DVec3::new(-d.y, d.x, 0.0).normalize() * width;
    let down = DVec3::new(0.0, 0.0, side * depth);
    let profile = [p, p + down + across, p + down - across];
    builders::prism(&profile, d).expect("an edge prism")
}

/// A box with a triangular prism whose edge lies on its top face, from a
/// point inside the face to a point outside it, on its boundary, at a
/// corner or inside it; the prism's body inside the box (a groove that
/// opens along a slit) or outside (a fin that touches along it).
fn slit(rng: &mut Rng) -> Case {
    let s = rng.pick(&[1.0, 2.0, 4.0]);
    let a = cuboid(DVec3::ZERO, DVec3::splat(s));
    let p = DVec3::new(
        rng.eighth(0.125, s - 0.125),
        rng.eighth(0.125, s - 0.125),
        s,
    );
    let end = rng.int(0, 4);
    let q = match end {
        // Outside the face.
        0 => DVec3::new(rng.eighth(s + 0.25, s + 1.0), rng.eighth(-0.5, s + 0.5), s),
        // A corner of the face.
        1 => DVec3::new(rng.pick(&[0.0, s]), rng.pick(&[0.0, s]), s),
        // A point on an edge of the face.
        2 => DVec3::new(rng.pick(&[0.0, s]), rng.eighth(0.125, s - 0.125), s),
        // Inside the face.
        _ => DVec3::new(
            rng.eighth(0.125, s - 0.125),
            rng.eighth(0.125, s - 0.125),
            s,
        ),
    };
    let q = if q == p {
        p + DVec3::new(0.125, 0.0, 0.0)
    } else {
        q
    };
    let side = rng.pick(&[-1.0, 1.0]);
    let width = rng.pick(&[0.125, 0.25, 0.5]);
    let depth = rng.pick(&[0.25, 0.5, s / 2.0]);
    let b = edge_prism(p, q, width, depth, side);
    let symmetry = cube_symmetry(rng, s);
    Case {
        name: format!("slit s={s} p={p} q={q} end={end} side={side} width={width} depth={depth}"),
        a: moved(&a, symmetry),
        b: moved(&b, symmetry),
    }
}

/// A solid and a copy of it turned by 1e-15 to 1e-9 rad about a random
/// axis through its centre or a corner.
fn turned(rng: &mut Rng) -> Case {
    let (a, kind) = match rng.int(0, 5) {
        0 => (cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)), "cube"),
        1 => (builders::octahedron(), "octahedron"),
        2 => (builders::icosahedron(), "icosahedron"),
        3 => (builders::l_prism(), "l_prism"),
        _ => (builders::sphere(4), "sphere(4)"),
    };
    let angle = 10f64.powf(-15.0 + 6.0 * rng.unit());
    let axis = if rng.int(0, 2) == 0 {
        rng.direction()
    } else {
        rng.pick(&[DVec3::X, DVec3::Y, DVec3::Z])
    };
    let pivot = if rng.int(0, 2) == 0 {
        DVec3::ZERO
    } else {
        DVec3::splat(1.0)
    };
    let turn = DAffine3::from_translation(pivot)
        * DAffine3::from_quat(DQuat::from_axis_angle(axis, angle))
        * DAffine3::from_translation(-pivot);
    Case {
        name: format!("turned {kind} by {angle:e} rad about {axis} through {pivot}"),
        b: moved(&a, turn),
        a,
    }
}

/// A unit box and a prism along one axis whose cross-section has its
/// corners on the box's sides (a 4-segment cylinder of radius 0.5 is one),
/// some inside or outside; through the box, or with a cap in a face.
fn prism_on_faces(rng: &mut Rng) -> Case {
    let a = cuboid(DVec3::ZERO, DVec3::ONE);
    let n = rng.int(3, 9) as usize;
    // Corners at angles around the centre, each on the square's boundary
    // (scaled by 1), a little inside (0.75) or outside (1.25), exactly.
    let mut corners = Vec::with_capacity(n);
    let turn = rng.unit();
    for k in 0..n {
        let t = (turn + k as f64 / n as f64) * std::f64::consts::TAU;
        let (c, s) = (t.cos(), t.sin());
        let on_boundary = 0.5 / c.abs().max(s.abs());
        let scale = rng.pick(&[1.0, 1.0, 1.0, 0.75, 1.25]);
        let snap = |x: f64| (x * 64.0).round() / 64.0;
        let (mut x, mut y) = (0.5 + c * on_boundary, 0.5 + s * on_boundary);
        if scale == 1.0 {
            // Exactly on a side: the coordinate that reached it stays 0 or 1.
            if c.abs() >= s.abs() {
                y = snap(y);
            } else {
                x = snap(x);
            }
        } else {
            x = snap(0.5 + (x - 0.5) * scale);
            y = snap(0.5 + (y - 0.5) * scale);
        }
        corners.push(DVec3::new(x, y, 0.0));
    }
    if rng.int(0, 3) == 0 {
        // Manifold's 4-segment cylinder of radius 0.5 through the cube.
        corners = vec![
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(1.0, 0.5, 0.0),
            DVec3::new(0.5, 1.0, 0.0),
            DVec3::new(0.0, 0.5, 0.0),
        ];
    }
    corners.dedup();
    let (z0, z1) = rng.pick(&[
        (-0.5, 1.5),
        (0.0, 1.0),
        (0.25, 1.0),
        (-0.5, 0.5),
        (0.0, 1.5),
    ]);
    for c in &mut corners {
        c.z = z0;
    }
    let b = builders::prism(&corners, DVec3::new(0.0, 0.0, z1 - z0));
    let b = match b {
        Ok(b) => b,
        Err(_) => cuboid(DVec3::new(0.25, 0.25, z0), DVec3::new(0.75, 0.75, z1)),
    };
    let symmetry = cube_symmetry(rng, 1.0);
    Case {
        name: format!("prism on faces: corners {corners:?}, z {z0}..{z1}"),
        a: moved(&a, symmetry),
        b: moved(&b, symmetry),
    }
}

/// `x` moved by `k` units in the last place.
fn ulps(x: f64, k: i64) -> f64 {
    let mut y = x;
    for _ in 0..k.abs() {
        y = if k > 0 { y.next_up() } else { y.next_down() };
    }
    y
}

/// Two boxes whose faces are 0, 1 or 2 units in the last place apart, or
/// one box shifted by a few ulps along one axis.
fn ulps_apart(rng: &mut Rng) -> Case {
    let lo = DVec3::new(
        rng.pick(&[0.0, 0.5, -1.0]),
        rng.pick(&[0.0, 0.5]),
        rng.pick(&[0.0, 0.25]),
    );
    let hi = lo + DVec3::new(rng.pick(&[1.0, 0.75]), 1.0, rng.pick(&[1.0, 2.0]));
    let a = cuboid(lo, hi);
    let (mut blo, mut bhi) = (lo, hi);
    for axis in 0..3 {
        if rng.int(0, 2) == 0 {
            blo[axis] = ulps(lo[axis], rng.int(-2, 3));
        } else {
            blo[axis] = lo[axis] + rng.pick(&[0.25, 0.5]);
        }
        bhi[axis] = ulps(hi[axis], rng.int(-2, 3));
        if blo[axis] >= bhi[axis] {
            blo[axis] = lo[axis];
        }
    }
    Case {
        name: format!("ulps apart: {lo}..{hi} and {blo}..{bhi}"),
        a,
        b: cuboid(blo, bhi),
    }
}

/// A case of the other families moved by a large offset (1e3 … 1e12)
/// and scaled by a power of two: decisions must not depend on where the
/// model sits.
fn far(rng: &mut Rng) -> Case {
    let family = rng.int(0, 4) as usize;
    let inner = case(family, rng.next());
    let offset = DVec3::new(
        10f64.powi(rng.int(3, 13) as i32),
        rng.pick(&[0.0, 1e8, -3e5]),
        rng.pick(&[0.0, 7.0]),
    );
    let scale = 2f64.powi(rng.int(-3, 4) as i32);
    let map = DAffine3::from_translation(offset) * DAffine3::from_scale(DVec3::splat(scale));
    Case {
        name: format!("far ({offset}, ×{scale}): {}", inner.name),
        a: moved(&inner.a, map),
        b: moved(&inner.b, map),
    }
}

/// The four operators a case is evaluated with (`B − A` as the reverse
/// difference).
pub const OPERATORS: [wingedge::SetOp; 4] = [
    wingedge::SetOp::Union,
    wingedge::SetOp::Intersection,
    wingedge::SetOp::Difference,
    wingedge::SetOp::ReverseDifference,
];

/// What checking one case found.
pub enum Checked {
    /// Every boolean succeeded, its written file validates, and the
    /// volumes add up; the number of booleans run.
    Passed(usize),
    /// An operand is not a valid solid (possible only for the cases moved
    /// far, where rounding the move can bend a face): nothing to check.
    InvalidOperand(String),
}

/// Runs the four booleans of `case`; each result, written as OBJ and read
/// back, must be valid (or the empty solid), and the volumes must add up:
/// `V(A ∪ B) + V(A ∩ B) = V(A) + V(B)` and `V(A − B) + V(A ∩ B) = V(A)`,
/// to `1e-9` of the operands' volume.
///
/// # Errors
///
/// The first failure, naming the case, the operator and what failed.
pub fn check(case: &Case) -> Result<Checked, String> {
    use wingedge::boolean::{BooleanOptions, boolean};
    use wingedge::validate::{Options, Validity, validate_soup};
    for (name, s) in [("A", &case.a), ("B", &case.b)] {
        let report = validate_soup(&s.to_soup(), None, &Options::default())
            .map_err(|e| format!("{}: operand {name}: {e}", case.name))?;
        if report.validity != Validity::ValidSolid {
            return Ok(Checked::InvalidOperand(format!(
                "{}: operand {name} is {}",
                case.name,
                report.validity.describe()
            )));
        }
    }
    let mut volumes = [0.0; 4];
    for (k, op) in OPERATORS.into_iter().enumerate() {
        let fail = |what: String| format!("{}: {}: {what}", case.name, op.name());
        let result = boolean(&case.a, &case.b, op, BooleanOptions::default())
            .map_err(|e| fail(format!("refused: {e}")))?;
        let text = wingedge::io::to_obj_string(&result.solid);
        let read = wingedge::io::import_obj_bytes(
            std::path::Path::new("result.obj"),
            text.as_bytes(),
            &wingedge::io::ObjOptions::default(),
        );
        let empty = result.solid.face_count() == 0;
        match read {
            Ok(import) => {
                let report = wingedge::validate::validate_import(&import, &Options::default())
                    .map_err(|e| fail(format!("the written file: {e}")))?;
                let fine = if empty {
                    report.validity == Validity::Empty
                } else {
                    report.validity == Validity::ValidSolid
                };
                if !fine {
                    let first: Vec<String> = report
                        .violations
                        .iter()
                        .take(3)
                        .map(|v| v.message.clone())
                        .collect();
                    return Err(fail(format!(
                        "the written file is {}: {}",
                        report.validity.describe(),
                        first.join("; ")
                    )));
                }
            }
            Err(e) => return Err(fail(format!("the written file cannot be read: {e}"))),
        }
        volumes[k] = result.solid.volume();
    }
    let [union, intersection, a_minus_b, b_minus_a] = volumes;
    let (va, vb) = (case.a.volume(), case.b.volume());
    // The exact volumes add up; the written ones may differ by what
    // rounding each point to `f64` moves the surface: under an ulp of the
    // largest coordinate (a few, where a feature smaller than `f64` holds
    // was collapsed) times the area, for each of two results.
    let largest = [&case.a, &case.b]
        .iter()
        .flat_map(|s| s.vertices().map(|(_, v)| v.position.abs().max_element()))
        .fold(0.0f64, f64::max);
    let ulp = largest.next_up() - largest;
    let limit = 1e-9 * (va + vb) + 8.0 * ulp * (case.a.surface_area() + case.b.surface_area());
    let sums = [
        (
            "V(A∪B) + V(A∩B) − V(A) − V(B)",
            union + intersection - va - vb,
        ),
        ("V(A−B) + V(A∩B) − V(A)", a_minus_b + intersection - va),
        ("V(B−A) + V(A∩B) − V(B)", b_minus_a + intersection - vb),
    ];
    for (what, gap) in sums {
        if gap.abs() > limit || !gap.is_finite() {
            return Err(format!(
                "{}: {what} = {gap:e} (limit {limit:e}; volumes ∪ {union}, ∩ {intersection}, A−B {a_minus_b}, B−A {b_minus_a}, A {va}, B {vb})",
                case.name
            ));
        }
    }
    Ok(Checked::Passed(OPERATORS.len()))
}
