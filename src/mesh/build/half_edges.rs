//! The build's tables in index space: half-edges numbered by polygon
//! corner (then the holes' half-edges), and the compressed table of the
//! half-edges leaving each vertex, searched by end vertex.

/// Half-edges in index space: corners of polygons, then holes' half-edges.
pub(super) struct HalfEdges {
    pub(super) from: Vec<usize>,
    pub(super) to: Vec<usize>,
    /// The polygon of each face half-edge.
    pub(super) polygon: Vec<usize>,
    pub(super) next: Vec<usize>,
    pub(super) prev: Vec<usize>,
    pub(super) twin: Vec<usize>,
    /// How many half-edges belong to polygons; the rest run around holes.
    pub(super) face_count: usize,
    /// The soup vertex of each vertex made by splitting a pinch: vertex
    /// `soup.positions.len() + k` is a copy of `split_from[k]`.
    pub(super) split_from: Vec<usize>,
}

/// Outgoing lists up to this length are scanned; longer ones are sorted and
/// searched by halving.
const SCANNED: usize = 32;

/// Compressed table of the face half-edges leaving each soup vertex.
pub(super) struct Outgoing {
    offsets: Vec<usize>,
    list: Vec<usize>,
}

impl Outgoing {
    pub(super) fn new(vertex_count: usize, from: &[usize]) -> Outgoing {
        let mut offsets = vec![0usize; vertex_count + 1];
        for &v in from {
            offsets[v + 1] += 1;
        }
        for i in 0..vertex_count {
            offsets[i + 1] += offsets[i];
        }
        let mut fill = offsets.clone();
        let mut list = vec![0usize; from.len()];
        for (h, &v) in from.iter().enumerate() {
            list[fill[v]] = h;
            fill[v] += 1;
        }
        Outgoing { offsets, list }
    }

    pub(super) fn of(&self, v: usize) -> &[usize] {
        &self.list[self.offsets[v]..self.offsets[v + 1]]
    }

    /// Sorts the lists longer than [`SCANNED`] by the half-edges' end
    /// vertices, stably (half-edges with one end stay in index order).
    pub(super) fn sort_by_end(&mut self, to: &[usize]) {
        for v in 0..self.offsets.len() - 1 {
            let list = &mut self.list[self.offsets[v]..self.offsets[v + 1]];
            if list.len() > SCANNED {
                list.sort_by_key(|&g| to[g]);
            }
        }
    }

    /// The half-edges from `a` to `b`, in index order (after
    /// [`Outgoing::sort_by_end`]).
    pub(super) fn towards<'a>(
        &'a self,
        a: usize,
        b: usize,
        to: &'a [usize],
    ) -> impl Iterator<Item = usize> + Clone + 'a {
        self.candidates(a, b, to)
            .iter()
            .copied()
            .filter(move |&g| to[g] == b)
    }

    /// The number of half-edges from `a` to `b`: a binary search in a
    /// sorted list, so that the many uses of one edge (a fan of faces on
    /// it) are not each counted by walking all the others.
    pub(super) fn count_towards(&self, a: usize, b: usize, to: &[usize]) -> usize {
        let list = self.of(a);
        if list.len() <= SCANNED {
            list.iter().filter(|&&g| to[g] == b).count()
        } else {
            self.candidates(a, b, to).len()
        }
    }

    /// The half-edges out of `a` that may end at `b`: the whole short
    /// list, or exactly those ending at `b` in a sorted long one.
    fn candidates<'a>(&'a self, a: usize, b: usize, to: &[usize]) -> &'a [usize] {
        let list = self.of(a);
        if list.len() <= SCANNED {
            list
        } else {
            let start = list.partition_point(|&g| to[g] < b);
            let end = start + list[start..].partition_point(|&g| to[g] == b);
            &list[start..end]
        }
    }
}
