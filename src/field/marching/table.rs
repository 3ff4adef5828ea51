//! The 256-entry case table, generated from the base cases by the cube's
//! 48 symmetries and, where the ambiguity rule allows, by complement.
//!
//! Generation, once per process:
//!
//! 1. Each base case's loops become triangles: a loop is oriented so that
//!    its vector area points at the outside corners (the sum over its
//!    crossed edges of `outside corner − inside corner`), then
//!    fan-triangulated from its first edge.
//! 2. Every symmetry maps a base configuration to another one; its
//!    triangles are mapped edge by edge, and reversed by a reflection.
//! 3. A base case without an ambiguous face also gives the complements of
//!    its images: the same surface, reversed (inside and outside swap).
//!    Cases with an ambiguous face are not complemented: their complements
//!    are base cases of their own ([`BASE_CASES`]).
//!
//! The tests check that every configuration is reached, that each entry is
//! a set of oriented disks, that its segments on each face follow the
//! ambiguity rule, and that two cells sharing a face run their segments on
//! it in opposite directions for every pair of configurations: together,
//! that the surface is closed, oriented and 2-manifold for any field.

use std::sync::OnceLock;

use super::base_cases::{BASE_CASES, BaseCase};
use super::cube::{EDGES, Symmetry, corner_coords, edge_between, has_ambiguous_face};

/// A triangle as three crossed edges, counter-clockwise seen from outside.
pub(crate) type EdgeTriangle = [u8; 3];

/// One configuration's triangles and the base case they came from.
#[derive(Clone, Debug, Default)]
pub(crate) struct Case {
    /// The triangles.
    pub(crate) triangles: Vec<EdgeTriangle>,
    /// The base case's name.
    pub(crate) base: &'static str,
}

/// The table: entry `config` (bit `c` set = corner `c` inside) is that
/// configuration's [`Case`].
pub(crate) struct CaseTable {
    cases: Vec<Case>,
}

impl CaseTable {
    /// The case of a configuration.
    pub(crate) fn case(&self, config: u8) -> &Case {
        &self.cases[usize::from(config)]
    }
}

/// The table, generated on first use.
pub(crate) fn case_table() -> &'static CaseTable {
    static TABLE: OnceLock<CaseTable> = OnceLock::new();
    TABLE.get_or_init(generate)
}

fn config_of(inside: &[u8]) -> u8 {
    inside.iter().fold(0, |acc, &c| acc | 1 << c)
}

fn generate() -> CaseTable {
    let mut cases: Vec<Option<Case>> = vec![None; 256];
    let based: Vec<(u8, &BaseCase, Vec<EdgeTriangle>)> = BASE_CASES
        .iter()
        .map(|b| {
            let config = config_of(b.inside);
            (config, b, triangulate(b, config))
        })
        .collect();
    for (config, base, triangles) in &based {
        for s in Symmetry::all() {
            let image = s.config(*config);
            let slot = &mut cases[usize::from(image)];
            if slot.is_none() {
                *slot = Some(Case {
                    triangles: map(triangles, s, s.reverses_orientation()),
                    base: base.name,
                });
            }
        }
    }
    for (config, base, triangles) in &based {
        if has_ambiguous_face(*config) {
            continue;
        }
        for s in Symmetry::all() {
            let image = !s.config(*config);
            let slot = &mut cases[usize::from(image)];
            if slot.is_none() {
                *slot = Some(Case {
                    triangles: map(triangles, s, !s.reverses_orientation()),
                    base: base.name,
                });
            }
        }
    }
    debug_assert!(
        cases.iter().all(Option::is_some),
        "a configuration is unreached"
    );
    CaseTable {
        cases: cases.into_iter().map(Option::unwrap_or_default).collect(),
    }
}

fn map(triangles: &[EdgeTriangle], s: Symmetry, reverse: bool) -> Vec<EdgeTriangle> {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|e| s.edge(e));
            if reverse { [a, c, b] } else { [a, b, c] }
        })
        .collect()
}

