//! The two groupings an exact weld needs, each in time linear in its
//! input rather than by sorting all of it: vertices by bit-identical
//! position (a hash table keyed by the coordinates' bits), and edge uses by
//! the pair of clusters they join (a counting sort by the lower cluster,
//! then a sort of each bucket, a handful of uses around one vertex).
//!
//! A binary STL of a million triangles has three million corners and as
//! many edge uses; sorting them whole was most of the time of reading it.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hash, Hasher};

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::PolygonSoup;

/// A hasher for the bits of coordinates. `f32` values widened to `f64`
/// (every binary STL) end in 29 zero bits, which a plain multiplicative
/// hash keeps in its low bits, the ones a table indexes by; a final
/// avalanche (MurmurHash3's `fmix64`) spreads every input bit over every
/// output bit.
#[derive(Default)]
struct BitsHasher(u64);

impl Hasher for BitsHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, word: u64) {
        self.0 = (self.0.rotate_left(23) ^ word).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    }

    fn write_usize(&mut self, word: usize) {
        self.write_u64(word as u64);
    }

    fn finish(&self) -> u64 {
        let mut x = self.0;
        x ^= x >> 33;
        x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
        x ^= x >> 33;
        x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
        x ^ (x >> 33)
    }
}

/// The cluster of each vertex under an exact weld: the smallest index of a
/// vertex at the bit-identical position (`-0.0` counted as `0.0`).
///
/// Vertices are split by bits of their hash into [`SHARDS`] groups, each
/// with a table of its own, small enough to stay in cache, and the groups
/// are done in parallel; within a group vertices are visited in order, so
/// the first at a position is the smallest.
pub(super) fn exact_clusters(positions: &[DVec3]) -> Vec<usize> {
    let n = positions.len();
    if n < 1 << 16 || n >= u32::MAX as usize {
        let mut first = table(n);
        return positions
            .iter()
            .enumerate()
            .map(|(i, &p)| *first.entry(canonical(p)).or_insert(i))
            .collect();
    }
    // Bits 32 to 39 of the hash pick the group: the tables index by the
    // low bits and tag by the top seven, which then still vary.
    let shard = |p: DVec3| {
        let mut hasher = BitsHasher::default();
        canonical(p).hash(&mut hasher);
        (hasher.finish() >> 32) as usize % SHARDS
    };
    let shards: Vec<u8> = positions.par_iter().map(|&p| shard(p) as u8).collect();
    // A counting sort of the vertices by group, each group in order.
    let mut start = vec![0usize; SHARDS + 1];
    for &s in &shards {
        start[usize::from(s) + 1] += 1;
    }
    for s in 0..SHARDS {
        start[s + 1] += start[s];
    }
    let mut order = vec![0u32; n];
    let mut fill = start.clone();
    for (i, &s) in shards.iter().enumerate() {
        order[fill[usize::from(s)]] = i as u32;
        fill[usize::from(s)] += 1;
    }
    drop(shards);
    let firsts: Vec<Vec<u32>> = (0..SHARDS)
        .into_par_iter()
        .map(|s| {
            let members = &order[start[s]..start[s + 1]];
            let mut first = table(members.len());
            members
                .iter()
                .map(|&i| *first.entry(canonical(positions[i as usize])).or_insert(i))
                .collect()
        })
        .collect();
    let mut cluster = vec![0usize; n];
    for (s, firsts) in firsts.iter().enumerate() {
        for (&i, &f) in order[start[s]..start[s + 1]].iter().zip(firsts) {
            cluster[i as usize] = f as usize;
        }
    }
    cluster
}

/// How many groups [`exact_clusters`] splits the vertices of a large soup
/// into: a million-triangle STL's half a million positions make tables of
/// a few thousand entries each.
const SHARDS: usize = 256;

/// The bits that decide an exact weld: `-0.0` counted as `0.0`.
fn canonical(p: DVec3) -> [u64; 3] {
    [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits)
}

/// A table from position bits to the first vertex there, for `vertices`
/// vertices: it starts at a quarter of them (a binary STL has about a
/// sixth as many positions as corners) and grows.
fn table<V>(vertices: usize) -> HashMap<[u64; 3], V, BuildHasherDefault<BitsHasher>> {
    HashMap::with_capacity_and_hasher(vertices / 4, BuildHasherDefault::default())
}

