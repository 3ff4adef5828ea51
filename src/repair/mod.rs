//! Valid solids from imperfect soups, exactly, with a report of what
//! changed.
//!
//! The stages, one file each, in the order they run:
//!
//! 1. `clean`: bit-identical positions merged; polygons that bound
//!    nothing dropped (fewer than three corners, zero area, repeats, a
//!    polygon with its reverse).
//! 2. `orient` (consistency): each piece wound so that neighbours across
//!    an edge of two polygons run it in opposite directions.
//! 3. `fill`: each hole (a loop of unpartnered edge uses) triangulated
//!    exactly, optionally only up to `max_hole_edges` edges.
//! 4. `orient` (outward): each closed piece turned to face out, a piece
//!    nested in an odd number of others to face in.
//! 5. resolve: the soup is arranged
//!    against itself by the boolean's stages and reduced to the boundary
//!    of the region where its winding number is positive
//!    ([`crate::boolean::arrange_soup`]; Zhou, Grinspun, Zorin and
//!    Jacobson 2016); the result is proven valid by the boolean's output
//!    stage.
//!
//! The winding number `w` of the soup after stage 4 is an integer off its
//! surface (every edge is run as often one way as the other), and the
//! result holds exactly the points where `w > ½`.

mod clean;
mod fill;
mod orient;
mod report;

use thiserror::Error;

use crate::boolean::{BooleanError, MAX_CONTACTS, arrange_soup, prove};
use crate::mesh::{PolygonSoup, Solid};
use crate::validate::Report;

pub use report::{DropReason, DroppedPolygon, HoleLoop, OpenReason, RepairReport, TurnedOver};

/// How to repair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RepairOptions {
    /// Fill only holes of at most this many edges; larger ones stay open
    /// and are reported (the result is then no solid). `None`: fill all.
    pub max_hole_edges: Option<usize>,
    /// Resolve self-intersections and overlapping or nested shells by the
    /// arrangement (on by default). Off, a soup that is not a valid solid
    /// after filling and orienting is refused.
    pub resolve: bool,
    /// The most pairs of touching triangles the arrangement takes on (as
    /// [`crate::boolean::BooleanOptions::max_contacts`]).
    pub max_contacts: usize,
}

impl Default for RepairOptions {
    fn default() -> RepairOptions {
        RepairOptions {
            max_hole_edges: None,
            resolve: true,
            max_contacts: MAX_CONTACTS,
        }
    }
}

/// A repaired soup.
#[derive(Clone, Debug)]
pub struct Repaired {
    /// The valid solid (possibly empty: the soup encloses nothing); `None`
    /// when holes were left open, so that no solid could be made.
    pub solid: Option<Solid>,
    /// The soup after cleaning, orienting and filling (before resolving):
    /// what the result is the solid of.
    pub soup: PolygonSoup,
    /// The validator's report on the solid.
    pub validation: Option<Report>,
    /// What changed.
    pub report: RepairReport,
}

/// Why a soup could not be repaired.
#[derive(Debug, Error)]
pub enum RepairError {
    /// A polygon names a vertex past the positions.
    #[error("polygon {polygon} names vertex {vertex}, but the soup has {count} vertices")]
    IndexOutOfRange {
        /// The polygon (0-based).
        polygon: usize,
        /// The vertex index it names (0-based).
        vertex: usize,
        /// How many vertices there are.
        count: usize,
    },
    /// A polygon uses a vertex with a NaN or infinite coordinate.
    #[error("polygon {polygon} uses vertex {vertex}, whose position is not finite")]
    NonFinitePosition {
        /// The polygon (0-based).
        polygon: usize,
        /// The vertex (0-based).
        vertex: usize,
    },
    /// Without resolving, the soup is no valid solid.
    #[error(
        "the soup is no valid solid after cleaning, orienting and filling ({0}); resolving (on by default) would make one"
    )]
    NotASolid(String),
    /// The arrangement failed.
    #[error("resolving: {0}")]
    Resolve(#[from] BooleanError),
}

