//! Euler operators: random legal sequences keep every invariant and the
//! Euler–Poincaré formula after each step, each operator followed by its
//! inverse restores the store, and refused operators change nothing.

use std::collections::BTreeSet;

use glam::DVec3;
use proptest::prelude::*;
use wingedge::geom::Plane;
use wingedge::mesh::{
    Corner, Edge, EdgeId, EdgeUse, EulerError, FaceAttributes, FaceId, LoopId, LoopStart, Solid,
    Vertex, VertexId, builders,
};

/// A loop by its content: the lone vertex, or its uses from the smallest.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum LoopContent {
    Lone(VertexId),
    Cycle(Vec<EdgeUse>),
}

/// The whole store, with loops compared by their content (the use a walk
/// starts from, and the id of a loop made anew, are not compared).
#[derive(Debug, PartialEq)]
struct Snapshot {
    vertices: Vec<(VertexId, Vertex)>,
    edges: Vec<(EdgeId, Edge)>,
    faces: Vec<FaceSnapshot>,
    loop_count: usize,
}

#[derive(Debug, PartialEq)]
struct FaceSnapshot {
    id: FaceId,
    plane: Option<Plane>,
    attributes: FaceAttributes,
    outer: LoopContent,
    rings: BTreeSet<LoopContent>,
}

fn content(solid: &Solid, l: LoopId) -> LoopContent {
    match solid.loop_record(l).start {
        LoopStart::Vertex(v) => LoopContent::Lone(v),
        LoopStart::Edge(_) => {
            let mut uses: Vec<EdgeUse> = solid.loop_uses(l).collect();
            let first = (0..uses.len()).min_by_key(|&i| uses[i]).unwrap();
            uses.rotate_left(first);
            LoopContent::Cycle(uses)
        }
    }
}

fn snapshot(solid: &Solid) -> Snapshot {
    Snapshot {
        vertices: solid.vertices().map(|(id, v)| (id, v.clone())).collect(),
        edges: solid.edges().map(|(id, e)| (id, e.clone())).collect(),
        faces: solid
            .faces()
            .map(|(id, f)| FaceSnapshot {
                id,
                plane: f.plane,
                attributes: f.attributes.clone(),
                outer: content(solid, f.outer),
                rings: f.rings.iter().map(|&r| content(solid, r)).collect(),
            })
            .collect(),
        loop_count: solid.loop_count(),
    }
}

/// A random solid being edited, with the handles (`H`) the operators made.
struct Model {
    solid: Solid,
    handles: i64,
    applied: usize,
    inverted: usize,
    /// Applied operators by kind (the `op % 12` of a step).
    by_kind: [usize; 12],
}

/// `V − E + F − R = 2 (S − H)`, with `S` from the face adjacency.
fn euler_poincare(model: &Model) {
    let s = &model.solid;
    let shells = s.shells().len() as i64;
    assert_eq!(
        s.euler_characteristic(),
        2 * (shells - model.handles),
        "V {} E {} F {} R {} S {shells} H {}",
        s.vertex_count(),
        s.edge_count(),
        s.face_count(),
        s.ring_count(),
        model.handles
    );
    assert_eq!(
        s.shells().iter().map(|sh| sh.ring_count).sum::<usize>(),
        s.ring_count()
    );
}

/// The inverse of an applied operator, to run on the solid.
type Undo = Box<dyn FnOnce(&mut Solid) -> Result<(), EulerError>>;

/// One step of a script: which operator, three choices, a position.
type Step = (u8, u32, u32, u32, bool, [i8; 3]);

fn pick<T: Copy>(items: &[T], choice: u32) -> Option<T> {
    (!items.is_empty()).then(|| items[choice as usize % items.len()])
}

fn corners_of_loop(solid: &Solid, l: LoopId) -> Vec<Corner> {
    match solid.loop_record(l).start {
        LoopStart::Vertex(_) => vec![Corner::Lone(l)],
        LoopStart::Edge(_) => solid.loop_uses(l).map(Corner::After).collect(),
    }
}

fn all_loops(solid: &Solid) -> Vec<LoopId> {
    solid.loops().map(|(id, _)| id).collect()
}

fn random_corner(solid: &Solid, a: u32, b: u32) -> Option<Corner> {
    let l = pick(&all_loops(solid), a)?;
    pick(&corners_of_loop(solid, l), b)
}

