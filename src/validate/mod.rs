//! Validation of imported polyhedra: named checks over the soup and over the
//! winged-edge solid, every instance located, and a graded verdict.
//!
//! Data flow: [`PolygonSoup`] (with OBJ lines) → soup checks (they work on
//! anything: non-manifold edges, pinches, holes) → the faces that are
//! polygons are built into a [`Solid`] → solid checks
//! (shell orientation against nesting) and measures (shells, Euler
//! characteristic, genus, volume, area) → [`Report`].
//!
//! Each check lives in its own file under `checks/`, named after what is
//! wrong; see [`Rule`] for the list and for how overlapping defects are
//! attributed to exactly one rule.
//!
//! Faces with rings (holes through a face) exist only in solids made
//! through the API; [`check_rings`] judges them ([`RingRule`]).

mod checks;
mod context;
mod exact;
mod json;
mod report;
mod rings;
mod solid_view;

use thiserror::Error;

use crate::geom::Tolerance;
use crate::io::ObjImport;
use crate::mesh::{PolygonSoup, Solid};

pub use json::report_json;
pub use report::{Report, Rule, ShellSummary, Validity, Violation};
pub use rings::{RingRule, RingViolation, check_rings};

/// What to judge and how strictly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The planarity tolerance (`tolerance.planarity`, a fraction of the
    /// model's bounding-box diagonal) used by [`Rule::NonPlanarFace`].
    pub tolerance: Tolerance,
    /// Whether to run the self-intersection check (on by default).
    pub self_intersection: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            tolerance: Tolerance::default(),
            self_intersection: true,
        }
    }
}

/// Why a soup cannot be validated at all (an [`ObjImport`] never has these).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ValidateError {
    /// A polygon refers to a vertex that does not exist.
    #[error("polygon {polygon} refers to vertex {index}, but there are only {len} vertices")]
    IndexOutOfRange {
        /// The polygon.
        polygon: usize,
        /// The bad index.
        index: usize,
        /// The number of vertices.
        len: usize,
    },
    /// More vertices, faces or corners than validation can index.
    #[error("{count} {what}: more than validation supports ({max})")]
    TooLarge {
        /// What there are too many of.
        what: &'static str,
        /// How many there are.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// A vertex position is NaN or infinite.
    #[error("vertex {vertex} has a non-finite position")]
    NonFinite {
        /// The vertex.
        vertex: usize,
    },
}

/// Validates an imported OBJ file; messages name OBJ lines.
///
/// # Errors
///
/// [`ValidateError::TooLarge`] for more than 2³² − 1 vertices, faces or
/// corners.
pub fn validate_import(import: &ObjImport, options: &Options) -> Result<Report, ValidateError> {
    validate_soup(&import.soup, Some(&import.vertex_lines), options)
}

/// Validates a polygon soup; `vertex_lines` (one per position) lets
/// messages name the `v` line of a vertex.
///
/// # Errors
///
/// [`ValidateError`] when an index is out of range, a position is not
/// finite or the soup is too large (nothing can be judged then).
pub fn validate_soup(
    soup: &PolygonSoup,
    vertex_lines: Option<&[usize]>,
    options: &Options,
) -> Result<Report, ValidateError> {
    check_soup(soup)?;
    let lines = vertex_lines.filter(|l| l.len() == soup.positions.len());
    Ok(run(soup, lines, options, None, Keep::ReportOnly).0)
}

/// [`validate_soup`] with the default options, the self-intersection check
/// restricted to pairs of faces with at least one marked in `changed`
/// (by polygon index): for a surface made by editing ones known to be
/// valid and apart (a boolean's result), whose unchanged faces cannot meet
/// each other. Every other rule runs on the whole soup.
///
/// # Errors
///
/// As for [`validate_soup`].
pub(crate) fn validate_soup_near_changed(
    soup: &PolygonSoup,
    changed: &[bool],
) -> Result<Report, ValidateError> {
    check_soup(soup)?;
    Ok(run(
        soup,
        None,
        &Options::default(),
        Some(changed),
        Keep::ReportOnly,
    )
    .0)
}

/// Validates an imported OBJ file and also returns the winged-edge solid
/// when its faces could be built into one (so that callers need not build
/// it again).
///
/// # Errors
///
/// As for [`validate_import`].
pub fn validate_and_build(
    import: &ObjImport,
    options: &Options,
) -> Result<(Report, Option<Solid>), ValidateError> {
    check_soup(&import.soup)?;
    Ok(run(
        &import.soup,
        Some(&import.vertex_lines),
        options,
        None,
        Keep::Solid,
    ))
}

