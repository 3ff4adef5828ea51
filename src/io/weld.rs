//! Welding coincident vertices of an imported soup, only where it closes
//! open edges.
//!
//! Exporters often split vertices (one copy per face, for normals or texture
//! seams), which leaves every edge open. A weld merges such copies, but a
//! careless weld damages valid input: two solids touching at a corner would
//! be pinched into one non-manifold vertex, and a face with two coincident
//! corners would repeat a vertex. So the weld here is conservative:
//!
//! 1. Vertices are grouped into *clusters*: bit-identical positions
//!    ([`WeldMode::Exact`], `-0.0` counts as `0.0`) or positions within a
//!    distance ([`WeldMode::Within`]).
//! 2. Two open edge uses are glued only when they join the same two clusters
//!    in opposite directions and no other edge use joins those clusters; the
//!    glue merges their end vertices pairwise. So no edge ever gets a third
//!    face and no orientation is contradicted.
//! 3. A merged vertex whose faces would form more than one fan (a pinch), or
//!    that would appear twice in one face, is not merged; the refusal is
//!    reported ([`WeldRefusal`]). This repeats until nothing is refused.

use crate::disjoint_sets::DisjointSets;
use std::collections::HashMap;

use glam::DVec3;

use super::weld_closed::clusters_close_triangles;
use super::weld_groups::{exact_clusters, glue_candidates};
use crate::geom::{Aabb, Tolerance};
use crate::mesh::PolygonSoup;

/// Which vertices a weld may merge.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum WeldMode {
    /// Merge nothing.
    None,
    /// Merge vertices with bit-identical positions (the default).
    #[default]
    Exact,
    /// Merge vertices closer than `tolerance.weld × diagonal` of the model's
    /// bounding box (see [`Tolerance::weld_distance`]); pairs are linked
    /// transitively, so a chain of close vertices forms one cluster.
    Within(Tolerance),
}

/// A merge the weld refused, so that it is never silent.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WeldRefusal {
    /// Merging would make a face visit a vertex twice.
    WouldRepeatVertex {
        /// The face (0-based number in the file).
        face: usize,
        /// Its OBJ line.
        line: Option<usize>,
    },
    /// Merging would join separate fans of faces at one vertex.
    WouldPinch {
        /// The vertex: the file's number of the first copy (1-based OBJ
        /// number; the other formats count from 0, STL by corners).
        vertex: usize,
        /// Its line, in the text formats.
        line: Option<usize>,
    },
}

impl std::fmt::Display for WeldRefusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            WeldRefusal::WouldRepeatVertex { face, line } => write!(
                f,
                "not welded: face {face}{} would visit a vertex twice",
                line.map(|l| format!(" (line {l})")).unwrap_or_default()
            ),
            WeldRefusal::WouldPinch {
                vertex,
                line: Some(line),
            } => write!(
                f,
                "not welded: the copies of OBJ vertex #{vertex} (line {line}) would join separate fans of faces (a pinch)"
            ),
            WeldRefusal::WouldPinch { vertex, line: None } => write!(
                f,
                "not welded: the copies of vertex {vertex} would join separate fans of faces (a pinch)"
            ),
        }
    }
}

/// What a weld did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WeldReport {
    /// The mode used.
    pub mode: WeldMode,
    /// How many vertices were merged into others (vertices before minus
    /// vertices after).
    pub merged: usize,
    /// Merges refused, with the reason.
    pub refused: Vec<WeldRefusal>,
}

/// Welds `soup` as `mode` says and compacts it: each merged class becomes its
/// first copy. Returns the soup, the `v` line (when `vertex_lines` has one
/// per vertex; else nothing) and 1-based number in `soup` of each new
/// vertex, and the report.
pub(crate) fn weld(
    soup: PolygonSoup,
    vertex_lines: Vec<usize>,
    mode: WeldMode,
) -> (PolygonSoup, Vec<usize>, Vec<usize>, WeldReport) {
    let n = soup.positions.len();
    let numbers: Vec<usize> = (1..=n).collect();
    let vertex_lines = if vertex_lines.len() == n {
        vertex_lines
    } else {
        Vec::new()
    };
    let Some(cluster) = clusters(&soup.positions, mode) else {
        let report = WeldReport {
            mode,
            ..WeldReport::default()
        };
        return (soup, vertex_lines, numbers, report);
    };
    let mut shared = vec![false; n];
    for (v, &c) in cluster.iter().enumerate() {
        if c != v {
            shared[c] = true;
            shared[v] = true;
        }
    }
    if !shared.contains(&true) {
        // No two vertices coincide: nothing to weld (the common case).
        let report = WeldReport {
            mode,
            ..WeldReport::default()
        };
        return (soup, vertex_lines, numbers, report);
    }
    if mode == WeldMode::Exact && clusters_close_triangles(&soup, &cluster) {
        // Every cluster merges whole and nothing is refused (weld_closed.rs
        // says why); `cluster` holds each class's smallest member.
        let uf = DisjointSets::from_roots(cluster);
        return compact(soup, vertex_lines, numbers, uf, mode, Vec::new());
    }
    let (uf, refused) = glue(&soup, &cluster, &shared, &vertex_lines);
    compact(soup, vertex_lines, numbers, uf, mode, refused)
}