/// A second corner on the same face: on the same loop for even `a`, on any
/// loop of the face otherwise.
fn second_corner(solid: &Solid, first: Corner, a: u32, b: u32) -> Option<Corner> {
    let face = match first {
        Corner::After(u) => solid.use_face(u)?,
        Corner::Lone(l) => solid.loop_record(l).face,
    };
    let loops: Vec<LoopId> = solid.face_loops(face).collect();
    let l = if a.is_multiple_of(2) {
        match first {
            Corner::Lone(l) => l,
            Corner::After(u) => *loops
                .iter()
                .find(|&&l| corners_of_loop(solid, l).contains(&Corner::After(u)))?,
        }
    } else {
        pick(&loops, a / 2)?
    };
    pick(&corners_of_loop(solid, l), b)
}

fn position(p: [i8; 3]) -> DVec3 {
    DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
}

/// Applies one step; refused operators must leave the store unchanged; an
/// applied one must keep every invariant, and (when `invert`) its inverse
/// must restore the store.
fn step(model: &mut Model, (op, a, b, c, invert, p): Step) {
    let before = snapshot(&model.solid);
    let handles_before = model.handles;
    let shells_before = model.solid.shells().len();
    let solid = &mut model.solid;
    let edges: Vec<EdgeId> = solid.edges().map(|(id, _)| id).collect();
    let vertices: Vec<VertexId> = solid.vertices().map(|(id, _)| id).collect();
    let faces: Vec<FaceId> = solid.faces().map(|(id, _)| id).collect();
    // The inverse to try, when the operator applies.
    let mut undo: Option<Undo> = None;
    let result: Result<(), EulerError> = match op % 12 {
        0 => solid.mvfs(position(p)).map(|(_, f)| {
            undo = Some(Box::new(move |s: &mut Solid| s.kvfs(f)));
        }),
        1 => match pick(&faces, a) {
            Some(f) => solid.kvfs(f),
            None => return,
        },
        2 => match random_corner(solid, a, b) {
            Some(corner) => solid.mev(corner, position(p)).map(|(e, v)| {
                undo = Some(Box::new(move |s: &mut Solid| s.kev(e, v)));
            }),
            None => return,
        },
        3 => match pick(&edges, a) {
            Some(e) => {
                let ends = solid.edge_vertices(e);
                solid.kev(e, ends[b as usize % 2])
            }
            None => return,
        },
        4 => {
            let Some(from) = random_corner(solid, a, b) else {
                return;
            };
            let Some(to) = second_corner(solid, from, c, b.rotate_left(7)) else {
                return;
            };
            solid.mef(from, to).map(|(e, f)| {
                undo = Some(Box::new(move |s: &mut Solid| s.kef(e, f)));
            })
        }
        5 => match pick(&edges, a) {
            Some(e) => {
                let faces: Vec<FaceId> = solid.edge_faces(e).collect();
                solid.kef(e, faces[b as usize % faces.len()])
            }
            None => return,
        },
        6 => match pick(&edges, a) {
            Some(e) => solid.kemr(e).map(|_| ()),
            None => return,
        },
        7 => {
            let Some(from) = random_corner(solid, a, b) else {
                return;
            };
            let Some(to) = second_corner(solid, from, c | 1, b.rotate_left(7)) else {
                return;
            };
            solid.mekr(from, to).map(|e| {
                undo = Some(Box::new(move |s: &mut Solid| s.kemr(e).map(|_| ())));
            })
        }
        8 => match (pick(&faces, a), pick(&faces, b)) {
            (Some(keep), Some(kill)) => solid.kfmrh(keep, kill).map(|_| ()),
            _ => return,
        },
        9 => {
            let rings: Vec<LoopId> = solid.faces().flat_map(|(_, f)| f.rings.clone()).collect();
            match pick(&rings, a) {
                Some(r) => {
                    let old = solid.loop_record(r).face;
                    solid.mfkrh(r).map(|f| {
                        undo = Some(Box::new(move |s: &mut Solid| s.kfmrh(old, f).map(|_| ())));
                    })
                }
                None => return,
            }
        }
        10 => match pick(&edges, a) {
            Some(e) => solid.split_edge(e, position(p)).map(|(v, _)| {
                undo = Some(Box::new(move |s: &mut Solid| s.join_edges(v).map(|_| ())));
            }),
            None => return,
        },
        _ => match pick(&vertices, a) {
            Some(v) => solid.join_edges(v).map(|_| ()),
            None => return,
        },
    };
    match result {
        Err(_) => {
            assert_eq!(
                snapshot(&model.solid),
                before,
                "a refused operator changed the store"
            );
            return;
        }
        Ok(()) => {
            model.applied += 1;
            model.by_kind[usize::from(op % 12)] += 1;
        }
    }
    if let Err(e) = model.solid.check_consistency() {
        panic!("operator {} broke the store: {e}", op % 12);
    }
    // kfmrh / mfkrh change either the shells or the handles.
    let shells_after = model.solid.shells().len();
    match op % 12 {
        8 if shells_after == shells_before => model.handles += 1,
        9 if shells_after == shells_before => model.handles -= 1,
        _ => {}
    }
    euler_poincare(model);
    if let (true, Some(undo)) = (invert, undo) {
        undo(&mut model.solid).expect("the inverse applies");
        assert_eq!(
            snapshot(&model.solid),
            before,
            "the inverse of {} differs",
            op % 12
        );
        model.handles = handles_before;
        model.inverted += 1;
        model.solid.check_consistency().unwrap();
        euler_poincare(model);
    }
}