fn check_soup(soup: &PolygonSoup) -> Result<(), ValidateError> {
    let len = soup.positions.len();
    let corners: usize = soup.polygons.iter().map(|p| p.vertices.len()).sum();
    for (what, count) in [
        ("vertices", len),
        ("faces", soup.polygons.len()),
        ("face corners", corners),
    ] {
        if count > context::MAX_ELEMENTS {
            return Err(ValidateError::TooLarge {
                what,
                count,
                max: context::MAX_ELEMENTS,
            });
        }
    }
    for (polygon, p) in soup.polygons.iter().enumerate() {
        if let Some(&index) = p.vertices.iter().find(|&&i| i >= len) {
            return Err(ValidateError::IndexOutOfRange {
                polygon,
                index,
                len,
            });
        }
    }
    if let Some(vertex) = soup.positions.iter().position(|p| !p.is_finite()) {
        return Err(ValidateError::NonFinite { vertex });
    }
    Ok(())
}

/// What a validation returns besides its report.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Keep {
    /// The built solid too.
    Solid,
    /// The report only: the solid is built only where the verdict needs
    /// it (see [`run`]).
    ReportOnly,
}

/// Every rule on `soup`; the self-intersection check only on pairs with a
/// face marked in `changed` when it is given.
///
/// Whether the faces build into a winged-edge solid is part of the
/// verdict. With [`Keep::ReportOnly`] the solid is not built when the
/// soup is clean ([`context::Context::is_clean`]), has a face, and the
/// soup checks find nothing: then [`Solid::try_from_soup`] cannot fail, so
/// the verdict is the same as if it had been built. Its errors each imply
/// a soup violation or an unclean context: a polygon with fewer than three
/// corners is not polygon-shaped (unclean); an index out of range or a
/// non-finite position is refused before any rule runs; a polygon visiting
/// a vertex twice is a [`Rule::DegenerateFace`] (or, twice in a row,
/// unclean); an edge used three or more times is a
/// [`Rule::EdgeInMoreThanTwoFaces`], an edge run twice one way a
/// [`Rule::InconsistentOrientation`]; no polygons at all is excluded.
/// Otherwise only the build's checks run (`solid_view::check_builds`):
/// the verdict needs whether it fails and why, not the solid.
fn run(
    soup: &PolygonSoup,
    vertex_lines: Option<&[usize]>,
    options: &Options,
    changed: Option<&[bool]>,
    keep: Keep,
) -> (Report, Option<Solid>) {
    let start = std::time::Instant::now();
    if soup.polygons.is_empty() && soup.positions.is_empty() {
        return (empty_report(), keep_solid(keep));
    }
    // The soup usually needs no cleaning (no repeats in a row, no duplicate
    // or broken faces): build the solid from it while the context is made.
    let (ctx, raw) = match keep {
        Keep::Solid => {
            let (ctx, raw) = rayon::join(
                || context::Context::new(soup, vertex_lines, options.tolerance),
                || Solid::try_from_soup(soup),
            );
            (ctx, Some(raw))
        }
        Keep::ReportOnly => (
            context::Context::new(soup, vertex_lines, options.tolerance),
            None,
        ),
    };
    let prepared = start.elapsed().as_secs_f64();
    let soup_checks: [fn(&context::Context) -> Vec<Violation>; 13] = [
        checks::vertex_in_fewer_than_three_edges::check,
        checks::vertex_in_fewer_than_three_faces::check,
        checks::edge_without_two_distinct_vertices::check,
        checks::edge_in_one_face::check,
        checks::edge_in_more_than_two_faces::check,
        checks::face_with_fewer_than_three_vertices::check,
        checks::face_with_fewer_than_three_edges::check,
        checks::unreferenced_vertex::check,
        checks::duplicate_face::check,
        checks::inconsistent_orientation::check,
        checks::non_manifold_vertex::check,
        checks::non_planar_face::check,
        checks::degenerate_face::check,
    ];
    let ((intersections, si_seconds), (mut violations, built)) = rayon::join(
        || {
            let t = std::time::Instant::now();
            let found = match (options.self_intersection, changed) {
                (false, _) => Vec::new(),
                (true, None) => checks::self_intersection::check(&ctx),
                (true, Some(changed)) => {
                    checks::self_intersection::check_near_changed(&ctx, changed)
                }
            };
            (found, t.elapsed().as_secs_f64())
        },
        || {
            let violations: Vec<Violation> =
                soup_checks.iter().flat_map(|check| check(&ctx)).collect();
            let needs_build = !(ctx.is_clean() && violations.is_empty() && ctx.face_count() > 0);
            let (built, view) = rayon::join(
                || match raw {
                    Some(Ok(solid)) if ctx.is_clean() => Ok(Some(solid)),
                    Some(_) => solid_view::build(&ctx).map(Some),
                    None if needs_build => solid_view::check_builds(&ctx).map(|()| None),
                    None => Ok(None),
                },
                || solid_view::measure(&ctx),
            );
            (violations, built.map(|solid| (solid, view)))
        },
    );
    let (solid, built) = match built {
        Ok((solid, view)) => (solid, Ok(view)),
        Err(why) => (None, Err(why)),
    };
    let (shells, genus, volume, not_built) = match built {
        Ok(view) => {
            violations.extend(checks::shell_oriented_inward::check(
                &view.geometry,
                &view.shells,
            ));
            (view.shells, view.genus, view.volume, None)
        }
        Err(why) => (Vec::new(), None, None, Some(why)),
    };
    violations.extend(intersections);
    violations.sort_by_key(|v| v.rule);
    // Summed in fixed chunks: the same bits for any number of threads.
    let area = crate::fixed_chunks::sum(ctx.face_count(), |f| {
        let points: smallvec::SmallVec<[glam::DVec3; 8]> =
            ctx.corners(f).iter().map(|&v| ctx.position(v)).collect();
        match points.first() {
            Some(&o) => crate::geom::newell_vector_area(&points, o).length(),
            None => 0.0,
        }
    });
    let shell_count = if not_built.is_none() {
        shells.len()
    } else {
        soup_components(&ctx)
    };
    let validity = grade(&violations, not_built.is_some());
    let total = start.elapsed().as_secs_f64();
    let report = Report {
        validity,
        vertices: soup.positions.len(),
        edges: ctx.edges.len(),
        faces: ctx.face_count(),
        shells: shell_count,
        holes: holes(&ctx),
        genus,
        volume,
        area,
        not_built,
        shell_details: shells,
        violations,
        stage_seconds: vec![
            ("context ∥ solid build", prepared),
            ("self-intersection (∥ checks + measures)", si_seconds),
            ("all checks", total - prepared),
        ],
    };
    (report, solid)
}

