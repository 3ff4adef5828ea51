//! Why a sweep, revolve or loft cannot be built, naming the argument.

use glam::DVec3;
use thiserror::Error;

use crate::curve::CurveError;
use crate::geom::TriangulateError;

use crate::mesh::BuildError;

/// Which argument of a sweep, revolve or loft an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Argument {
    /// The profile polygon (or curve) of a sweep or revolve.
    Profile,
    /// The path of a sweep.
    Path,
    /// One section of a loft, by index.
    Section(usize),
    /// One hole of a sweep's profile, by index.
    Hole(usize),
}

impl std::fmt::Display for Argument {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Argument::Profile => write!(f, "the profile"),
            Argument::Path => write!(f, "the path"),
            Argument::Section(i) => write!(f, "section {i}"),
            Argument::Hole(i) => write!(f, "hole {i} of the profile"),
        }
    }
}

/// Why a sweep, revolve or loft cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SweepError {
    /// A curve argument is bad or cannot be flattened.
    #[error("{argument}: {source}")]
    Curve {
        /// The argument.
        argument: Argument,
        /// What is wrong with it.
        #[source]
        source: CurveError,
    },
    /// A polygon with fewer than three vertices.
    #[error("{argument} has {count} vertices; at least 3 are needed")]
    TooFewVertices {
        /// The polygon.
        argument: Argument,
        /// How many vertices it has.
        count: usize,
    },
    /// A polygon vertex with a NaN or infinite coordinate.
    #[error("{argument}: vertex {vertex} is not finite")]
    NonFiniteVertex {
        /// The polygon.
        argument: Argument,
        /// The vertex.
        vertex: usize,
    },
    /// Two vertices of a polygon at the same position.
    #[error("{argument}: vertices {first} and {second} are at the same position")]
    RepeatedVertex {
        /// The polygon.
        argument: Argument,
        /// The first of the two.
        first: usize,
        /// The second.
        second: usize,
    },
    /// A polygon with zero area (all its vertices collinear).
    #[error("{argument} has zero area")]
    ZeroArea {
        /// The polygon.
        argument: Argument,
    },
    /// A polygon whose edges cross or touch (edge `i` runs from vertex `i`
    /// to vertex `i + 1`).
    #[error("{argument} is not simple: its edges {} and {} meet", .edges[0], .edges[1])]
    SelfIntersecting {
        /// The polygon.
        argument: Argument,
        /// The two edges that meet.
        edges: [usize; 2],
    },
    /// A polygon vertex farther from the polygon's plane than the planarity
    /// tolerance, or off the plane a profile curve must lie in.
    #[error(
        "{argument} is not planar: vertex {vertex} is {} from its plane (limit {})", crate::geom::Readable(*.deviation), crate::geom::Readable(*.limit)
    )]
    NonPlanar {
        /// The polygon.
        argument: Argument,
        /// The vertex.
        vertex: usize,
        /// Its distance from the plane.
        deviation: f64,
        /// The largest distance allowed.
        limit: f64,
    },
    /// A sweep path of zero length (every point of it the same).
    #[error("the path has zero length: it stays at {}", crate::geom::ReadableVec(*.point))]
    ZeroLengthPath {
        /// Where it stays.
        point: DVec3,
    },
    /// A sweep path that ends where it starts: the end caps would meet.
    #[error("the path is closed (it ends at its start {}); closed sweeps are not supported", crate::geom::ReadableVec(*.point))]
    ClosedPath {
        /// The start and end.
        point: DVec3,
    },
    /// A sweep path whose tangent vanishes at a sample, so no frame is
    /// defined there.
    #[error("the path's tangent is zero at parameter {}", crate::geom::Readable(*.parameter))]
    ZeroTangent {
        /// The path parameter.
        parameter: f64,
    },
    /// Consecutive sections fold over each other: the solid would intersect
    /// itself there.
    #[error("the solid folds onto itself at section {section}{}: vertex {vertex} of one section is not strictly beyond the plane of its neighbour", at_parameter(*.parameter))]
    Folds {
        /// The later of the two sections.
        section: usize,
        /// The path parameter of that section (sweeps only).
        parameter: Option<f64>,
        /// The offending vertex (a profile index).
        vertex: usize,
    },
    /// Loft sections wound in opposite directions.
    #[error("section {section} is wound against section {previous}")]
    SectionWinding {
        /// The section.
        section: usize,
        /// The section before it.
        previous: usize,
    },
    /// Fewer than two loft sections.
    #[error("{count} sections: a loft needs at least 2")]
    TooFewSections {
        /// How many were given.
        count: usize,
    },
    /// A loft section with another vertex count than the first.
    #[error("section {section} has {count} vertices, section 0 has {expected}")]
    SectionSize {
        /// The section.
        section: usize,
        /// Its vertex count.
        count: usize,
        /// Section 0's vertex count.
        expected: usize,
    },
    /// A revolve axis whose direction is zero or not finite, or whose
    /// radial direction is parallel to it.
    #[error("the axis is degenerate: direction {}, radial {}", crate::geom::ReadableVec(*.direction), crate::geom::ReadableVec(*.radial))]
    BadAxis {
        /// The axis direction.
        direction: DVec3,
        /// The radial direction (angle 0).
        radial: DVec3,
    },
    /// A revolve profile vertex on the wrong side of the axis.
    #[error("profile vertex {vertex} has radius {} < 0: the profile crosses the axis", crate::geom::Readable(*.radius))]
    CrossesAxis {
        /// The vertex.
        vertex: usize,
        /// Its distance coordinate.
        radius: f64,
    },
    /// A revolve profile touching the axis at a single vertex in a full
    /// turn: the solid would pinch to a point there.
    #[error("profile vertex {vertex} touches the axis alone: a full turn pinches there")]
    PinchOnAxis {
        /// The vertex.
        vertex: usize,
    },
    /// A revolve angle outside `(0, 2π]`.
    #[error("the angle {} is not in (0, 2π]", crate::geom::Readable(*.angle))]
    BadAngle {
        /// The angle in radians.
        angle: f64,
    },
    /// A revolve segment count out of range.
    #[error("{segments} segments: between {minimum} and {limit} are allowed")]
    BadSegments {
        /// The count given.
        segments: usize,
        /// The least count (3 for a full turn, else 1).
        minimum: usize,
        /// The largest ([`MAX_SEGMENTS`](crate::curve::MAX_SEGMENTS)).
        limit: usize,
    },
    /// A turn whose validation would cost more than the limit: many
    /// steps around with profile edges that run far towards or away from
    /// the axis make long, thin quadrilaterals, each of whose boxes
    /// overlaps those of its neighbours across a wide angle, so checking
    /// the solid for self-intersection grows with the square of the steps
    /// ([`MAX_TURN_STEPS`](crate::shape::MAX_TURN_STEPS),
    /// [`MAX_TURN_SLIVERS`](crate::shape::MAX_TURN_SLIVERS)).
    #[error(
        "{segments} steps around make {slivers} sliver pieces to check (limits: {step_limit} steps, {sliver_limit} pieces); use fewer segments or a larger tolerance"
    )]
    TurnTooFine {
        /// The steps around.
        segments: usize,
        /// The estimated pieces: per profile edge, the steps times how many
        /// of its quadrilaterals' widths fit in its radial extent.
        slivers: u64,
        /// [`MAX_TURN_STEPS`](crate::shape::MAX_TURN_STEPS).
        step_limit: usize,
        /// [`MAX_TURN_SLIVERS`](crate::shape::MAX_TURN_SLIVERS).
        sliver_limit: u64,
    },
    /// The solid would have more vertices than the stated limit.
    #[error("the solid would have {vertices} vertices, more than {limit}")]
    TooLarge {
        /// How many it would have.
        vertices: usize,
        /// The limit ([`MAX_VERTICES`](super::MAX_VERTICES)).
        limit: usize,
    },
    /// Two parts of a sweep or loft that are not neighbours meet: the
    /// band of side faces after section `sections[0]` (or an end cap, for
    /// the first or last section) touches the one after `sections[1]`.
    #[error("the solid meets itself: {}{}", collision_text(.parts), at_parameters(*.parameters))]
    Collides {
        /// The parts the two meeting faces belong to, in order along the
        /// solid (equal when one band of side faces crosses itself, as a
        /// twisted loft's does).
        parts: [SolidPart; 2],
        /// The path parameters of those parts (sweeps only): of the two
        /// parts' first sections, or of the band's two sections when one
        /// band crosses itself.
        parameters: Option<[f64; 2]>,
    },
    /// An end cap could not be triangulated for the self-intersection test.
    #[error("an end cap cannot be triangulated: {0}")]
    Cap(#[from] TriangulateError),
    /// The faces could not be built into a winged-edge solid.
    #[error("the faces do not form a solid: {0}")]
    Build(#[from] BuildError),
}

/// A part of the boundary of a swept or lofted solid, as a collision names
/// it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SolidPart {
    /// The end cap at a section (the first or the last).
    Cap(usize),
    /// The band of side faces from a section to the next one.
    Side(usize),
}

impl SolidPart {
    /// The section the part starts at.
    #[must_use]
    pub fn section(self) -> usize {
        match self {
            SolidPart::Cap(s) | SolidPart::Side(s) => s,
        }
    }
}

impl std::fmt::Display for SolidPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            SolidPart::Cap(s) => write!(f, "the cap at section {s}"),
            SolidPart::Side(s) => write!(f, "the side between sections {s} and {}", s + 1),
        }
    }
}

fn collision_text([a, b]: &[SolidPart; 2]) -> String {
    if a == b {
        format!("{a} crosses itself")
    } else {
        format!("{a} meets {b}")
    }
}

fn at_parameters(parameters: Option<[f64; 2]>) -> String {
    parameters
        .map(|[a, b]| {
            format!(
                " (path parameters {} and {})",
                crate::geom::Readable(a),
                crate::geom::Readable(b)
            )
        })
        .unwrap_or_default()
}

fn at_parameter(parameter: Option<f64>) -> String {
    parameter
        .map(|t| format!(" (path parameter {})", crate::geom::Readable(t)))
        .unwrap_or_default()
}
