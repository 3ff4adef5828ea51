//! The weld's fast path: a soup of triangles whose clusters close it.
//!
//! A binary STL of a closed solid repeats every corner, and welding all
//! copies of each position gives a mesh where every edge has exactly two
//! uses, in opposite directions, no triangle visits a position twice, and
//! the triangles around each position form one fan. When that holds, the
//! conservative weld (glue pairs of opposite open edges, refuse pinches and
//! repeats, repeat until nothing is refused) merges every cluster whole and
//! refuses nothing, so the clusters are the answer. This file checks those
//! three facts on flat arrays of 32-bit corner numbers, in time linear in
//! the corners, and says `None` (take the general path) at the first that
//! fails.
//!
//! Why the general path then merges each cluster whole: every edge's two
//! uses form a glue candidate (or are already twins), and the glue joins
//! the corners at each end; walking a fan from corner to corner crosses one
//! such edge per step, so every corner of a fan is joined to the next, and
//! a cluster that is one fan ends as one vertex. No triangle then repeats a
//! vertex, and no class has two fans, so nothing is refused.

use crate::mesh::PolygonSoup;

/// Whether the clusters are the weld's final classes by the fast path:
/// `soup` is all triangles, every vertex is used by one, the corners are
/// fewer than `u32::MAX`, and the clusters close every edge as described
/// above. `cluster[v]` is the smallest vertex of `v`'s cluster.
pub(super) fn clusters_close_triangles(soup: &PolygonSoup, cluster: &[usize]) -> bool {
    closed(soup, cluster).is_some()
}

fn closed(soup: &PolygonSoup, cluster: &[usize]) -> Option<()> {
    let corners = soup.polygons.len().checked_mul(3)?;
    let n = cluster.len();
    if corners >= u32::MAX as usize || n >= u32::MAX as usize {
        return None;
    }
    // The cluster of each corner, and every vertex used.
    let mut used = vec![false; n];
    let mut at: Vec<u32> = Vec::with_capacity(corners);
    for p in &soup.polygons {
        let [a, b, c] = p.vertices[..] else {
            return None;
        };
        let (ca, cb, cc) = (*cluster.get(a)?, *cluster.get(b)?, *cluster.get(c)?);
        if ca == cb || cb == cc || cc == ca {
            return None;
        }
        used[a] = true;
        used[b] = true;
        used[c] = true;
        at.extend([ca as u32, cb as u32, cc as u32]);
    }
    if used.contains(&false) {
        return None;
    }
    drop(used);
    let next = |k: usize| k - k % 3 + (k + 1) % 3;
    let twin = twins(&at, n, next)?;
    // Each fan: from a corner, across its outgoing edge to the twin's
    // triangle, whose next corner sits at the same cluster. The step is a
    // permutation of the corners, so each walk returns to its start.
    let mut visited = vec![false; corners];
    let mut has_fan = vec![false; n];
    for start in 0..corners {
        if visited[start] {
            continue;
        }
        let c = at[start] as usize;
        if std::mem::replace(&mut has_fan[c], true) {
            return None; // a second fan: a pinch
        }
        let mut k = start;
        loop {
            visited[k] = true;
            k = next(twin[k] as usize);
            if k == start {
                break;
            }
        }
    }
    Some(())
}

/// The twin of each corner's outgoing edge use (the use running the other
/// way between the same two clusters), when every edge has exactly two
/// uses, one each way. A counting sort by the lower cluster, then each
/// bucket (the edges at one vertex) sorted.
fn twins(at: &[u32], clusters: usize, next: impl Fn(usize) -> usize) -> Option<Vec<u32>> {
    let ends = |k: usize| (at[k], at[next(k)]);
    let mut start = vec![0u32; clusters + 1];
    for k in 0..at.len() {
        let (a, b) = ends(k);
        start[a.min(b) as usize + 1] += 1;
    }
    for c in 0..clusters {
        start[c + 1] += start[c];
    }
    // (higher cluster, corner) of each use, by lower cluster.
    let mut uses = vec![(0u32, 0u32); at.len()];
    for k in 0..at.len() {
        let (a, b) = ends(k);
        let low = a.min(b) as usize;
        uses[start[low] as usize] = (a.max(b), k as u32);
        start[low] += 1;
    }
    let mut twin = vec![0u32; at.len()];
    let mut begin = 0;
    for &end in &start[..clusters] {
        let bucket = &mut uses[begin as usize..end as usize];
        begin = end;
        bucket.sort_unstable();
        for pair in bucket.chunk_by(|x, y| x.0 == y.0) {
            let [(_, k1), (_, k2)] = *pair else {
                return None; // an edge used once, or three times or more
            };
            if at[k1 as usize] == at[k2 as usize] {
                return None; // two uses the same way
            }
            twin[k1 as usize] = k2;
            twin[k2 as usize] = k1;
        }
    }
    Some(twin)
}