/// The report on the empty solid: nothing to check, nothing wrong.
fn empty_report() -> Report {
    Report {
        validity: Validity::Empty,
        vertices: 0,
        edges: 0,
        faces: 0,
        shells: 0,
        holes: 0,
        genus: None,
        volume: Some(0.0),
        area: 0.0,
        not_built: None,
        shell_details: Vec::new(),
        violations: Vec::new(),
        stage_seconds: Vec::new(),
    }
}

/// The empty solid when the caller keeps the solid.
fn keep_solid(keep: Keep) -> Option<Solid> {
    matches!(keep, Keep::Solid).then(Solid::default)
}

/// The grade the violations allow. A soup that could not be built into a
/// winged-edge solid for a reason no violation explains (a face visiting a
/// vertex twice) is not a surface either.
fn grade(violations: &[Violation], not_built: bool) -> Validity {
    let any = |f: fn(Rule) -> bool| violations.iter().any(|v| f(v.rule));
    let grade = if any(Rule::breaks_surface) {
        Validity::NotASurface
    } else if any(|r| r == Rule::InconsistentOrientation) {
        Validity::ManifoldSurface
    } else if any(|r| r == Rule::EdgeInOneFace) {
        Validity::OrientedSurface
    } else if !violations.is_empty() {
        Validity::ClosedOrientedSurface
    } else {
        Validity::ValidSolid
    };
    if not_built && grade > Validity::ManifoldSurface {
        Validity::NotASurface
    } else {
        grade
    }
}

/// Groups of edges with one face joined through shared vertices: the holes.
fn holes(ctx: &context::Context) -> usize {
    let mut rims = crate::disjoint_sets::DisjointSets::new(ctx.soup.positions.len());
    let mut on_rim = vec![false; ctx.soup.positions.len()];
    for e in (0..ctx.edges.len()).filter(|&e| ctx.uses(e).len() == 1) {
        let (a, b) = (ctx.edges[e].low(), ctx.edges[e].high());
        rims.union(a, b);
        on_rim[a] = true;
        on_rim[b] = true;
    }
    (0..on_rim.len())
        .filter(|&v| on_rim[v] && rims.is_root(v))
        .count()
}

