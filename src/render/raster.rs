//! A small z-buffer rasterizer: filled triangles, thick lines and dots in
//! screen space, for drawing meshes that are no solid (open, non-manifold,
//! self-intersecting), where the ray-cast renderer has nothing to classify.
//!
//! Screen coordinates: `x` to the right and `y` down, in pixels, pixel
//! `(i, j)` covering `[i, i + 1) × [j, j + 1)`; `z` is the depth along the
//! view (smaller is nearer). Nothing here panics on any input: non-finite
//! coordinates are skipped, and every loop is clamped to the image.

use glam::DVec3;

use super::Image;

/// An RGB colour.
pub(crate) type Rgb = [u8; 3];

/// A colour buffer with a depth per pixel.
///
/// # Invariants
///
/// `colour.len() == depth.len() == width × height`.
pub(crate) struct Raster {
    width: u32,
    height: u32,
    colour: Vec<Rgb>,
    depth: Vec<f64>,
    /// Pixels with depth below this are not drawn (a cut-away plane).
    near: f64,
}

impl Raster {
    /// A raster filled with `background`, at infinite depth, drawing only
    /// at depths of at least `near`.
    pub(crate) fn new(width: u32, height: u32, background: Rgb, near: f64) -> Raster {
        let n = (width as usize) * (height as usize);
        Raster {
            width,
            height,
            colour: vec![background; n],
            depth: vec![f64::INFINITY; n],
            near,
        }
    }

    fn index(&self, x: i64, y: i64) -> Option<usize> {
        (x >= 0 && y >= 0 && x < i64::from(self.width) && y < i64::from(self.height))
            .then(|| (y as usize) * (self.width as usize) + x as usize)
    }

    /// The colour of pixel `(x, y)`, if it is in the image.
    #[cfg(test)]
    pub(crate) fn get(&self, x: i64, y: i64) -> Option<Rgb> {
        self.index(x, y).map(|i| self.colour[i])
    }

    /// Sets pixel `(x, y)` regardless of depth (no-op outside the image).
    pub(crate) fn set(&mut self, x: i64, y: i64, colour: Rgb) {
        if let Some(i) = self.index(x, y) {
            self.colour[i] = colour;
        }
    }

    /// Fills a triangle given in screen coordinates, keeping the nearest
    /// surface per pixel (pixel centres inside or on the triangle).
    pub(crate) fn fill_triangle(&mut self, corners: [DVec3; 3], colour: Rgb) {
        if corners.iter().any(|c| !c.is_finite()) {
            return;
        }
        let [a, b, c] = corners;
        let area = edge(a, b, c);
        if area == 0.0 || !area.is_finite() {
            return;
        }
        let (x0, x1) = span(a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x), self.width);
        let (y0, y1) = span(a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y), self.height);
        for y in y0..y1 {
            for x in x0..x1 {
                let p = DVec3::new(x as f64 + 0.5, y as f64 + 0.5, 0.0);
                let (wa, wb, wc) = (
                    edge(b, c, p) / area,
                    edge(c, a, p) / area,
                    edge(a, b, p) / area,
                );
                if wa < 0.0 || wb < 0.0 || wc < 0.0 {
                    continue;
                }
                let z = wa * a.z + wb * b.z + wc * c.z;
                let i = (y as usize) * (self.width as usize) + x as usize;
                if z >= self.near && z < self.depth[i] {
                    self.depth[i] = z;
                    self.colour[i] = colour;
                }
            }
        }
    }

    /// Draws the segment `from`–`to` over the surfaces: `thickness` pixels
    /// wide in `colour` where it is no farther than `slack` behind the
    /// nearest surface, one pixel wide and half blended into what is there
    /// where it is hidden.
    pub(crate) fn draw_line(
        &mut self,
        from: DVec3,
        to: DVec3,
        thickness: u32,
        slack: f64,
        colour: Rgb,
    ) {
        let Some((from, to)) = self.clip(from, to) else {
            return;
        };
        let length = (to.truncate() - from.truncate()).length();
        // Two samples per pixel of length; the clip bounds the count.
        let steps = (2.0 * length).ceil().max(1.0) as u64;
        let reach = i64::from(thickness / 2);
        let low = -i64::from(thickness.saturating_sub(1) / 2);
        let mut last = None;
        for k in 0..=steps {
            let p = from.lerp(to, k as f64 / steps as f64);
            let (x, y) = (p.x.floor() as i64, p.y.floor() as i64);
            if last.replace((x, y)) == Some((x, y)) {
                continue;
            }
            let Some(i) = self.index(x, y) else {
                continue;
            };
            if p.z <= self.depth[i] + slack {
                for dy in low..=reach {
                    for dx in low..=reach {
                        self.set(x + dx, y + dy, colour);
                    }
                }
            } else if self.colour[i] != colour {
                let under = self.colour[i];
                self.colour[i] = std::array::from_fn(|c| {
                    ((u16::from(under[c]) + u16::from(colour[c])) / 2) as u8
                });
            }
        }
    }

    /// A filled disc of `radius` pixels in `colour` with a one-pixel
    /// `outline`, over everything.
    pub(crate) fn draw_dot(&mut self, centre: DVec3, radius: f64, colour: Rgb, outline: Rgb) {
        if !centre.is_finite() || centre.z < self.near {
            return;
        }
        let r = radius.ceil() as i64 + 1;
        let (cx, cy) = (centre.x.floor() as i64, centre.y.floor() as i64);
        if cx < -r || cy < -r || cx > i64::from(self.width) + r || cy > i64::from(self.height) + r {
            return;
        }
        for dy in -r..=r {
            for dx in -r..=r {
                let d = ((dx * dx + dy * dy) as f64).sqrt();
                if d <= radius {
                    self.set(cx + dx, cy + dy, colour);
                } else if d <= radius + 1.0 {
                    self.set(cx + dx, cy + dy, outline);
                }
            }
        }
    }

    /// Fills the rectangle `[x, x + w) × [y, y + h)` regardless of depth.
    pub(crate) fn fill_rect(&mut self, x: i64, y: i64, w: i64, h: i64, colour: Rgb) {
        for yy in y.max(0)..(y + h).min(i64::from(self.height)) {
            for xx in x.max(0)..(x + w).min(i64::from(self.width)) {
                self.set(xx, yy, colour);
            }
        }
    }

    /// The part of a segment inside the image (one pixel of margin) and at
    /// depth at least `near` (Liang–Barsky), or `None`.
    fn clip(&self, from: DVec3, to: DVec3) -> Option<(DVec3, DVec3)> {
        if !from.is_finite() || !to.is_finite() {
            return None;
        }
        let d = to - from;
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        let (w, h) = (f64::from(self.width) + 1.0, f64::from(self.height) + 1.0);
        // Each bound as `q + t × p ≥ 0`.
        for (p, q) in [
            (d.x, from.x + 1.0),
            (-d.x, w - from.x),
            (d.y, from.y + 1.0),
            (-d.y, h - from.y),
            (d.z, from.z - self.near),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let t = -q / p;
                if p > 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        (t0 <= t1 && t0.is_finite() && t1.is_finite()).then(|| (from + d * t0, from + d * t1))
    }

    /// The finished image.
    pub(crate) fn into_image(self) -> Image {
        let bytes = self.colour.into_iter().flatten().collect();
        Image::from_rgb_bytes(self.width, self.height, bytes)
            .unwrap_or_else(|| unreachable!("the buffer has width × height pixels"))
    }
}

