//! Box queries: the leaves and items whose bounds overlap a closed box (an
//! octree cell, a face's box).

use glam::DVec3;

use crate::geom::Aabb;
use crate::spatial::rounding::{f64_above, f64_below};

use super::node::{LEAF, Node8, WIDTH};
use super::tree::Bvh;

impl Bvh {
    /// Calls `visit(leaf)` for every leaf whose box overlaps the closed box
    /// `query` (touching counts). Conservative: every leaf holding an item
    /// whose exact box overlaps `query` is visited (and possibly some that
    /// hold none). An empty or NaN `query` visits nothing.
    pub fn leaves_overlapping(&self, query: &Aabb, visit: impl FnMut(u32)) {
        self.walk(query, |_, _| true, visit);
    }

    /// [`Bvh::leaves_overlapping`] that opens a node (inner or leaf) only
    /// when `keep` accepts its box as well: `keep` gets a box in input
    /// coordinates, rounded outward, that holds the exact box the node's
    /// `f32` box stands for. With `keep` an exact test of a shape against a
    /// box (a triangle's, say), every leaf holding an item whose exact box
    /// overlaps `query` and meets the shape is visited: a node's box holds
    /// its items' boxes, and a shape meeting a box meets every box that
    /// holds it. A sliver crossing the tree obliquely opens the nodes along
    /// it, not every node its box overlaps.
    pub fn leaves_overlapping_where(
        &self,
        query: &Aabb,
        keep: impl Fn(&Aabb) -> bool,
        visit: impl FnMut(u32),
    ) {
        self.walk(query, |n, k| keep(&self.slot_box(n, k)), visit);
    }

    /// The walk of both queries: opens slot `k` of node `n` when its box
    /// overlaps `query` and `open(n, k)`.
    fn walk(&self, query: &Aabb, open: impl Fn(&Node8, usize) -> bool, mut visit: impl FnMut(u32)) {
        if query.is_empty() || query.intersection(self.bounds()).is_empty() {
            return;
        }
        // The query in the frame, rounded outward: it contains the exact
        // in-frame query, so comparing it with the (outward-rounded) node
        // boxes can only err towards visiting.
        let frame = self.frame();
        let lo: [f32; 3] = std::array::from_fn(|a| frame.lower(query.min[a], a));
        let hi: [f32; 3] = std::array::from_fn(|a| frame.upper(query.max[a], a));
        let mut stack = vec![0u32];
        while let Some(node) = stack.pop() {
            let n = &self.nodes()[node as usize];
            for k in (0..WIDTH).rev() {
                let child = n.child[k];
                let meets = child != u32::MAX
                    && n.bounds[0][k] <= hi[0]
                    && lo[0] <= n.bounds[3][k]
                    && n.bounds[1][k] <= hi[1]
                    && lo[1] <= n.bounds[4][k]
                    && n.bounds[2][k] <= hi[2]
                    && lo[2] <= n.bounds[5][k]
                    && open(n, k);
                if !meets {
                    continue;
                }
                if child & LEAF != 0 {
                    visit(child & !LEAF);
                } else {
                    stack.push(child);
                }
            }
        }
    }

    /// The box of slot `k` of node `n` in input coordinates, rounded
    /// outward (the division by the frame's power-of-two scale is exact,
    /// adding the centre is rounded to nearest, which the next `f64`
    /// outward covers).
    fn slot_box(&self, n: &Node8, k: usize) -> Aabb {
        let f = self.frame();
        let back = |row: usize, a: usize| f64::from(n.bounds[row][k]) / f.scale + f.centre[a];
        Aabb {
            min: DVec3::new(
                f64_below(back(0, 0)),
                f64_below(back(1, 1)),
                f64_below(back(2, 2)),
            ),
            max: DVec3::new(
                f64_above(back(3, 0)),
                f64_above(back(4, 1)),
                f64_above(back(5, 2)),
            ),
        }
    }

    /// Calls `visit(p)` for every item position `p` whose exact box,
    /// `item_bounds(p)`, overlaps the closed box `query`: exactly those
    /// items, each once, leaf by leaf.
    pub fn items_overlapping(
        &self,
        query: &Aabb,
        item_bounds: impl Fn(usize) -> Aabb,
        mut visit: impl FnMut(usize),
    ) {
        self.leaves_overlapping(query, |leaf| {
            let Some(items) = self.leaf(leaf) else {
                return;
            };
            for p in items.range() {
                if !item_bounds(p).intersection(*query).is_empty() {
                    visit(p);
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::spatial::bvh::pair_walk::tests::random_boxes;

    /// A box query reports exactly the items whose boxes overlap the closed
    /// query box (touching included), each once; empty and NaN queries
    /// report nothing.
    #[test]
    fn box_queries_find_exactly_the_overlapping_items() {
        let items = random_boxes(2_000, 0x3C6E_F372_FE94_F82B, 5.0, 2.0, 0.2);
        let (bvh, order) = Bvh::build(&items);
        let mut u = crate::test_rng::uniform(0xA54F_F53A_5F1D_36F1);
        for case in 0..200 {
            let lo = DVec3::new(u(), u(), u()) * 2.4 + DVec3::splat(4.8);
            let query = if case % 10 == 0 {
                // Exactly touching an item's corner.
                Aabb::from_points([items[case].max, items[case].max + DVec3::splat(0.1)])
            } else {
                Aabb::from_points([lo, lo + DVec3::new(u(), u(), u()) * 0.5])
            };
            let mut found = Vec::new();
            bvh.items_overlapping(
                &query,
                |p| items[order[p] as usize],
                |p| {
                    found.push(order[p] as usize);
                },
            );
            found.sort_unstable();
            let before = found.len();
            found.dedup();
            assert_eq!(found.len(), before, "case {case}: an item twice");
            let want: Vec<usize> = (0..items.len())
                .filter(|&i| !items[i].intersection(query).is_empty())
                .collect();
            assert_eq!(found, want, "case {case}");
            if case % 10 == 0 {
                assert!(found.contains(&case), "case {case}: the touched item");
            }
        }
        let nan = Aabb {
            min: DVec3::NAN,
            max: DVec3::NAN,
        };
        for query in [Aabb::EMPTY, nan] {
            bvh.leaves_overlapping(&query, |leaf| panic!("leaf {leaf} for {query:?}"));
        }
    }
}