/// The general weld: glue pairs of open edges between clusters, refuse
/// merges that repeat a vertex in a face or pinch, and glue again without
/// the refused classes until nothing more is refused. Returns the classes
/// and the refusals.
fn glue(
    soup: &PolygonSoup,
    cluster: &[usize],
    shared: &[bool],
    vertex_lines: &[usize],
) -> (DisjointSets, Vec<WeldRefusal>) {
    let n = soup.positions.len();
    let candidates = glue_candidates(soup, cluster, shared);
    let incident = incident_polygons(soup);
    let mut blocked = vec![false; n];
    let mut refused = Vec::new();
    loop {
        let mut uf = DisjointSets::new(n);
        for &[a1, b1, a2, b2] in &candidates {
            if ![a1, b1, a2, b2].iter().any(|&v| blocked[v]) {
                uf.union(a1, b2);
                uf.union(b1, a2);
            }
        }
        let before = refused.len();
        refuse_repeats(soup, &mut uf, &mut blocked, &mut refused);
        refuse_pinches(
            soup,
            &incident,
            vertex_lines,
            &mut uf,
            &mut blocked,
            &mut refused,
        );
        if refused.len() == before {
            break (uf, refused);
        }
    }
}

/// The cluster of each vertex, or `None` when nothing may be merged.
fn clusters(positions: &[DVec3], mode: WeldMode) -> Option<Vec<usize>> {
    match mode {
        WeldMode::None => None,
        WeldMode::Within(tolerance) => {
            let diagonal = Aabb::from_points(positions.iter().copied()).diagonal();
            let d = tolerance.weld_distance(diagonal);
            if d.is_nan() || d <= 0.0 || !d.is_finite() {
                return clusters(positions, WeldMode::Exact);
            }
            // `as_i64vec3` saturates, and neighbours are found with
            // saturating steps: a tolerance so small that cells overflow
            // `i64` (`--weld 1e-300`) only puts far-apart vertices in one
            // cell, where the distance test still decides.
            let cell = |p: DVec3| (p / d).floor().as_i64vec3();
            let mut grid: HashMap<glam::I64Vec3, Vec<usize>> = HashMap::new();
            let mut uf = DisjointSets::new(positions.len());
            for (i, &p) in positions.iter().enumerate() {
                let c = cell(p);
                for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            let key = c.saturating_add(glam::I64Vec3::new(dx, dy, dz));
                            if let Some(list) = grid.get(&key) {
                                for &j in list {
                                    if positions[j].distance(p) <= d {
                                        uf.union(i, j);
                                    }
                                }
                            }
                        }
                    }
                }
                grid.entry(c).or_default().push(i);
            }
            Some((0..positions.len()).map(|i| uf.find(i)).collect())
        }
        WeldMode::Exact => Some(exact_clusters(positions)),
    }
}