/// Where a script starts: one lone vertex, a cube, or a frame (a solid
/// with a through hole and faces with rings).
#[derive(Clone, Copy, Debug)]
enum Start {
    Vertex,
    Cube,
    Frame,
}

fn run(script: &[Step], start: Start) -> Model {
    let mut model = Model {
        solid: match start {
            Start::Vertex => Solid::default(),
            Start::Cube => builders::cube(),
            Start::Frame => builders::frame(),
        },
        handles: i64::from(matches!(start, Start::Frame)),
        applied: 0,
        inverted: 0,
        by_kind: [0; 12],
    };
    if let Start::Vertex = start {
        model.solid.mvfs(DVec3::ZERO).unwrap();
    }
    euler_poincare(&model);
    for &s in script {
        step(&mut model, s);
    }
    model
}

fn step_strategy() -> impl Strategy<Value = Step> {
    (
        prop_oneof![
            // Weighted towards the operators that grow the solid, so that
            // the killers find something to kill.
            3 => Just(2u8), 3 => Just(4u8), 2 => Just(10u8), 1 => Just(0u8),
            1 => Just(1u8), 1 => Just(3u8), 1 => Just(5u8), 1 => Just(6u8),
            1 => Just(7u8), 1 => Just(8u8), 1 => Just(9u8), 1 => Just(11u8),
        ],
        any::<u32>(),
        any::<u32>(),
        any::<u32>(),
        any::<bool>(),
        any::<[i8; 3]>(),
    )
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(64)))]

    #[test]
    fn random_operator_sequences_keep_the_invariants(
        script in prop::collection::vec(step_strategy(), 1..150),
        start in prop_oneof![Just(Start::Vertex), Just(Start::Cube), Just(Start::Frame)],
    ) {
        run(&script, start);
    }
}

/// The same driver on a fixed script, to pin how much it exercises: thousands
/// of applied operators, hundreds of them undone by their inverse.
#[test]
fn a_long_fixed_sequence_applies_thousands_of_operators() {
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let weights = [
        2u8, 2, 2, 4, 4, 4, 4, 4, 4, 10, 10, 0, 1, 3, 5, 6, 7, 8, 9, 11,
    ];
    let script: Vec<Step> = (0..6000)
        .map(|_| {
            let r = next();
            (
                weights[(r % weights.len() as u64) as usize],
                (r >> 8) as u32,
                (r >> 24) as u32,
                (r >> 40) as u32,
                r & (1 << 63) != 0,
                [(r >> 3) as i8, (r >> 17) as i8, (r >> 33) as i8],
            )
        })
        .collect();
    let model = run(&script, Start::Vertex);
    eprintln!(
        "applied {} (by kind {:?}), inverted {}; final V {} E {} F {} R {} S {} H {}",
        model.applied,
        model.by_kind,
        model.inverted,
        model.solid.vertex_count(),
        model.solid.edge_count(),
        model.solid.face_count(),
        model.solid.ring_count(),
        model.solid.shells().len(),
        model.handles
    );
    assert!(
        model.by_kind.iter().all(|&n| n > 0),
        "every operator applies at least once: {:?}",
        model.by_kind
    );
    assert!(
        model.applied >= 2000,
        "only {} operators applied",
        model.applied
    );
    assert!(
        model.inverted >= 500,
        "only {} inverses checked",
        model.inverted
    );
}

