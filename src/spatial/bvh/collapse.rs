//! Collapsing the binary SAH tree into eight-wide nodes, and each node's
//! order of children per octant of ray directions.

use rayon::prelude::*;

use crate::spatial::raw::huge_pages::HugeVec;

use super::node::{LEAF, LeafItems, Node, Node8, WIDTH};

/// Turns the binary BVH (one box per node) into [`Node8`]s, root first:
/// each binary inner node becomes a node whose slots hold up to eight of its
/// descendants (the inner descendant with the largest box opened first),
/// and each binary leaf a leaf, numbered in the order the pass meets it.
/// Returns the nodes, the leaves' items by leaf number, and the depth of
/// the new tree (nodes on its longest path from the root).
///
/// The nodes are made in one serial pass; anything per leaf that is costly
/// (the first touch of fresh huge pages, for one) is better made by the
/// caller afterwards, on all cores, from the leaves returned.
pub(super) fn collapse(nodes: &[Node]) -> (HugeVec<Node8>, Vec<LeafItems>, usize) {
    let leaves = nodes.iter().filter(|n| n.count > 0).count();
    // Each node but a leaf root's is made from its own binary inner node.
    let mut out = HugeVec::with_capacity((nodes.len() - leaves).max(1));
    out.push(Node8::EMPTY);
    let mut c = Collapse {
        nodes,
        out,
        leaves: Vec::with_capacity(leaves),
    };
    let has_triangles = nodes
        .first()
        .is_some_and(|n| n.count > 0 || nodes.len() > 1);
    let depth = if !has_triangles {
        1
    } else if nodes[0].count > 0 {
        let leaf = c.leaf(0);
        c.out[0].set(0, &nodes[0], leaf);
        1
    } else {
        c.fill(0, 0)
    };
    let leaves = c
        .leaves
        .iter()
        .map(|&j| LeafItems {
            first: nodes[j].first,
            count: nodes[j].count,
        })
        .collect();
    let mut out = c.out;
    out.par_iter_mut().for_each(Node8::order_children);
    (out, leaves, depth)
}

/// The state of [`collapse`]'s pass over the binary tree.
struct Collapse<'a> {
    nodes: &'a [Node],
    out: HugeVec<Node8>,
    /// The binary leaves met so far, by leaf number.
    leaves: Vec<usize>,
}

impl Collapse<'_> {
    /// Numbers binary leaf `j` as the next leaf; returns its slot entry.
    fn leaf(&mut self, j: usize) -> u32 {
        self.leaves.push(j);
        (self.leaves.len() - 1) as u32 | LEAF
    }

    /// Fills `out[at]` from the binary inner node `i`, appending the nodes
    /// of its inner descendants and numbering its leaves; returns the
    /// depth of the subtree at `out[at]`.
    fn fill(&mut self, i: usize, at: usize) -> usize {
        let nodes = self.nodes;
        let area = |n: &Node| {
            let s = [0, 1, 2].map(|a| f64::from(n.max[a]) - f64::from(n.min[a]));
            s[0] * s[1] + s[1] * s[2] + s[2] * s[0]
        };
        let mut slots: smallvec::SmallVec<[usize; WIDTH]> =
            smallvec::smallvec![i + 1, nodes[i].first as usize];
        while slots.len() < WIDTH {
            let open = (0..slots.len())
                .filter(|&k| nodes[slots[k]].count == 0)
                .max_by(|&p, &q| area(&nodes[slots[p]]).total_cmp(&area(&nodes[slots[q]])));
            let Some(k) = open else { break };
            let j = slots[k];
            slots[k] = j + 1;
            slots.insert(k + 1, nodes[j].first as usize);
        }
        let mut depth = 1;
        for (k, &j) in slots.iter().enumerate() {
            let n = &nodes[j];
            if n.count > 0 {
                let leaf = self.leaf(j);
                self.out[at].set(k, n, leaf);
            } else {
                let child = self.out.len();
                self.out.push(Node8::EMPTY);
                self.out[at].set(k, n, child as u32);
                depth = depth.max(1 + self.fill(j, child));
            }
        }
        depth
    }
}

impl Node8 {
    /// Fills [`Node8::order`] from the slots' boxes.
    pub(crate) fn order_children(&mut self) {
        // Twice each box's centre; empty slots come first (their flag
        // keeps them from ever being pushed).
        let centre: [[f64; 3]; WIDTH] = std::array::from_fn(|k| {
            std::array::from_fn(|a| f64::from(self.bounds[a][k]) + f64::from(self.bounds[3 + a][k]))
        });
        let empty: [bool; WIDTH] = std::array::from_fn(|k| self.child[k] == u32::MAX);
        let flag = |slot: usize| slot as u32 | if empty[slot] { 8 } else { 0 };
        // The opposite octant (every sign flipped) takes the reverse order.
        for octant in 0..WIDTH / 2 {
            let along: [f64; WIDTH] = std::array::from_fn(|k| {
                if empty[k] {
                    return f64::INFINITY;
                }
                (0..3)
                    .map(|a| {
                        if octant >> a & 1 == 1 {
                            -centre[k][a]
                        } else {
                            centre[k][a]
                        }
                    })
                    .sum()
            });
            // Each slot's place by descending projection (ties by slot),
            // counted rather than sorted (a sort's comparisons are not
            // predictable, and this runs for every node). `total_cmp` is a
            // total order, NaN included, so the places are a permutation.
            let (mut forward, mut backward) = (0, 0);
            for k in 0..WIDTH {
                let place = (0..WIDTH)
                    .filter(|&j| match along[j].total_cmp(&along[k]) {
                        std::cmp::Ordering::Greater => true,
                        std::cmp::Ordering::Equal => j < k,
                        std::cmp::Ordering::Less => false,
                    })
                    .count();
                forward |= flag(k) << (4 * place);
                backward |= flag(k) << (4 * (WIDTH - 1 - place));
            }
            self.order[octant] = forward;
            self.order[WIDTH - 1 - octant] = backward;
        }
    }

    fn set(&mut self, k: usize, n: &Node, child: u32) {
        for a in 0..3 {
            self.bounds[a][k] = n.min[a];
            self.bounds[3 + a][k] = n.max[a];
        }
        self.child[k] = child;
    }
}
