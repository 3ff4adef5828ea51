//! Why a polygon soup cannot be built into a solid, in messages that name
//! the polygons, vertices and OBJ lines.

use glam::DVec3;
use thiserror::Error;

use crate::geom::triangulate::TriangulateError;
use crate::mesh::euler::EulerError;

/// Why a polygon soup cannot be built into a winged-edge solid.
///
/// Polygon and vertex numbers are 0-based indices into the soup; `line` is the
/// OBJ line of a polygon when the soup came from a file.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum BuildError {
    /// The soup holds no polygon at all.
    #[error("there are no polygons to build a solid from")]
    NoPolygons,
    /// A polygon with fewer than three corners.
    #[error("polygon {polygon}{} has {count} vertices; a face needs at least 3", at_line(*.line))]
    TooFewVertices {
        /// The polygon.
        polygon: usize,
        /// Its OBJ line.
        line: Option<usize>,
        /// How many vertices it has.
        count: usize,
    },
    /// A polygon refers to a vertex that does not exist.
    #[error("polygon {polygon}{} refers to vertex {index}, but there are only {len} vertices", at_line(*.line))]
    IndexOutOfRange {
        /// The polygon.
        polygon: usize,
        /// Its OBJ line.
        line: Option<usize>,
        /// The bad index.
        index: usize,
        /// The number of vertices.
        len: usize,
    },
    /// A polygon visits the same vertex twice.
    #[error("polygon {polygon}{} visits vertex {vertex} more than once", at_line(*.line))]
    RepeatedVertex {
        /// The polygon.
        polygon: usize,
        /// Its OBJ line.
        line: Option<usize>,
        /// The repeated vertex.
        vertex: usize,
    },
    /// A vertex used by a polygon has a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite position {}", crate::geom::ReadableVec(*.position))]
    NonFinitePosition {
        /// The vertex.
        vertex: usize,
        /// Its position.
        position: DVec3,
    },
    /// An edge shared by three or more polygons.
    #[error("edge {}–{} is used by {} polygons {}{}; a manifold edge has at most 2", .vertices[0], .vertices[1], .polygons.len(), capped(.polygons), at_lines(.lines))]
    NonManifoldEdge {
        /// The edge's end vertices.
        vertices: [usize; 2],
        /// Every polygon that uses the edge.
        polygons: Vec<usize>,
        /// Their OBJ lines, where known.
        lines: Vec<Option<usize>>,
    },
    /// Two polygons run an edge in the same direction: their orientations
    /// disagree.
    #[error("edge {}–{} is run in the same direction by polygons {} and {}{}: their orientations disagree", .vertices[0], .vertices[1], .polygons[0], .polygons[1], at_lines(.lines))]
    InconsistentOrientation {
        /// The edge's vertices, in the direction both polygons use.
        vertices: [usize; 2],
        /// The two polygons.
        polygons: [usize; 2],
        /// Their OBJ lines, where known.
        lines: [Option<usize>; 2],
    },
    /// A polygon given to a builder encloses no area.
    #[error("the polygon has zero area")]
    ZeroArea,
    /// A polygon given to a builder crosses itself.
    #[error("the polygon is not simple: its edges {0} and {1} meet")]
    SelfIntersecting(usize, usize),
    /// A sweep or apex that would give a flat solid.
    #[error("the sweep vector or apex lies in the polygon's plane")]
    Flat,
    /// A profile with holes given to a builder that is not a valid face: a
    /// hole not strictly inside the outer polygon, holes touching, a loop
    /// not simple.
    #[error("the profile is not a valid face: {0}")]
    InvalidProfile(#[from] TriangulateError),
    /// An Euler operator of a builder refused (the builder's own checks
    /// should have caught its input first).
    #[error(transparent)]
    Euler(#[from] EulerError),
}

fn at_line(line: Option<usize>) -> String {
    line.map(|l| format!(" (line {l})")).unwrap_or_default()
}

/// How many items of a list a message shows; the error's fields keep all.
const SHOWN: usize = 10;

/// `[3, 8, 12]`, or the first [`SHOWN`] items and `… and N more`: a fan of
/// 100,000 polygons on one edge makes a one-line message, not megabytes.
fn capped(items: &[usize]) -> String {
    let shown: Vec<String> = items.iter().take(SHOWN).map(ToString::to_string).collect();
    let more = items.len().saturating_sub(SHOWN);
    if more == 0 {
        format!("[{}]", shown.join(", "))
    } else {
        format!("[{}, … and {more} more]", shown.join(", "))
    }
}

/// " (lines 4, 9)" for the known lines of several polygons (the first
/// [`SHOWN`], then how many more), or nothing.
fn at_lines(lines: &[Option<usize>]) -> String {
    let known: Vec<usize> = lines.iter().flatten().copied().collect();
    if known.is_empty() {
        String::new()
    } else {
        let listed = capped(&known);
        format!(" (lines {})", &listed[1..listed.len() - 1])
    }
}
