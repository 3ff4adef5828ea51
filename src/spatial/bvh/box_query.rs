//! Box queries: the leaves and items whose bounds overlap a closed box (an
//! octree cell, a face's box).

use crate::geom::Aabb;

use super::node::{LEAF, WIDTH};
use super::tree::Bvh;

impl Bvh {
    /// Calls `visit(leaf)` for every leaf whose box overlaps the closed box
    /// `query` (touching counts). Conservative: every leaf holding an item
    /// whose exact box overlaps `query` is visited (and possibly some that
    /// hold none). An empty or NaN `query` visits nothing.
    pub fn leaves_overlapping(&self, query: &Aabb, mut visit: impl FnMut(u32)) {
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
                    && (0..3).all(|a| n.bounds[a][k] <= hi[a] && lo[a] <= n.bounds[3 + a][k]);
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