/// Vertex → polygons using it, as offsets into one list.
fn incident_polygons(soup: &PolygonSoup) -> (Vec<usize>, Vec<usize>) {
    let n = soup.positions.len();
    let mut offsets = vec![0usize; n + 1];
    for p in &soup.polygons {
        for &v in &p.vertices {
            offsets[v + 1] += 1;
        }
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut fill = offsets.clone();
    let mut list = vec![0usize; offsets[n]];
    for (index, p) in soup.polygons.iter().enumerate() {
        for &v in &p.vertices {
            list[fill[v]] = index;
            fill[v] += 1;
        }
    }
    (offsets, list)
}

/// Blocks every member of the classes whose roots are given: one pass over
/// the vertices however many classes are blocked.
fn block_classes(uf: &mut DisjointSets, blocked: &mut [bool], roots: &[usize]) {
    if roots.is_empty() {
        return;
    }
    let roots: std::collections::HashSet<usize> = roots.iter().copied().collect();
    for (v, flag) in blocked.iter_mut().enumerate() {
        if roots.contains(&uf.find(v)) {
            *flag = true;
        }
    }
}

fn refuse_repeats(
    soup: &PolygonSoup,
    uf: &mut DisjointSets,
    blocked: &mut [bool],
    refused: &mut Vec<WeldRefusal>,
) {
    let mut roots: Vec<usize> = Vec::new();
    let mut bad_roots = Vec::new();
    for (index, p) in soup.polygons.iter().enumerate() {
        roots.clear();
        roots.extend(p.vertices.iter().map(|&v| uf.find(v)));
        let mut merged_twice = None;
        for (i, &r) in roots.iter().enumerate() {
            let original_repeat = p.vertices[..i].contains(&p.vertices[i]);
            if roots[..i].contains(&r) && !original_repeat {
                merged_twice = Some(r);
            }
        }
        if let Some(r) = merged_twice {
            bad_roots.push(r);
            refused.push(WeldRefusal::WouldRepeatVertex {
                face: p.attributes.source_index.unwrap_or(index),
                line: p.attributes.line,
            });
        }
    }
    block_classes(uf, blocked, &bad_roots);
}

fn refuse_pinches(
    soup: &PolygonSoup,
    incident: &(Vec<usize>, Vec<usize>),
    vertex_lines: &[usize],
    uf: &mut DisjointSets,
    blocked: &mut [bool],
    refused: &mut Vec<WeldRefusal>,
) {
    let n = blocked.len();
    let roots: Vec<usize> = (0..n).map(|v| uf.find(v)).collect();
    // The members of each class of two or more, grouped by root (a
    // counting sort: roots in increasing order, members in order).
    let mut offsets = vec![0usize; n + 1];
    for (v, &r) in roots.iter().enumerate() {
        if r != v {
            offsets[r + 1] += 1;
        }
    }
    for r in 0..n {
        if offsets[r + 1] > 0 {
            offsets[r + 1] += 1; // the root itself
        }
    }
    for r in 0..n {
        offsets[r + 1] += offsets[r];
    }
    let mut fill = offsets.clone();
    let mut members = vec![0usize; offsets[n]];
    for (v, &r) in roots.iter().enumerate() {
        if offsets[r + 1] > offsets[r] {
            members[fill[r]] = v;
            fill[r] += 1;
        }
    }
    let mut bad_roots = Vec::new();
    // Buffers reused for every class.
    let mut polygons: Vec<usize> = Vec::new();
    let mut by_neighbour: Vec<(usize, usize)> = Vec::new();
    let mut fans: Vec<usize> = Vec::new();
    for root in 0..n {
        let class = &members[offsets[root]..offsets[root + 1]];
        if class.is_empty() {
            continue;
        }
        polygons.clear();
        for &m in class {
            polygons.extend_from_slice(&incident.1[incident.0[m]..incident.0[m + 1]]);
        }
        polygons.sort_unstable();
        polygons.dedup();
        // Each polygon touches the vertex through its two edges there; two
        // polygons sharing such an edge belong to one fan.
        by_neighbour.clear();
        for (slot, &index) in polygons.iter().enumerate() {
            let p = &soup.polygons[index];
            let k = p.vertices.len();
            for i in 0..k {
                if roots[p.vertices[i]] == root {
                    for j in [(i + 1) % k, (i + k - 1) % k] {
                        let other = roots[p.vertices[j]];
                        if other != root {
                            by_neighbour.push((other, slot));
                        }
                    }
                }
            }
        }
        by_neighbour.sort_unstable();
        fans.clear();
        fans.extend(0..polygons.len());
        let find = |fans: &mut Vec<usize>, mut x: usize| {
            while fans[x] != x {
                fans[x] = fans[fans[x]];
                x = fans[x];
            }
            x
        };
        for group in by_neighbour.chunk_by(|a, b| a.0 == b.0) {
            for w in group.windows(2) {
                let (a, b) = (find(&mut fans, w[0].1), find(&mut fans, w[1].1));
                fans[a.max(b)] = a.min(b);
            }
        }
        let count = (0..polygons.len()).filter(|&i| fans[i] == i).count();
        if count > 1 {
            refused.push(WeldRefusal::WouldPinch {
                vertex: root + 1,
                line: vertex_lines.get(root).copied(),
            });
            bad_roots.push(root);
        }
    }
    block_classes(uf, blocked, &bad_roots);
}

fn compact(
    soup: PolygonSoup,
    vertex_lines: Vec<usize>,
    numbers: Vec<usize>,
    mut uf: DisjointSets,
    mode: WeldMode,
    refused: Vec<WeldRefusal>,
) -> (PolygonSoup, Vec<usize>, Vec<usize>, WeldReport) {
    let n = soup.positions.len();
    let mut new_index = vec![usize::MAX; n];
    let mut positions = Vec::with_capacity(n);
    let mut lines = Vec::with_capacity(n);
    let mut new_numbers = Vec::with_capacity(n);
    for v in 0..n {
        let r = uf.find(v);
        if r == v {
            new_index[v] = positions.len();
            positions.push(soup.positions[v]);
            if let Some(&line) = vertex_lines.get(v) {
                lines.push(line);
            }
            new_numbers.push(numbers[v]);
        } else {
            // Roots are the smallest member, so they were numbered first.
            new_index[v] = new_index[r];
        }
    }
    let merged = n - positions.len();
    let mut polygons = soup.polygons;
    for p in &mut polygons {
        for v in &mut p.vertices {
            *v = new_index[*v];
        }
    }
    let report = WeldReport {
        mode,
        merged,
        refused,
    };
    (
        PolygonSoup {
            positions,
            polygons,
        },
        lines,
        new_numbers,
        report,
    )
}

#[cfg(test)]
#[path = "weld_tests.rs"]
mod tests;
