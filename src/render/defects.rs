//! Pictures of what validation found: the polygon soup drawn by a z-buffer
//! rasterizer (fan triangles, flat two-sided shading, orthographic view),
//! faces named by face rules filled in the rule's colour, edges named by
//! edge rules drawn thick over the surface, named vertices drawn as dots,
//! framed on the defects, with a legend of the counts per rule.
//!
//! It reads only the soup and the violations, never a solid: the input may
//! be open, non-manifold or self-intersecting. Ids out of range (a report
//! of another soup) are skipped.

use glam::DVec3;
use thiserror::Error;

use super::Image;
use super::font::{GLYPH_HEIGHT, draw_text, text_width};
use super::raster::{Raster, Rgb};
use crate::mesh::PolygonSoup;
use crate::validate::{Rule, Violation};

/// The largest picture drawn, in pixels (the `render` command's limit).
pub const MAX_DEFECT_IMAGE_PIXELS: u64 = 100_000_000;

/// Why a defect picture cannot be drawn.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum DefectImageError {
    /// The size asked for is empty or larger than
    /// [`MAX_DEFECT_IMAGE_PIXELS`].
    #[error("image size {width}x{height}: a picture needs 1 to {MAX_DEFECT_IMAGE_PIXELS} pixels")]
    Size {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
}

/// How to draw a defect picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DefectImageOptions {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Default for DefectImageOptions {
    /// 800 × 600.
    fn default() -> DefectImageOptions {
        DefectImageOptions {
            width: 800,
            height: 600,
        }
    }
}

/// How a rule's violations are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DefectMark {
    /// The faces named are filled (and outlined when they may have no area).
    Face,
    /// The edge from the first to the second vertex named is drawn thick.
    Edge,
    /// Each vertex named is drawn as a dot.
    Vertex,
}

/// How violations of `rule` are drawn.
#[must_use]
pub fn defect_mark(rule: Rule) -> DefectMark {
    match rule {
        Rule::EdgeInOneFace | Rule::EdgeInMoreThanTwoFaces | Rule::InconsistentOrientation => {
            DefectMark::Edge
        }
        Rule::SelfIntersection
        | Rule::NonPlanarFace
        | Rule::DegenerateFace
        | Rule::DuplicateFace
        | Rule::FaceWithFewerThanThreeVertices
        | Rule::FaceWithFewerThanThreeEdges
        | Rule::ShellOrientedInward => DefectMark::Face,
        Rule::VertexInFewerThanThreeEdges
        | Rule::VertexInFewerThanThreeFaces
        | Rule::EdgeWithoutTwoDistinctVertices
        | Rule::UnreferencedVertex
        | Rule::NonManifoldVertex => DefectMark::Vertex,
    }
}

/// The colour a rule is drawn in (distinct per rule; none is grey, the
/// colour of faces without defects). Filled faces are shaded: their pixels
/// are this colour scaled by a factor in `(0, 1]`.
#[must_use]
pub fn defect_colour(rule: Rule) -> [u8; 3] {
    match rule {
        Rule::SelfIntersection => [255, 160, 0],
        Rule::NonPlanarFace => [0, 170, 230],
        Rule::DegenerateFace => [150, 80, 230],
        Rule::DuplicateFace => [60, 180, 75],
        Rule::FaceWithFewerThanThreeVertices => [170, 110, 40],
        Rule::FaceWithFewerThanThreeEdges => [128, 128, 0],
        Rule::ShellOrientedInward => [230, 190, 255],
        Rule::EdgeInOneFace => [230, 25, 75],
        Rule::EdgeInMoreThanTwoFaces => [240, 50, 230],
        Rule::InconsistentOrientation => [0, 128, 128],
        Rule::EdgeWithoutTwoDistinctVertices => [128, 0, 0],
        Rule::NonManifoldVertex => [255, 225, 25],
        Rule::VertexInFewerThanThreeEdges => [70, 240, 240],
        Rule::VertexInFewerThanThreeFaces => [0, 0, 128],
        Rule::UnreferencedVertex => [250, 190, 212],
    }
}

