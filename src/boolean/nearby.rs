//! Which operands can meet: a BVH over the operands' boxes, so that the
//! broad phase and the membership decisions cost what the contacts cost,
//! not the number of operand pairs. A union of `n` disjoint boxes asks
//! each operand about the few whose boxes meet it, never all `n − 1`.

use crate::geom::Aabb;
use crate::spatial::Bvh;

/// The operands' exact bounding boxes, indexed.
///
/// # Invariants
///
/// `bvh` is built over `boxes` (item position `p` is operand `order[p]`).
pub(crate) struct Nearby {
    boxes: Vec<Aabb>,
    bvh: Bvh,
    order: Vec<u32>,
}

impl Nearby {
    /// The index over `boxes` (operand `k`'s box is `boxes[k]`).
    pub fn new(boxes: Vec<Aabb>) -> Nearby {
        let (bvh, order) = Bvh::build(&boxes);
        Nearby { boxes, bvh, order }
    }

    /// Every pair `(i, j)`, `i < j`, of operands whose closed boxes
    /// overlap (touching counts: the test is the exact
    /// `Aabb::intersection` of the two boxes), in increasing order.
    pub fn meeting_pairs(&self) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        self.bvh.self_leaf_pairs(|a, b| {
            let (Some(a), Some(b)) = (self.bvh.leaf(a), self.bvh.leaf(b)) else {
                return;
            };
            for p in a.range() {
                for q in b.range() {
                    let (i, j) = (self.order[p] as usize, self.order[q] as usize);
                    if i < j && self.meet(i, j) {
                        pairs.push((i, j));
                    } else if j < i && self.meet(j, i) {
                        pairs.push((j, i));
                    }
                }
            }
        });
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// Whether the boxes of operands `i` and `j` overlap.
    fn meet(&self, i: usize, j: usize) -> bool {
        !self.boxes[i].intersection(self.boxes[j]).is_empty()
    }

    /// Calls `visit(k)` for every operand whose box overlaps the closed box
    /// `query` (exactly those, each once).
    pub fn overlapping(&self, query: &Aabb, mut visit: impl FnMut(usize)) {
        self.bvh.items_overlapping(
            query,
            |p| self.boxes[self.order[p] as usize],
            |p| visit(self.order[p] as usize),
        );
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// The pairs and the box queries are exactly those of the all-pairs
    /// loop they replace, touching boxes included.
    #[test]
    fn the_index_finds_exactly_the_overlapping_boxes() {
        let mut u = crate::test_rng::uniform(0x9E37_79B9_7F4A_7C15);
        let boxes: Vec<Aabb> = (0..600)
            .map(|_| {
                // Integer corners: many boxes touch exactly.
                let min = DVec3::new(u() * 40.0, u() * 40.0, u() * 40.0).floor();
                let size = DVec3::new(1.0 + u() * 3.0, 1.0 + u() * 3.0, 1.0 + u() * 3.0).floor();
                Aabb {
                    min,
                    max: min + size,
                }
            })
            .collect();
        let nearby = Nearby::new(boxes.clone());
        let mut expected = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if !boxes[i].intersection(boxes[j]).is_empty() {
                    expected.push((i, j));
                }
            }
        }
        assert!(expected.len() > 100, "{}", expected.len());
        assert_eq!(nearby.meeting_pairs(), expected);
        for query in boxes.iter().take(50) {
            let mut got = Vec::new();
            nearby.overlapping(query, |k| got.push(k));
            got.sort_unstable();
            let want: Vec<usize> = (0..boxes.len())
                .filter(|&k| !boxes[k].intersection(*query).is_empty())
                .collect();
            assert_eq!(got, want);
        }
    }
}