/// Twice an edge's midpoint, in integers.
pub(crate) fn doubled_midpoint(e: u8) -> [i32; 3] {
    let [a, b] = EDGES[usize::from(e)];
    let (pa, pb) = (corner_coords(a), corner_coords(b));
    [pa[0] + pb[0], pa[1] + pb[1], pa[2] + pb[2]]
}

/// `outside corner − inside corner` of a crossed edge of `config`.
pub(crate) fn outward(config: u8, e: u8) -> [i32; 3] {
    let [a, b] = EDGES[usize::from(e)];
    let (pa, pb) = (corner_coords(a), corner_coords(b));
    let sign = if config >> a & 1 == 1 { 1 } else { -1 };
    [0, 1, 2].map(|i| sign * (pb[i] - pa[i]))
}

fn cross(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [i32; 3], b: [i32; 3]) -> i32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A base case's triangles: each loop oriented toward the outside corners
/// and fanned from its first edge.
fn triangulate(base: &BaseCase, config: u8) -> Vec<EdgeTriangle> {
    let mut triangles = Vec::new();
    for corner_loop in base.loops {
        let mut edges: Vec<u8> = corner_loop
            .iter()
            .filter_map(|&[a, b]| edge_between(a, b))
            .collect();
        debug_assert_eq!(edges.len(), corner_loop.len(), "case {}", base.name);
        let points: Vec<[i32; 3]> = edges.iter().map(|&e| doubled_midpoint(e)).collect();
        let mut area = [0; 3];
        for i in 0..points.len() {
            let c = cross(points[i], points[(i + 1) % points.len()]);
            area = [area[0] + c[0], area[1] + c[1], area[2] + c[2]];
        }
        let out = edges.iter().fold([0; 3], |acc, &e| {
            let o = outward(config, e);
            [acc[0] + o[0], acc[1] + o[1], acc[2] + o[2]]
        });
        debug_assert_ne!(dot(area, out), 0, "case {}", base.name);
        if dot(area, out) < 0 {
            edges[1..].reverse();
        }
        for i in 1..edges.len() - 1 {
            triangles.push([edges[0], edges[i], edges[i + 1]]);
        }
    }
    triangles
}

#[cfg(test)]
mod tests {
    use std::collections::{BTreeSet, HashMap};

    use super::super::cube::{CubeFace, face_is_ambiguous};
    use super::*;

    fn crossed(config: u8, e: u8) -> bool {
        let [a, b] = EDGES[usize::from(e)];
        (config >> a & 1) != (config >> b & 1)
    }

    /// The directed boundary segments of a case (edges of its triangles
    /// whose reverse is not also there), after checking that every other
    /// edge appears exactly once in each direction.
    fn boundary(config: u8) -> Vec<(u8, u8)> {
        let mut count: HashMap<(u8, u8), i32> = HashMap::new();
        for t in &case_table().case(config).triangles {
            for i in 0..3 {
                *count.entry((t[i], t[(i + 1) % 3])).or_default() += 1;
            }
        }
        assert!(
            count.values().all(|&n| n == 1),
            "config {config:#010b}: an edge run twice the same way"
        );
        count
            .keys()
            .filter(|&&(a, b)| !count.contains_key(&(b, a)))
            .copied()
            .collect()
    }

    fn on_one_face(a: u8, b: u8) -> Option<CubeFace> {
        CubeFace::all().find(|f| f.holds_edge(a) && f.holds_edge(b))
    }

    #[test]
    fn every_configuration_is_reached_and_uses_exactly_its_crossed_edges() {
        let mut bases = BTreeSet::new();
        for config in 0..=255u8 {
            let case = case_table().case(config);
            bases.insert(case.base);
            let used: BTreeSet<u8> = case.triangles.iter().flatten().copied().collect();
            let expected: BTreeSet<u8> = (0..12).filter(|&e| crossed(config, e)).collect();
            assert_eq!(used, expected, "config {config:#010b} (case {})", case.base);
        }
        assert_eq!(bases.len(), 17);
    }