/// Connected components of the faces in the topology, joined through shared
/// edges (used when the solid cannot be built).
fn soup_components(ctx: &context::Context) -> usize {
    let mut shells = crate::disjoint_sets::DisjointSets::new(ctx.face_count());
    for e in 0..ctx.edges.len() {
        let uses = ctx.uses(e);
        for u in &uses[1..] {
            shells.union(uses[0].face(), u.face());
        }
    }
    (0..ctx.face_count())
        .filter(|&f| ctx.in_topology[f] && shells.is_root(f))
        .count()
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    fn pyramid(base: [usize; 4]) -> PolygonSoup {
        let positions = vec![
            DVec3::new(0., 0., 0.),
            DVec3::new(1., 0., 0.),
            DVec3::new(1., 1., 0.),
            DVec3::new(0., 1., 0.),
            DVec3::new(0.5, 0.5, 1.),
        ];
        let mut polygons: Vec<Vec<usize>> = vec![base.to_vec()];
        polygons.extend([[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]].map(|t| t.to_vec()));
        PolygonSoup::new(positions, polygons)
    }

    #[test]
    fn a_valid_pyramid_and_a_bow_tie_base() {
        let r = validate_soup(&pyramid([0, 3, 2, 1]), None, &Options::default()).unwrap();
        assert!(r.is_valid(), "{:#?}", r.violations);
        let r = validate_soup(&pyramid([0, 2, 3, 1]), None, &Options::default()).unwrap();
        let degenerate: Vec<_> = r.of(Rule::DegenerateFace).collect();
        assert_eq!(degenerate.len(), 1);
        assert!(
            degenerate[0].message.contains("not simple"),
            "{degenerate:?}"
        );
        assert_eq!(degenerate[0].faces, [0]);
    }

    #[test]
    fn a_face_of_one_repeated_vertex_has_a_loop_edge_per_corner() {
        let mut soup = pyramid([0, 3, 2, 1]);
        soup.polygons.push(crate::mesh::Polygon::new([4, 4, 4]));
        let r = validate_soup(&soup, None, &Options::default()).unwrap();
        assert_eq!(r.count(Rule::EdgeWithoutTwoDistinctVertices), 3);
        assert_eq!(r.count(Rule::FaceWithFewerThanThreeVertices), 1);
        assert_eq!(r.validity, Validity::NotASurface);
    }

    /// The report alone (solid built only where the verdict needs it)
    /// says exactly what the report beside the built solid says, on soups
    /// that build and on soups that each break one of the build's rules.
    #[test]
    fn a_report_without_the_solid_is_the_same_report() {
        let valid = pyramid([0, 3, 2, 1]);
        let bow_tie = pyramid([0, 2, 3, 1]);
        let mut flipped = pyramid([0, 3, 2, 1]);
        flipped.polygons[1].vertices.reverse();
        let mut three_on_an_edge = pyramid([0, 3, 2, 1]);
        three_on_an_edge
            .polygons
            .push(crate::mesh::Polygon::new([0, 1, 2]));
        let mut repeated = pyramid([0, 3, 2, 1]);
        repeated.polygons[0] = crate::mesh::Polygon::new([0, 3, 0, 2, 1]);
        let mut in_a_row = pyramid([0, 3, 2, 1]);
        in_a_row.polygons[0] = crate::mesh::Polygon::new([0, 3, 3, 2, 1]);
        let mut too_few = pyramid([0, 3, 2, 1]);
        too_few.polygons.push(crate::mesh::Polygon::new([0, 1]));
        let empty = PolygonSoup::new(Vec::new(), Vec::<Vec<usize>>::new());
        let soups = [
            valid,
            bow_tie,
            flipped,
            three_on_an_edge,
            repeated,
            in_a_row,
            too_few,
            empty,
        ];
        let mut not_built = 0;
        for (k, soup) in soups.iter().enumerate() {
            let options = Options::default();
            let (with_solid, solid) = run(soup, None, &options, None, Keep::Solid);
            let (alone, none) = run(soup, None, &options, None, Keep::ReportOnly);
            assert!(none.is_none(), "soup {k}");
            assert_eq!(solid.is_some(), with_solid.not_built.is_none(), "soup {k}");
            not_built += usize::from(with_solid.not_built.is_some());
            assert_eq!(alone.validity, with_solid.validity, "soup {k}");
            assert_eq!(alone.violations, with_solid.violations, "soup {k}");
            assert_eq!(alone.not_built, with_solid.not_built, "soup {k}");
            assert_eq!(alone.shell_details, with_solid.shell_details, "soup {k}");
            assert_eq!(
                (alone.genus, alone.volume),
                (with_solid.genus, with_solid.volume),
                "soup {k}"
            );
        }
        // Some of these soups do not build: the reason must still be said.
        assert!(not_built >= 3, "{not_built}");
    }

    #[test]
    fn bad_soups_are_errors_not_panics() {
        let mut soup = pyramid([0, 3, 2, 1]);
        soup.polygons[0].vertices[0] = 99;
        assert!(matches!(
            validate_soup(&soup, None, &Options::default()),
            Err(ValidateError::IndexOutOfRange { index: 99, .. })
        ));
        let mut soup = pyramid([0, 3, 2, 1]);
        soup.positions[4].z = f64::NAN;
        assert!(matches!(
            validate_soup(&soup, None, &Options::default()),
            Err(ValidateError::NonFinite { vertex: 4 })
        ));
    }
}
