//! The solid-level part of validation: build the winged-edge solid from the
//! faces that passed the soup checks, then measure its shells and decide
//! their nesting.

use glam::DVec3;

use super::context::Context;
use super::exact::{VolumeFilter, volume_sign, winding_numbers};
use super::report::ShellSummary;
use crate::geom::{Aabb, Sign};
use crate::spatial::Bvh;

use crate::mesh::{Polygon, PolygonSoup, Solid};

/// What the orientation check needs to know about a shell besides its
/// summary.
pub(crate) struct ShellGeometry {
    /// The exact sign of the shell's signed volume.
    pub volume_sign: Sign,
    /// The shell's first face (soup numbering).
    pub first_face: usize,
    /// "face 3 (line 17)".
    pub first_face_name: String,
}

/// The solid's shells, measured.
pub(crate) struct SolidView {
    pub shells: Vec<ShellSummary>,
    pub geometry: Vec<ShellGeometry>,
    pub volume: Option<f64>,
    pub genus: Option<i64>,
}

/// How many vertices of a shell are tried when deciding whether it lies
/// inside another (a vertex on the other shell's surface is inconclusive).
const NESTING_PROBES: usize = 16;

/// Builds the solid from the faces that count in the topology (repeats in a
/// row collapsed, duplicates and non-polygons left out).
///
/// # Errors
///
/// The build error, as text, when the faces do not form a winged-edge solid.
pub(crate) fn build(ctx: &Context) -> Result<Solid, String> {
    Solid::try_from_soup(&topology_soup(ctx)).map_err(|e| e.to_string())
}

/// Whether [`build`] succeeds, and its error when not, without building
/// the solid (`mesh::check_buildable`) and, when the context is clean,
/// without copying the soup: then the faces in the topology are the
/// soup's own, corner for corner.
///
/// # Errors
///
/// The error [`build`] returns.
pub(crate) fn check_builds(ctx: &Context) -> Result<(), String> {
    let checked = if ctx.is_clean() {
        crate::mesh::check_buildable(ctx.soup)
    } else {
        crate::mesh::check_buildable(&topology_soup(ctx))
    };
    checked.map_err(|e| e.to_string())
}

/// The faces that count in the topology, repeats in a row collapsed, as a
/// soup of their own.
fn topology_soup(ctx: &Context) -> PolygonSoup {
    PolygonSoup {
        positions: ctx.soup.positions.clone(),
        polygons: (0..ctx.face_count())
            .filter(|&f| ctx.in_topology[f])
            .map(|f| Polygon {
                vertices: ctx.corners(f).iter().copied().collect(),
                attributes: ctx.soup.polygons[f].attributes.clone(),
            })
            .collect(),
    }
}

/// Shells, volumes, genus and nesting, measured on the soup's topology (the
/// same faces, edges and vertices as the built solid, whose construction
/// guarantees they form 2-manifold shells). Computed from the context rather
/// than by walking the solid because it parallelises: on a million faces
/// this is several times faster than [`Solid::shells`].
/// Per shell: the exact-sign filter of its volume, its volume, its area and
/// its face count.
type ShellSums = (VolumeFilter, f64, f64, usize);

