//! Stage 7: coplanar neighbours merged back into polygon faces.
//!
//! The pieces are triangles; the result should have the faces a person
//! expects (a box minus a smaller box: 6 + 6 faces, a drilled face: one
//! face with a ring). Two neighbouring faces are merged when they came
//! from the same operand face, or when the operand triangles they came from
//! lie exactly in one plane (four `orient3d` = 0) facing the same way; the
//! merge itself is [`Solid::merge_faces_where`] (Euler operators only). A
//! vertex it leaves with two edges lies on the line where its two faces'
//! planes meet, so removing it changes no shape, and it drops the
//! near-collinear points that rounding could otherwise fold.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;
use crate::geom::{Sign, orient3d};
use crate::mesh::{FaceId, Solid, VertexId};

use super::intersect::projection;
use super::operand::FaceOrigin;

/// What the merge needs to know about each polygon of the soup the solid
/// was built from (indexed by the faces' `source_index`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PieceSource {
    /// The kept piece's index (stable over the output stage's rounds).
    pub piece: usize,
    pub origin: FaceOrigin,
    /// The operand triangle the piece lies in, wound as the piece faces.
    pub plane: [DVec3; 3],
    /// Whether the piece is less than its whole operand triangle.
    pub changed: bool,
    /// Whether the piece is the only one of its operand face (the face is
    /// one triangle, the piece all of it): then every face of the result
    /// that has this origin has this source.
    pub alone: bool,
}

/// The most corners a merged face may have: the limit the validator and
/// the readers apply to a polygon by default
/// ([`DEFAULT_MAX_FACE_CORNERS`](crate::io::DEFAULT_MAX_FACE_CORNERS)), so
/// that every written result is read back by the project's own tools. A
/// larger flat region stays several faces.
pub(crate) const MAX_MERGED_CORNERS: usize = crate::io::DEFAULT_MAX_FACE_CORNERS;

/// Merges every pair of neighbouring faces from the same operand face or
/// exactly one plane facing one way ([`Solid::merge_faces_where`]), except
/// faces at a point where the result touches itself (two vertices at one
/// position: a sphere resting on a plate touches it at its pole, two cubes
/// sharing an edge touch along it) unless that vertex is a corner, with
/// at least three edges between faces that cannot merge. Merging every
/// piece around a contact in a flat face would leave it inside one face,
/// where a face cannot keep a vertex, and the contact would turn into a
/// vertex on a face; at the end of a contact along an edge of a face, the
/// vertex would be left with two edges and dropped, and the contact edge
/// would end inside the other sheet's edge. At a corner the edges between
/// faces that cannot merge stay, so the corner does.
///
/// Pieces in `blocked` (by [`PieceSource::piece`]) merge with nothing: the
/// output stage blocks the pieces of a merged face that could not be
/// written valid. Pairs in `joined` (smaller piece first) merge although
/// they lie in two planes: pieces of two sheets so nearly coplanar that
/// rounding folds them over each other, which one flat face does not.
///
/// Returns the faces after the merge that hold a changed piece (see
/// [`PieceSource::changed`]), and the pairs of soup polygons (by source
/// index) whose faces were merged.
pub(crate) fn merge_faces(
    solid: &mut Solid,
    sources: &[PieceSource],
    blocked: &HashSet<usize>,
    joined: &HashSet<(usize, usize)>,
) -> (HashSet<FaceId>, Vec<(usize, usize)>) {
    let source_of =
        |solid: &Solid, f: FaceId| solid.face(f).attributes.source_index.map(|i| sources[i]);
    let mut changed: HashSet<FaceId> = solid
        .faces()
        .filter(|(_, face)| {
            face.attributes
                .source_index
                .is_none_or(|i| sources[i].changed)
        })
        .map(|(f, _)| f)
        .collect();
    let mut merge_rule = MergeRule::default();
    let mut mergeable = |l: &PieceSource, r: &PieceSource| {
        let pair = (l.piece.min(r.piece), l.piece.max(r.piece));
        !blocked.contains(&l.piece)
            && !blocked.contains(&r.piece)
            && (joined.contains(&pair) || merge_rule.allows(l, r))
    };
    let mut touching = touching_vertices(solid);
    touching.retain(|&v| {
        let creases = solid
            .vertex_edges(v)
            .filter(|&e| {
                let edge = solid.edge(e);
                let sides = (
                    source_of(solid, edge.left_face),
                    edge.right_face.and_then(|f| source_of(solid, f)),
                );
                !matches!(sides, (Some(l), Some(r)) if mergeable(&l, &r))
            })
            .count();
        creases < 3
    });
    // Faces allowed to merge, as pairs: a merged face holds a changed piece
    // when any face of its group did (an allowed merge that the Euler
    // operators then skip only makes the set larger).
    let mut merged: Vec<(FaceId, FaceId)> = Vec::new();
    let mut merged_sources: Vec<(usize, usize)> = Vec::new();
    solid.merge_faces_where(|solid, left, right| {
        let (Some(l), Some(r)) = (source_of(solid, left), source_of(solid, right)) else {
            return false;
        };
        if !touching.is_empty()
            && [left, right]
                .iter()
                .any(|&f| solid.face_vertices(f).any(|v| touching.contains(&v)))
        {
            return false;
        }
        // A merged face stays readable: its polygon within the corner
        // limit every reader of the project applies (counted before the
        // shared edges go, so the bound holds).
        let corners = |f: FaceId| solid.face_vertices(f).count();
        let allowed = mergeable(&l, &r) && corners(left) + corners(right) <= MAX_MERGED_CORNERS;
        if allowed {
            merged.push((left, right));
            let index = |f: FaceId| solid.face(f).attributes.source_index.unwrap_or_default();
            merged_sources.push((index(left), index(right)));
        }
        allowed
    });
    // "Changed" spread over each group of merged faces.
    let mut index: HashMap<FaceId, usize> = HashMap::default();
    for &(l, r) in &merged {
        for f in [l, r] {
            let next = index.len();
            index.entry(f).or_insert(next);
        }
    }
    let mut groups = DisjointSets::new(index.len());
    for &(l, r) in &merged {
        groups.union(index[&l], index[&r]);
    }
    let changed_groups: HashSet<usize> = index
        .iter()
        .filter(|(f, _)| changed.contains(f))
        .map(|(_, &i)| groups.find(i))
        .collect();
    for (&f, &i) in &index {
        if changed_groups.contains(&groups.find(i)) {
            changed.insert(f);
        }
    }
    changed.retain(|&f| solid.get_face(f).is_some());
    (changed, merged_sources)
}