/// Twice the signed area of `a, b, p` in the screen plane.
fn edge(a: DVec3, b: DVec3, p: DVec3) -> f64 {
    (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)
}

/// The pixel range whose centres may lie in `[low, high]`, clamped to
/// `[0, size)`.
fn span(low: f64, high: f64, size: u32) -> (i64, i64) {
    let first = (low - 0.5).ceil().max(0.0).min(f64::from(size)) as i64;
    let end = ((high - 0.5).floor() + 1.0).max(0.0).min(f64::from(size)) as i64;
    (first, end)
}

#[cfg(test)]
mod tests {
    use super::*;

    const WHITE: Rgb = [255, 255, 255];
    const RED: Rgb = [255, 0, 0];
    const BLUE: Rgb = [0, 0, 255];

    #[test]
    fn the_nearer_triangle_wins_whatever_the_order() {
        let mut r = Raster::new(20, 20, WHITE, f64::NEG_INFINITY);
        let tri = |z| {
            [
                DVec3::new(0.0, 0.0, z),
                DVec3::new(20.0, 0.0, z),
                DVec3::new(0.0, 20.0, z),
            ]
        };
        r.fill_triangle(tri(1.0), RED);
        r.fill_triangle(tri(2.0), BLUE);
        assert_eq!(r.get(2, 2), Some(RED));
        assert_eq!(r.get(18, 18), Some(WHITE));
    }

    #[test]
    fn hostile_coordinates_draw_nothing_and_do_not_panic() {
        let mut r = Raster::new(8, 8, WHITE, f64::NEG_INFINITY);
        let huge = DVec3::new(1e300, -1e300, 0.0);
        r.fill_triangle([DVec3::NAN, huge, DVec3::ZERO], RED);
        r.draw_line(huge, -huge, 3, 0.0, RED);
        r.draw_dot(DVec3::splat(f64::INFINITY), 3.0, RED, BLUE);
        r.fill_triangle(
            [
                huge,
                DVec3::new(-1e300, -1e300, 0.0),
                DVec3::new(0.0, 1e300, 0.0),
            ],
            BLUE,
        );
        assert!(r.get(0, 0).is_some());
    }

    #[test]
    fn a_line_is_as_thick_as_asked() {
        let mut r = Raster::new(20, 20, WHITE, f64::NEG_INFINITY);
        r.draw_line(
            DVec3::new(2.0, 10.5, 0.0),
            DVec3::new(18.0, 10.5, 0.0),
            3,
            0.0,
            RED,
        );
        let column: Vec<bool> = (0..20).map(|y| r.get(10, y) == Some(RED)).collect();
        assert_eq!(column.iter().filter(|&&c| c).count(), 3);
        assert!(column[9] && column[10] && column[11]);
    }
}