pub(crate) fn measure(ctx: &Context) -> SolidView {
    let faces = ctx.face_count();
    let mut sets = crate::disjoint_sets::DisjointSets::new(faces);
    for e in 0..ctx.edges.len() {
        let uses = ctx.uses(e);
        for u in &uses[1..] {
            sets.union(uses[0].face(), u.face());
        }
    }
    // Shells numbered in order of their first face.
    let mut shell_of = vec![usize::MAX; faces];
    let mut first_faces = Vec::new();
    for f in (0..faces).filter(|&f| ctx.in_topology[f]) {
        let r = sets.find(f);
        if shell_of[r] == usize::MAX {
            shell_of[r] = first_faces.len();
            first_faces.push(f);
        }
        shell_of[f] = shell_of[r];
    }
    let count = first_faces.len();
    let centre = ctx.bounds.center();
    let per_face = |f: usize| {
        let c = ctx.corners(f);
        let points: smallvec::SmallVec<[DVec3; 8]> = c.iter().map(|&v| ctx.position(v)).collect();
        let mut filter = VolumeFilter::default();
        let mut volume = 0.0;
        for i in 1..points.len() - 1 {
            filter.add(points[0], points[i], points[i + 1]);
            let (a, b, d) = (
                points[0] - centre,
                points[i] - centre,
                points[i + 1] - centre,
            );
            volume += a.dot(b.cross(d)) / 6.0;
        }
        let area = crate::geom::newell_vector_area(&points, points[0]).length();
        (filter, volume, area)
    };
    // Per chunk of faces, the sums of each run of faces of one shell, in
    // face order; combined in chunk order, so that the floating-point sums
    // (and the reports) do not depend on the number of threads.
    let runs = crate::fixed_chunks::map_chunks(faces, |range| {
        let mut runs: Vec<(usize, ShellSums)> = Vec::new();
        for f in range.filter(|&f| ctx.in_topology[f]) {
            let (filter, volume, area) = per_face(f);
            let shell = shell_of[f];
            if runs.last().is_none_or(|(s, _)| *s != shell) {
                runs.push((shell, ShellSums::default()));
            }
            if let Some((_, sums)) = runs.last_mut() {
                sums.0.merge(&filter);
                sums.1 += volume;
                sums.2 += area;
                sums.3 += 1;
            }
        }
        runs
    });
    let mut sums = vec![ShellSums::default(); count];
    for (shell, run) in runs.into_iter().flatten() {
        let slot = &mut sums[shell];
        slot.0.merge(&run.0);
        slot.1 += run.1;
        slot.2 += run.2;
        slot.3 += run.3;
    }
    let mut vertices = vec![0usize; count];
    for v in 0..ctx.soup.positions.len() {
        if let Some(&f) = ctx.vertex_faces(v).first() {
            vertices[shell_of[f as usize]] += 1;
        }
    }
    let mut edges = vec![0usize; count];
    let mut boundary = vec![0usize; count];
    for e in 0..ctx.edges.len() {
        let uses = ctx.uses(e);
        let s = shell_of[uses[0].face()];
        edges[s] += 1;
        boundary[s] += usize::from(uses.len() == 1);
    }
    // Each shell's faces, in face order: made once, when a shell's volume
    // sign or the nesting needs them (never a pass over all faces per
    // shell, which made a union of n boxes cost n²).
    let mut members: Option<Vec<Vec<usize>>> = None;
    let mut members_of = |shell: usize| -> Vec<usize> {
        members.get_or_insert_with(|| {
            let mut members = vec![Vec::new(); count];
            for f in (0..faces).filter(|&f| ctx.in_topology[f]) {
                members[shell_of[f]].push(f);
            }
            members
        })[shell]
            .clone()
    };
    let mut shells = Vec::with_capacity(count);
    let mut geometry = Vec::with_capacity(count);
    for (i, &first) in first_faces.iter().enumerate() {
        let (filter, volume, area, face_count) = sums[i];
        let closed = boundary[i] == 0;
        let chi = vertices[i] as i64 - edges[i] as i64 + face_count as i64;
        let sign = filter
            .sign()
            .unwrap_or_else(|| volume_sign(&triangles_of(ctx, &members_of(i))));
        geometry.push(ShellGeometry {
            volume_sign: sign,
            first_face: first,
            first_face_name: ctx.face_name(first),
        });
        shells.push(ShellSummary {
            faces: face_count,
            vertices: vertices[i],
            edges: edges[i],
            boundary_edges: boundary[i],
            euler_characteristic: chi,
            genus: (closed && chi % 2 == 0 && chi <= 2).then_some((2 - chi) / 2),
            volume,
            area,
            closed,
            depth: None,
            parent: None,
            first_line: ctx.face_line(first),
        });
    }
    let closed = shells.iter().filter(|s| s.closed).count();
    if closed > 1 {
        let triangles: Vec<Vec<[DVec3; 3]>> = (0..count)
            .map(|i| triangles_of(ctx, &members_of(i)))
            .collect();
        nest(&mut shells, &triangles);
    } else {
        for s in shells.iter_mut().filter(|s| s.closed) {
            s.depth = Some(0);
        }
    }
    let all_closed = shells.iter().all(|s| s.closed);
    let volume = all_closed.then(|| shells.iter().map(|s| s.volume).sum());
    let genus = if all_closed {
        shells.iter().map(|s| s.genus).sum::<Option<i64>>()
    } else {
        None
    };
    SolidView {
        shells,
        geometry,
        volume,
        genus,
    }
}

/// A fan triangulation of each face (its signed volume and winding are
/// those of the face, convex or not).
fn triangles_of(ctx: &Context, faces: &[usize]) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for &f in faces {
        let c = ctx.corners(f);
        for i in 1..c.len() - 1 {
            out.push([c[0], c[i], c[i + 1]].map(|v| ctx.position(v)));
        }
    }
    out
}

/// Depth and parent of each closed shell: how many closed shells contain it,
/// by exact winding numbers at its vertices.
fn nest(shells: &mut [ShellSummary], triangles: &[Vec<[DVec3; 3]>]) {
    let boxes: Vec<Aabb> = triangles
        .iter()
        .map(|t| Aabb::from_points(t.iter().flatten().copied()))
        .collect();
    let closed: Vec<usize> = (0..shells.len()).filter(|&i| shells[i].closed).collect();
    // The closed shells by their boxes: a shell is tested against those
    // whose boxes hold its own, found by a box query, not against all.
    let (index, order) = Bvh::build_by(closed.len(), |k| boxes[closed[k]]);
    let mut around: Vec<usize> = Vec::new();
    for &a in &closed {
        around.clear();
        index.items_overlapping(
            &boxes[a],
            |p| boxes[closed[order[p] as usize]],
            |p| around.push(closed[order[p] as usize]),
        );
        // In shell order, as the test of every pair took them.
        around.sort_unstable();
        let probes: Vec<DVec3> = triangles[a]
            .iter()
            .flatten()
            .step_by(3)
            .take(NESTING_PROBES)
            .copied()
            .collect();
        let mut depth = Some(0);
        let mut parent: Option<(usize, f64)> = None;
        for &b in &around {
            // A shell inside another lies inside its bounding box.
            let inside_box =
                boxes[b].min.cmple(boxes[a].min).all() && boxes[a].max.cmple(boxes[b].max).all();
            if a == b || !inside_box {
                continue;
            }
            // Inside when every decisive probe is inside, outside when every
            // one is outside; mixed answers mean the shells cross (reported
            // as self-intersection) and leave the depth undecided.
            let (in_box, off_box): (Vec<DVec3>, Vec<DVec3>) =
                probes.iter().partition(|&&p| boxes[b].contains(p));
            let answers: Vec<bool> = winding_numbers(&triangles[b], &in_box)
                .into_iter()
                .filter_map(|w| w.map(|w| w != 0))
                .chain(off_box.iter().map(|_| false))
                .collect();
            if answers.is_empty() || answers.iter().any(|&x| x != answers[0]) {
                depth = None;
            } else if answers[0] {
                depth = depth.map(|d| d + 1);
                let size = boxes[b].volume();
                if parent.is_none_or(|(_, s)| size < s) {
                    parent = Some((b, size));
                }
            }
        }
        shells[a].depth = depth;
        shells[a].parent = parent.map(|(b, _)| b);
    }
}