/// Whether two neighbouring pieces may merge: from one operand face, or
/// lying in operand triangles of one plane that face one way. The answer
/// for two wound operand triangles is found once and kept (neighbouring
/// pieces of two cut triangles ask again and again, and coplanar ones
/// reach `orient3d`'s exact stage); pieces that are the only ones of
/// their origins are answered directly (their pair is asked once).
#[derive(Default)]
struct MergeRule {
    coplanar: HashMap<([u64; 9], [u64; 9]), bool>,
}

impl MergeRule {
    fn allows(&mut self, l: &PieceSource, r: &PieceSource) -> bool {
        if l.origin == r.origin {
            return true;
        }
        if l.alone && r.alone {
            return same_plane_same_way(&l.plane, &r.plane);
        }
        let key = |plane: &[DVec3; 3]| {
            let mut bits = [0u64; 9];
            for (k, p) in plane.iter().enumerate() {
                for axis in 0..3 {
                    bits[3 * k + axis] = p[axis].to_bits();
                }
            }
            bits
        };
        *self
            .coplanar
            .entry((key(&l.plane), key(&r.plane)))
            .or_insert_with(|| same_plane_same_way(&l.plane, &r.plane))
    }
}

/// The vertices that share their position with another vertex.
fn touching_vertices(solid: &Solid) -> HashSet<VertexId> {
    // −0 and +0 are one position.
    let mut by_position: Vec<([u64; 3], VertexId)> = solid
        .vertices()
        .map(|(v, vertex)| {
            let key = (vertex.position + DVec3::ZERO).to_array().map(f64::to_bits);
            (key, v)
        })
        .collect();
    by_position.sort_unstable_by_key(|&(key, _)| key);
    by_position
        .chunk_by(|x, y| x.0 == y.0)
        .filter(|run| run.len() > 1)
        .flatten()
        .map(|&(_, v)| v)
        .collect()
}

/// Whether two triangles lie exactly in one plane and face the same way.
///
/// A corner of `b` at a corner of `a` lies in `a`'s plane without a test
/// (`orient3d` would be exactly zero there, and would reach its exact
/// fallback to say so): neighbouring pieces share two corners, so usually
/// one `orient3d` decides.
fn same_plane_same_way(a: &[DVec3; 3], b: &[DVec3; 3]) -> bool {
    if b.iter()
        .filter(|p| !a.contains(p))
        .any(|&p| orient3d(a[0], a[1], a[2], p) != Sign::Zero)
    {
        return false;
    }
    let (axis, facing) = projection(a);
    let flat = |p: DVec3| {
        let (u, v) = crate::geom::implicit::kept_axes(axis);
        glam::DVec2::new(p[u], p[v])
    };
    crate::geom::orient2d(flat(b[0]), flat(b[1]), flat(b[2])) == facing
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn the_rule_answers_each_pair_of_operand_triangles_not_each_pair_of_faces() {
        // Two faces of a cube as the origins (which faces does not matter,
        // only that they are two).
        let cube = builders::cube();
        let faces: Vec<FaceId> = cube.faces().map(|(f, _)| f).collect();
        let source = |face: FaceId, plane: [DVec3; 3]| PieceSource {
            piece: 0,
            origin: FaceOrigin { operand: 0, face },
            plane,
            changed: true,
            alone: false,
        };
        let flat = |z: f64, x: f64| {
            [
                DVec3::new(x, 0.0, z),
                DVec3::new(x + 1.0, 0.0, z),
                DVec3::new(x, 1.0, z),
            ]
        };
        let mut rule = MergeRule::default();
        // Pieces of two faces in one plane, facing one way: they merge.
        let a = source(faces[0], flat(0.0, 0.0));
        let b = source(faces[1], flat(0.0, 1.0));
        assert!(rule.allows(&a, &b));
        // Another piece of the second face lies in another of its
        // triangles, turned over (a piece kept the other way) or in
        // another plane: the first answer must not stand for it.
        let turned = source(
            faces[1],
            [flat(0.0, 1.0)[0], flat(0.0, 1.0)[2], flat(0.0, 1.0)[1]],
        );
        assert!(!rule.allows(&a, &turned));
        let lifted = source(faces[1], flat(1e-9, 1.0));
        assert!(!rule.allows(&a, &lifted));
        // Asked again, the same answers.
        assert!(rule.allows(&a, &b) && !rule.allows(&a, &turned));
        // One origin always merges.
        assert!(rule.allows(&b, &lifted));
    }
}