const BACKGROUND: Rgb = [255, 255, 255];
const SURFACE: f64 = 205.0;
const INK: Rgb = [0, 0, 0];
const PANEL: Rgb = [238, 238, 238];
/// The view: from this side of the mesh (+x, −y, +z), z up.
const TOWARD_EYE: DVec3 = DVec3::new(1.0, -1.6, 1.2);
/// Face rules in the order they win a face named by several.
const FACE_PRIORITY: [Rule; 7] = [
    Rule::SelfIntersection,
    Rule::DegenerateFace,
    Rule::FaceWithFewerThanThreeVertices,
    Rule::FaceWithFewerThanThreeEdges,
    Rule::DuplicateFace,
    Rule::NonPlanarFace,
    Rule::ShellOrientedInward,
];
/// Defects are framed with this margin around their bounding sphere, and
/// never closer than this fraction of the whole mesh's, so that some of
/// the mesh around them shows.
const DEFECT_MARGIN: f64 = 1.3;
const CONTEXT_FRACTION: f64 = 0.25;

/// Draws `soup` with the defects `violations` name (element ids as in a
/// [`Report`](crate::validate::Report) of this soup) marked, framed on the
/// defects (on the whole mesh when there are none), with a legend of the
/// count per rule in the top-left corner. Where the picture is framed on
/// defects, whatever lies nearer the eye than their neighbourhood is cut
/// away.
///
/// # Errors
///
/// [`DefectImageError::Size`] for an empty size or one of more than
/// [`MAX_DEFECT_IMAGE_PIXELS`].
pub fn render_defects(
    soup: &PolygonSoup,
    violations: &[Violation],
    options: &DefectImageOptions,
) -> Result<Image, DefectImageError> {
    let (width, height) = (options.width, options.height);
    let pixels = u64::from(width) * u64::from(height);
    if pixels == 0 || pixels > MAX_DEFECT_IMAGE_PIXELS {
        return Err(DefectImageError::Size { width, height });
    }
    Ok(draw(soup, violations, width, height).0)
}

/// A rectangle of pixels: left, top, width, height.
type PixelBox = (i64, i64, i64, i64);

/// An orthographic view: world points to screen `(x, y, depth)`.
struct Frame {
    centre: DVec3,
    right: DVec3,
    up: DVec3,
    toward_eye: DVec3,
    pixels_per_unit: f64,
    half_width: f64,
    half_height: f64,
    /// The framed sphere's radius.
    radius: f64,
}

impl Frame {
    fn new(centre: DVec3, radius: f64, width: u32, height: u32) -> Frame {
        let toward_eye = TOWARD_EYE.normalize();
        let right = DVec3::Z.cross(toward_eye).normalize();
        let up = toward_eye.cross(right);
        Frame {
            centre,
            right,
            up,
            toward_eye,
            pixels_per_unit: 0.45 * f64::from(width.min(height)) / radius,
            half_width: 0.5 * f64::from(width),
            half_height: 0.5 * f64::from(height),
            radius,
        }
    }

    fn project(&self, p: DVec3) -> DVec3 {
        let d = p - self.centre;
        DVec3::new(
            self.half_width + d.dot(self.right) * self.pixels_per_unit,
            self.half_height - d.dot(self.up) * self.pixels_per_unit,
            -d.dot(self.toward_eye),
        )
    }
}

/// The centre and radius of the sphere around the box of `points`, or
/// `None` for no points.
fn bounding_sphere(points: impl Iterator<Item = DVec3>) -> Option<(DVec3, f64)> {
    let (low, high) = points.fold(None, |acc: Option<(DVec3, DVec3)>, p| {
        Some(acc.map_or((p, p), |(l, h)| (l.min(p), h.max(p))))
    })?;
    let half = 0.5 * high - 0.5 * low;
    let radius = Some(half.length())
        .filter(|r| r.is_finite())
        .unwrap_or_else(|| half.max_element());
    Some((0.5 * low + 0.5 * high, radius))
}