/// Stale ids and ids issued by another solid are refused with the id named,
/// and the solid is unchanged.
#[test]
fn stale_and_foreign_ids_are_refused() {
    let mut solid = builders::cube();
    let face = solid.faces().next().unwrap().0;
    let corner = solid
        .corner(face, solid.face_vertices(face).next().unwrap())
        .unwrap();
    let (edge, vertex) = solid.mev(corner, DVec3::ZERO).unwrap();
    solid.kev(edge, vertex).unwrap();
    let before = snapshot(&solid);
    assert_eq!(solid.kev(edge, vertex), Err(EulerError::UnknownEdge(edge)));
    assert_eq!(
        solid.split_edge(edge, DVec3::ZERO),
        Err(EulerError::UnknownEdge(edge))
    );
    assert_eq!(
        solid.join_edges(vertex),
        Err(EulerError::UnknownVertex(vertex))
    );
    assert_eq!(
        solid.mev(
            Corner::After(EdgeUse {
                edge,
                side: wingedge::mesh::Side::Left
            }),
            DVec3::ZERO
        ),
        Err(EulerError::UnknownEdge(edge))
    );
    // A bigger solid issues ids this one never had.
    let other = builders::dodecahedron();
    let foreign_face = other.faces().last().unwrap().0;
    let foreign_edge = other.edges().last().unwrap().0;
    let foreign_vertex = other.vertices().last().unwrap().0;
    assert_eq!(
        solid.kef(foreign_edge, face),
        Err(EulerError::UnknownEdge(foreign_edge))
    );
    assert_eq!(
        solid.kfmrh(face, foreign_face),
        Err(EulerError::UnknownFace(foreign_face))
    );
    assert_eq!(
        solid.kvfs(foreign_face),
        Err(EulerError::UnknownFace(foreign_face))
    );
    assert_eq!(
        solid.corner(face, foreign_vertex),
        Err(EulerError::UnknownVertex(foreign_vertex))
    );
    assert_eq!(
        solid.extrude_face(foreign_face, DVec3::Z),
        Err(EulerError::UnknownFace(foreign_face))
    );
    assert_eq!(snapshot(&solid), before);
}

/// Each pre-condition, broken on a cube, is refused with its ids and leaves
/// the cube as it was.
#[test]
fn broken_preconditions_are_refused_and_change_nothing() {
    let mut solid = builders::cube();
    let before = snapshot(&solid);
    let (edge, e) = solid.edges().next().map(|(id, e)| (id, e.clone())).unwrap();
    let face = e.left_face;
    let other_face = e.right_face.unwrap();
    // kev needs a vertex of degree one.
    assert_eq!(
        solid.kev(edge, e.dest),
        Err(EulerError::WrongDegree {
            vertex: e.dest,
            degree: 3,
            expected: 1
        })
    );
    // mef between the ends of an existing edge would double it.
    let c1 = solid.corner(face, e.origin).unwrap();
    let c2 = solid.corner(face, e.dest).unwrap();
    assert_eq!(
        solid.mef(c1, c2),
        Err(EulerError::AlreadyJoined {
            v1: e.origin,
            v2: e.dest,
            edge
        })
    );
    assert_eq!(solid.mef(c1, c1), Err(EulerError::SameVertex(e.origin)));
    // kemr needs both sides on one loop.
    assert_eq!(
        solid.kemr(edge),
        Err(EulerError::SidesOnDifferentLoops { edge })
    );
    // mekr needs two loops.
    // The corner of the face diagonally opposite the edge's origin.
    let opposite = solid
        .face_vertices(face)
        .find(|&v| v != e.origin && solid.vertex_vertices(v).all(|w| w != e.origin))
        .unwrap();
    let c3 = solid.corner(face, opposite).unwrap();
    assert!(matches!(
        solid.mekr(c1, c3),
        Err(EulerError::SameLoop { .. })
    ));
    // kfmrh needs two faces; mfkrh needs a ring.
    assert_eq!(solid.kfmrh(face, face), Err(EulerError::SameFace(face)));
    let outer = solid.face(face).outer;
    assert_eq!(
        solid.mfkrh(outer),
        Err(EulerError::NotARing {
            loop_id: outer,
            face
        })
    );
    // kvfs needs a lone shell; join_edges a vertex of degree two.
    assert_eq!(solid.kvfs(face), Err(EulerError::NotLoneShell(face)));
    assert_eq!(
        solid.join_edges(e.origin),
        Err(EulerError::WrongDegree {
            vertex: e.origin,
            degree: 3,
            expected: 2
        })
    );
    // Corners on different faces.
    let c4 = solid
        .corner(
            other_face,
            solid
                .face_vertices(other_face)
                .find(|&v| v != e.origin && v != e.dest)
                .unwrap(),
        )
        .unwrap();
    assert_eq!(
        solid.mef(c3, c4),
        Err(EulerError::DifferentFaces {
            f1: face,
            f2: other_face
        })
    );
    // Non-finite positions; an extrusion inwards.
    assert!(matches!(
        solid.split_edge(edge, DVec3::new(f64::NAN, 0.0, 0.0)),
        Err(EulerError::NonFinitePosition { .. })
    ));
    let normal = solid.face(face).plane.unwrap().normal;
    assert!(matches!(
        solid.extrude_face(face, -normal),
        Err(EulerError::NotOutward { .. })
    ));
    assert_eq!(snapshot(&solid), before);
    solid.check_consistency().unwrap();
}
