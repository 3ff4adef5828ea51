//! Two loops of a face that share a point, or a loop that touches itself.

use crate::geom::polygon::{find_self_intersection, segments_touch};

use super::{FaceLoops, RingRule, RingViolation};

/// Reports every pair of loops of the face whose edges share a point (one
/// violation per pair, naming the first pair of edges found), and every loop
/// that touches itself. Returns, per loop, whether it touches anything.
pub(super) fn check(loops: &FaceLoops, found: &mut Vec<RingViolation>) -> Vec<bool> {
    let n = loops.ids.len();
    let mut touching = vec![false; n];
    for i in 0..n {
        if let Some((a, b)) = find_self_intersection(&loops.points[i]) {
            touching[i] = true;
            let m = loops.vertices[i].len();
            found.push(RingViolation {
                rule: RingRule::LoopsCrossOrTouch,
                message: format!(
                    "loop {:?} of face {:?} touches itself: its edges from vertices {:?} and {:?} meet",
                    loops.ids[i], loops.face, loops.vertices[i][a], loops.vertices[i][b % m]
                ),
                face: loops.face,
                loops: vec![loops.ids[i]],
                vertices: vec![loops.vertices[i][a], loops.vertices[i][b % m]],
            });
        }
        for j in i + 1..n {
            if let Some((a, b)) = first_contact(&loops.points[i], &loops.points[j]) {
                touching[i] = true;
                touching[j] = true;
                let (vi, vj) = (loops.vertices[i][a], loops.vertices[j][b]);
                found.push(RingViolation {
                    rule: RingRule::LoopsCrossOrTouch,
                    message: format!(
                        "loops {:?} and {:?} of face {:?} cross or touch: the edge from vertex {vi:?} meets the edge from vertex {vj:?}",
                        loops.ids[i], loops.ids[j], loops.face
                    ),
                    face: loops.face,
                    loops: vec![loops.ids[i], loops.ids[j]],
                    vertices: vec![vi, vj],
                });
            }
        }
    }
    touching
}

/// The first edges `(a, b)` of two loops that share a point, decided
/// exactly (edge `a` runs from vertex `a` to the next).
fn first_contact(p: &[glam::DVec2], q: &[glam::DVec2]) -> Option<(usize, usize)> {
    let (n, m) = (p.len(), q.len());
    (0..n).find_map(|a| {
        (0..m)
            .find(|&b| segments_touch(p[a], p[(a + 1) % n], q[b], q[(b + 1) % m]))
            .map(|b| (a, b))
    })
}