/// The picture, its view and the legend's box.
fn draw(
    soup: &PolygonSoup,
    violations: &[Violation],
    width: u32,
    height: u32,
) -> (Image, Frame, PixelBox) {
    let position = |v: usize| soup.positions.get(v).copied();
    let corners = |f: usize| {
        soup.polygons
            .get(f)
            .map(|p| p.vertices.as_slice())
            .unwrap_or_default()
    };
    let named = violations.iter().flat_map(|v| {
        let faces = v.faces.iter().flat_map(|&f| corners(f).iter().copied());
        v.vertices.iter().copied().chain(faces).filter_map(position)
    });
    let whole = bounding_sphere(soup.positions.iter().copied());
    let focus = bounding_sphere(named);
    let (centre, radius, near) = match (focus, whole) {
        (Some((c, r)), Some((_, all))) => {
            let radius = (DEFECT_MARGIN * r).max(CONTEXT_FRACTION * all);
            (c, radius, true)
        }
        (_, Some((c, r))) => (c, r, false),
        (_, None) => (DVec3::ZERO, 1.0, false),
    };
    let radius = if radius > 0.0 && radius.is_finite() {
        radius
    } else {
        1.0
    };
    let frame = Frame::new(centre, radius, width, height);
    let near = if near {
        -frame.radius
    } else {
        f64::NEG_INFINITY
    };
    let mut raster = Raster::new(width, height, BACKGROUND, near);
    draw_faces(&mut raster, &frame, soup, violations);
    draw_marks(&mut raster, &frame, soup, violations);
    let legend = draw_legend(&mut raster, violations, width);
    (raster.into_image(), frame, legend)
}

/// Every polygon, fan-triangulated, flat-shaded by its Newell normal on
/// either side; defect faces in their rule's colour.
fn draw_faces(raster: &mut Raster, frame: &Frame, soup: &PolygonSoup, violations: &[Violation]) {
    let mut face_rule: Vec<Option<Rule>> = vec![None; soup.polygons.len()];
    let rank = |rule: Rule| FACE_PRIORITY.iter().position(|&r| r == rule);
    for v in violations
        .iter()
        .filter(|v| defect_mark(v.rule) == DefectMark::Face)
    {
        for &f in &v.faces {
            if let Some(slot) = face_rule.get_mut(f)
                && slot.is_none_or(|old| rank(v.rule) < rank(old))
            {
                *slot = Some(v.rule);
            }
        }
    }
    let light = (frame.toward_eye + 0.6 * frame.up - 0.3 * frame.right).normalize();
    for (polygon, rule) in soup.polygons.iter().zip(&face_rule) {
        let points: Vec<DVec3> = polygon
            .vertices
            .iter()
            .filter_map(|&v| soup.positions.get(v).copied())
            .collect();
        if points.len() < 3 {
            continue;
        }
        let normal = newell_normal(&points).try_normalize();
        let (base, floor) = match rule {
            Some(rule) => (defect_colour(*rule).map(f64::from), 0.55),
            None => ([SURFACE; 3], 0.35),
        };
        let light_share = normal.map_or(0.5, |n| n.dot(light).abs());
        let factor = floor + (1.0 - floor) * light_share;
        let colour: Rgb = base.map(|c| (c * factor).round().clamp(0.0, 255.0) as u8);
        let screen: Vec<DVec3> = points.iter().map(|&p| frame.project(p)).collect();
        for k in 1..screen.len() - 1 {
            raster.fill_triangle([screen[0], screen[k], screen[k + 1]], colour);
        }
    }
}

