//! Disjoint sets (union–find with path halving), used to group faces into
//! shells and the faces around a vertex into fans.

/// A partition of `0..n` into disjoint sets.
///
/// # Invariants
///
/// Every `parent` chain ends at a root (`parent[r] == r`); a root is the
/// smallest element of its set, so results do not depend on the order of
/// unions.
#[derive(Clone, Debug)]
pub(crate) struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    /// `n` singletons.
    pub(crate) fn new(n: usize) -> DisjointSets {
        DisjointSets {
            parent: (0..n).collect(),
        }
    }

    /// The root (smallest element) of `i`'s set.
    pub(crate) fn find(&mut self, mut i: usize) -> usize {
        while self.parent[i] != i {
            self.parent[i] = self.parent[self.parent[i]];
            i = self.parent[i];
        }
        i
    }

    /// Joins the sets of `a` and `b`.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra.max(rb)] = ra.min(rb);
        }
    }

    /// The sets whose root (smallest element) each element names:
    /// `roots[i] <= i` and `roots[roots[i]] == roots[i]`.
    pub(crate) fn from_roots(roots: Vec<usize>) -> DisjointSets {
        debug_assert!(
            roots
                .iter()
                .enumerate()
                .all(|(i, &r)| r <= i && roots[r] == r)
        );
        DisjointSets { parent: roots }
    }

    /// Whether `i` is the root of its set.
    pub(crate) fn is_root(&mut self, i: usize) -> bool {
        self.find(i) == i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unions_join_sets_and_roots_are_smallest() {
        let mut sets = DisjointSets::new(6);
        sets.union(4, 2);
        sets.union(5, 4);
        sets.union(1, 3);
        assert_eq!(sets.find(5), 2);
        assert_eq!(sets.find(3), 1);
        assert_eq!((0..6).filter(|&i| sets.is_root(i)).count(), 3);
    }
}