/// Repairs `soup` into a valid solid (see the module's documentation).
///
/// # Errors
///
/// [`RepairError`]: bad indices or positions; a soup that is no solid
/// without resolving; the arrangement's errors.
pub fn repair(soup: &PolygonSoup, options: &RepairOptions) -> Result<Repaired, RepairError> {
    let clock = std::time::Instant::now();
    let mut stage_seconds = Vec::new();
    let mut lap = |name: &'static str, clock: &mut std::time::Instant| {
        stage_seconds.push((name, clock.elapsed().as_secs_f64()));
        *clock = std::time::Instant::now();
    };
    let mut clock = clock;
    let cleaned = clean::clean(soup)?;
    lap("clean", &mut clock);
    let origin = cleaned.origin;
    let mut soup = cleaned.soup;
    let mut report = RepairReport {
        welded: cleaned.welded,
        dropped: cleaned.dropped,
        ..RepairReport::default()
    };
    let (turned, non_orientable) = orient::make_consistent(&mut soup);
    report.non_orientable_pieces = non_orientable;
    if !turned.is_empty() {
        report.turned_over.push(TurnedOver {
            polygons: sorted(turned.iter().map(|&p| origin[p])),
            whole_piece: false,
        });
    }
    lap("orient", &mut clock);
    let filled = fill::fill(&mut soup, options.max_hole_edges);
    lap("fill", &mut clock);
    let input_of = |p: usize| origin[p];
    report.filled = filled
        .filled
        .into_iter()
        .map(|h| HoleLoop {
            next_to: input_of(h.next_to),
            ..h
        })
        .collect();
    report.left_open = filled
        .left_open
        .into_iter()
        .map(|(h, why)| {
            (
                HoleLoop {
                    next_to: input_of(h.next_to),
                    ..h
                },
                why,
            )
        })
        .collect();
    for piece in orient::face_out(&mut soup) {
        let polygons = sorted(piece.into_iter().filter_map(|p| origin.get(p).copied()));
        if !polygons.is_empty() {
            report.turned_over.push(TurnedOver {
                polygons,
                whole_piece: true,
            });
        }
    }
    lap("face out", &mut clock);
    let all: Vec<usize> = (0..soup.polygons.len()).collect();
    let centre = crate::geom::Aabb::from_points(soup.positions.iter().copied()).center();
    report.volume_before = if soup.positions.is_empty() {
        0.0
    } else {
        orient::signed_volume(&soup, &all, centre)
    };
    if !report.left_open.is_empty() {
        return Ok(Repaired {
            solid: None,
            soup,
            validation: None,
            report,
        });
    }
    report.stage_seconds = stage_seconds;
    if !options.resolve {
        // The soup as it is, if it is a valid solid.
        let solid =
            Solid::try_from_soup(&soup).map_err(|e| RepairError::NotASolid(e.to_string()))?;
        let validation = prove(&solid).map_err(|e| RepairError::NotASolid(e.to_string()))?;
        report.volume_after = solid.volume();
        return Ok(finish(solid, soup, validation, report));
    }
    // Always arranged: on a soup that is already a valid solid nothing is
    // cut and its faces come back as they were, and finding that out by
    // validating first would cost as much as the arrangement's contacts.
    let arranged = arrange_soup(&soup, options.max_contacts)?;
    report.resolved = true;
    report
        .stage_seconds
        .extend(arranged.stats.stages().into_iter().skip(1));
    report.crossing_pairs = arranged
        .crossing_polygons
        .iter()
        .filter_map(|&(p, q)| {
            let (a, b) = (origin.get(p)?, origin.get(q)?);
            Some(((*a).min(*b), (*a).max(*b)))
        })
        .collect();
    report.crossing_pairs.sort_unstable();
    report.crossing_pairs.dedup();
    report.volume_after = arranged.solid.volume();
    Ok(finish(arranged.solid, soup, arranged.report, report))
}

/// The repaired result, saying why when it is empty.
fn finish(
    solid: Solid,
    soup: PolygonSoup,
    validation: Report,
    mut report: RepairReport,
) -> Repaired {
    if solid.face_count() == 0 {
        report.empty_because = Some(if soup.polygons.is_empty() {
            "no polygon bounds anything after cleaning".to_string()
        } else {
            "the soup encloses no volume: its winding number is 0 everywhere off its surface (a sheet, or shells that cancel)".to_string()
        });
        report.volume_after = 0.0;
    }
    Repaired {
        solid: Some(solid),
        soup,
        validation: Some(validation),
        report,
    }
}

/// The items, sorted.
fn sorted(items: impl IntoIterator<Item = usize>) -> Vec<usize> {
    let mut v: Vec<usize> = items.into_iter().collect();
    v.sort_unstable();
    v
}