/// Pairs of open edge uses `a1→b1`, `a2→b2` that join the same two clusters
/// in opposite directions, with no third use between those clusters. Only
/// edges touching a `shared` vertex (one whose cluster has other members)
/// can be glued, so only those are looked at. Pairs come in the order of
/// their lower cluster, then their higher one.
pub(super) fn glue_candidates(
    soup: &PolygonSoup,
    cluster: &[usize],
    shared: &[bool],
) -> Vec<[usize; 4]> {
    // The lower and higher cluster of the use `a → b`, when it may glue.
    let joins = |a: usize, b: usize| {
        let (ca, cb) = (cluster[a], cluster[b]);
        (ca != cb && (shared[a] || shared[b])).then(|| (ca.min(cb), ca.max(cb)))
    };

    // A counting sort of the uses by lower cluster: `start[c]` is where
    // the bucket of cluster `c` begins, and then, as it fills, where its
    // next use goes, so that it ends as where the bucket of `c + 1` begins.
    let n = cluster.len();
    let mut start = vec![0usize; n + 1];
    for p in &soup.polygons {
        for (a, b) in edges(&p.vertices) {
            if let Some((low, _)) = joins(a, b) {
                start[low + 1] += 1;
            }
        }
    }
    for c in 0..n {
        start[c + 1] += start[c];
    }
    // (higher cluster, from, to) of each use.
    let mut uses = vec![(0usize, 0usize, 0usize); start[n]];
    for p in &soup.polygons {
        for (a, b) in edges(&p.vertices) {
            if let Some((low, high)) = joins(a, b) {
                uses[start[low]] = (high, a, b);
                start[low] += 1;
            }
        }
    }
    let mut out = Vec::new();
    let mut begin = 0;
    for &end in &start[..n] {
        let bucket = &mut uses[begin..end];
        begin = end;
        if bucket.len() < 2 {
            continue;
        }
        bucket.sort_unstable();
        for group in bucket.chunk_by(|x, y| x.0 == y.0) {
            if let [(_, a1, b1), (_, a2, b2)] = *group {
                let opposite = cluster[a1] == cluster[b2];
                let already_twins = a1 == b2 && b1 == a2;
                if opposite && !already_twins {
                    out.push([a1, b1, a2, b2]);
                }
            }
        }
    }
    out
}

/// The edge uses of a polygon, `(from, to)` in its order.
fn edges(vertices: &[usize]) -> impl Iterator<Item = (usize, usize)> + '_ {
    let k = vertices.len();
    (0..k).map(move |i| (vertices[i], vertices[(i + 1) % k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clusters_are_the_first_vertex_at_each_position() {
        let positions = [
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-0.0, 0.0, -0.0),
            DVec3::new(1.0, 2.0, 3.0 + f64::EPSILON * 4.0),
        ];
        assert_eq!(exact_clusters(&positions), [0, 1, 0, 1, 4]);
    }

    #[test]
    fn large_soups_cluster_as_small_ones() {
        // Past 65,536 vertices the clusters are found in parallel groups.
        let positions: Vec<DVec3> = (0..300_000u32)
            .map(|i| {
                let k = i.wrapping_mul(2_654_435_761) % 70_001;
                DVec3::new(
                    f64::from(k % 97),
                    f64::from(k / 97),
                    if k % 5 == 0 { -0.0 } else { 0.0 },
                )
            })
            .collect();
        let clusters = exact_clusters(&positions);
        let mut first = std::collections::HashMap::new();
        for (i, p) in positions.iter().enumerate() {
            let expected = *first.entry(canonical(*p)).or_insert(i);
            assert_eq!(clusters[i], expected, "vertex {i}");
        }
        assert!(first.len() > 1000 && first.len() < positions.len());
    }

    #[test]
    fn f32_positions_hash_apart() {
        // Widened `f32` values end in 29 zero bits: they must still spread
        // over the table (a hash that kept those zeros would put every
        // position in one bucket and take minutes here).
        let positions: Vec<DVec3> = (0..200_000)
            .map(|i| {
                let t = i as f32 * 1e-3;
                DVec3::new(f64::from(t), f64::from(t * 0.5), 1.0)
            })
            .collect();
        let clusters = exact_clusters(&positions);
        let distinct = clusters
            .iter()
            .enumerate()
            .filter(|&(i, &c)| c == i)
            .count();
        let expected: std::collections::HashSet<[u64; 3]> = positions
            .iter()
            .map(|p| p.to_array().map(f64::to_bits))
            .collect();
        assert_eq!(distinct, expected.len());
    }

    #[test]
    fn only_pairs_of_opposite_uses_are_candidates() {
        // Copies: 3 and 5 of 1, 4 of 2, 6 of 0. The edges 0–1, 1–2 and
        // 1–7 are each used twice, in opposite directions: candidates.
        let positions = vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::X,
            DVec3::Y,
            DVec3::X,
            DVec3::ZERO,
            DVec3::Z,
        ];
        let soup = PolygonSoup::new(positions.clone(), [[0, 1, 2], [4, 3, 7], [5, 6, 7]]);
        let cluster = exact_clusters(&positions);
        let shared: Vec<bool> = cluster
            .iter()
            .enumerate()
            .map(|(v, &c)| c != v || cluster.iter().enumerate().any(|(w, &d)| d == v && w != v))
            .collect();
        let pairs = glue_candidates(&soup, &cluster, &shared);
        assert_eq!(pairs, [[0, 1, 5, 6], [1, 2, 4, 3], [3, 7, 7, 5]]);
        // The edge 1–2 used three times, and 0–1 and 2–0 twice the same
        // way: nothing to glue.
        let tripled = PolygonSoup::new(positions, [[0, 1, 2], [4, 3, 7], [3, 4, 6]]);
        assert!(glue_candidates(&tripled, &cluster, &shared).is_empty());
    }
}