/// The Newell normal of a polygon (length twice its area when planar).
fn newell_normal(points: &[DVec3]) -> DVec3 {
    let origin = points[0];
    let mut normal = DVec3::ZERO;
    for (k, &p) in points.iter().enumerate() {
        let q = points[(k + 1) % points.len()];
        normal += (p - origin).cross(q - origin);
    }
    normal
}

/// Edges, outlines of faces that may have no area, then vertex dots.
fn draw_marks(raster: &mut Raster, frame: &Frame, soup: &PolygonSoup, violations: &[Violation]) {
    let screen = |v: usize| soup.positions.get(v).map(|&p| frame.project(p));
    let slack = 0.02 * frame.radius;
    let line = |raster: &mut Raster, a: usize, b: usize, thickness: u32, rule: Rule| {
        if let (Some(p), Some(q)) = (screen(a), screen(b)) {
            raster.draw_line(p, q, thickness, slack, defect_colour(rule));
        }
    };
    for v in violations {
        match (defect_mark(v.rule), v.vertices.as_slice()) {
            (DefectMark::Edge, &[a, b, ..]) => line(raster, a, b, 3, v.rule),
            (DefectMark::Face, _)
                if matches!(
                    v.rule,
                    Rule::DegenerateFace
                        | Rule::FaceWithFewerThanThreeVertices
                        | Rule::FaceWithFewerThanThreeEdges
                ) =>
            {
                for &f in &v.faces {
                    let ring = soup
                        .polygons
                        .get(f)
                        .map(|p| p.vertices.as_slice())
                        .unwrap_or_default();
                    for (k, &a) in ring.iter().enumerate() {
                        line(raster, a, ring[(k + 1) % ring.len()], 2, v.rule);
                    }
                }
            }
            _ => {}
        }
    }
    for v in violations
        .iter()
        .filter(|v| defect_mark(v.rule) == DefectMark::Vertex)
    {
        for p in v.vertices.iter().filter_map(|&i| screen(i)) {
            raster.draw_dot(p, 4.0, defect_colour(v.rule), INK);
        }
    }
}

/// The legend: a swatch, the rule's name and its count per rule broken
/// (or "no defects"), on a panel in the top-left corner; returns the panel.
fn draw_legend(raster: &mut Raster, violations: &[Violation], width: u32) -> PixelBox {
    let scale: i64 = if width >= 600 { 2 } else { 1 };
    let lines: Vec<(Option<Rule>, String)> = {
        let broken: Vec<_> = Rule::ALL
            .into_iter()
            .map(|rule| (rule, violations.iter().filter(|v| v.rule == rule).count()))
            .filter(|&(_, n)| n > 0)
            .map(|(rule, n)| (Some(rule), format!("{rule}: {n}")))
            .collect();
        if broken.is_empty() {
            vec![(None, "no defects".to_string())]
        } else {
            broken
        }
    };
    let (margin, pad, swatch) = (4 * scale, 4 * scale, GLYPH_HEIGHT * scale);
    let line_height = (GLYPH_HEIGHT + 4) * scale;
    let widest = lines
        .iter()
        .map(|(_, t)| text_width(t, scale))
        .max()
        .unwrap_or(0);
    let panel = (
        margin,
        margin,
        2 * pad + swatch + 2 * scale + widest,
        2 * pad + line_height * lines.len() as i64 - 4 * scale,
    );
    raster.fill_rect(panel.0, panel.1, panel.2, panel.3, PANEL);
    for (k, (rule, text)) in lines.iter().enumerate() {
        let top = panel.1 + pad + k as i64 * line_height;
        let mut left = panel.0 + pad;
        if let Some(rule) = rule {
            raster.fill_rect(left, top, swatch, swatch, defect_colour(*rule));
            left += swatch + 2 * scale;
        }
        draw_text(raster, left, top, text, scale, INK);
    }
    panel
}

#[cfg(test)]
#[path = "defects_tests.rs"]
mod tests;