    #[test]
    fn segments_on_each_face_follow_the_ambiguity_rule() {
        for config in 0..=255u8 {
            let segments = boundary(config);
            for face in CubeFace::all() {
                let mut found: Vec<BTreeSet<u8>> = segments
                    .iter()
                    .filter(|&&(a, b)| face.holds_edge(a) && face.holds_edge(b))
                    .map(|&(a, b)| BTreeSet::from([a, b]))
                    .collect();
                found.sort();
                let cycle = face.cycle();
                let edge = |i: usize| edge_between(cycle[i % 4], cycle[(i + 1) % 4]).unwrap();
                let mut expected: Vec<BTreeSet<u8>> = if face_is_ambiguous(config, face) {
                    // Each inside corner cut off by its own segment.
                    (0..4)
                        .filter(|&i| config >> cycle[i] & 1 == 1)
                        .map(|i| BTreeSet::from([edge(i + 3), edge(i)]))
                        .collect()
                } else {
                    let crossings: BTreeSet<u8> =
                        (0..4).map(edge).filter(|&e| crossed(config, e)).collect();
                    if crossings.is_empty() {
                        Vec::new()
                    } else {
                        vec![crossings]
                    }
                };
                expected.sort();
                assert_eq!(found, expected, "config {config:#010b}, face {face:?}");
            }
            // Every boundary segment lies in a face; no fan diagonal does.
            for &(a, b) in &segments {
                assert!(on_one_face(a, b).is_some(), "config {config:#010b}");
            }
            for t in &case_table().case(config).triangles {
                for i in 0..3 {
                    let (a, b) = (t[i], t[(i + 1) % 3]);
                    if !segments.contains(&(a, b)) {
                        assert!(
                            on_one_face(a, b).is_none(),
                            "config {config:#010b}: diagonal {a}-{b} in a face"
                        );
                    }
                }
                let flat = CubeFace::all().any(|f| t.iter().all(|&e| f.holds_edge(e)));
                assert!(
                    !flat,
                    "config {config:#010b}: triangle {t:?} lies in a face"
                );
            }
        }
    }

    #[test]
    fn every_triangle_faces_the_outside_corners() {
        for config in 0..=255u8 {
            for t in &case_table().case(config).triangles {
                let p = t.map(doubled_midpoint);
                let n = cross(
                    [0, 1, 2].map(|i| p[1][i] - p[0][i]),
                    [0, 1, 2].map(|i| p[2][i] - p[0][i]),
                );
                let out = t.iter().fold([0; 3], |acc, &e| {
                    let o = outward(config, e);
                    [acc[0] + o[0], acc[1] + o[1], acc[2] + o[2]]
                });
                assert!(dot(n, out) > 0, "config {config:#010b}: triangle {t:?}");
            }
        }
    }

    /// Two cells sharing a face (the first's face `axis = 1`, the second's
    /// `axis = 0`) with the same four signs on it must run each common
    /// segment in opposite directions, for every pair of configurations.
    #[test]
    fn neighbouring_cells_run_shared_segments_in_opposite_directions() {
        for axis in 0..3 {
            let upper = CubeFace { axis, side: 1 };
            let lower = CubeFace { axis, side: 0 };
            let across = |e: u8| {
                let [a, b] = EDGES[usize::from(e)];
                edge_between(a ^ (1 << axis), b ^ (1 << axis)).unwrap()
            };
            for first in 0..=255u8 {
                let on_face: BTreeSet<(u8, u8)> = boundary(first)
                    .into_iter()
                    .filter(|&(a, b)| upper.holds_edge(a) && upper.holds_edge(b))
                    .map(|(a, b)| (across(b), across(a)))
                    .collect();
                for second in 0..=255u8 {
                    let agree = (0..8u8)
                        .filter(|&c| upper.holds_corner(c))
                        .all(|c| (first >> c & 1) == (second >> (c ^ (1 << axis)) & 1));
                    if !agree {
                        continue;
                    }
                    let theirs: BTreeSet<(u8, u8)> = boundary(second)
                        .into_iter()
                        .filter(|&(a, b)| lower.holds_edge(a) && lower.holds_edge(b))
                        .collect();
                    assert_eq!(
                        on_face, theirs,
                        "configs {first:#010b} / {second:#010b}, axis {axis}"
                    );
                }
            }
        }
    }
}
