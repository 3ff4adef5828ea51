//! Measures of a solid: counts, volume, area, centroid, bounds, Euler
//! characteristic (with the ring term of Euler–Poincaré), shells and genus.
//!
//! All measures are floating-point constructions. Volumes are computed
//! relative to the centre of the bounding box, which leaves the exact value
//! unchanged for closed shells and keeps the rounding small far from the
//! origin.

use glam::DVec3;

use crate::geom::{Aabb, newell_vector_area};

use super::{FaceId, LoopStart, Solid, VertexId};

/// One connected component of a solid's surface.
///
/// # Invariants
///
/// `faces` is non-empty and sorted in the solid's face order; two faces are in
/// the same shell iff a chain of shared edges joins them.
#[derive(Clone, Debug, PartialEq)]
pub struct Shell {
    /// The shell's faces.
    pub faces: Vec<FaceId>,
    /// Vertices on the shell.
    pub vertex_count: usize,
    /// Edges on the shell.
    pub edge_count: usize,
    /// Edges of the shell with one face (the rims of its holes).
    pub boundary_edge_count: usize,
    /// Rings (inner loops of faces) on the shell.
    pub ring_count: usize,
    /// `V − E + F − R` of the shell (`R` its rings).
    pub euler_characteristic: i64,
    /// The signed volume enclosed (divergence theorem); positive for an
    /// outward-oriented closed shell, negative for an inward one. Meaningful
    /// only when the shell is closed.
    pub signed_volume: f64,
}

impl Shell {
    /// Whether the shell has no boundary edges.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.boundary_edge_count == 0
    }

    /// The genus of a closed shell, from Euler–Poincaré
    /// `V − E + F − R = 2 − 2g`; `None` for a shell
    /// with holes (genus is then not determined by `χ` alone) or an odd `χ`
    /// (impossible for an orientable closed surface).
    #[must_use]
    pub fn genus(&self) -> Option<i64> {
        let chi = self.euler_characteristic;
        (self.is_closed() && chi % 2 == 0 && chi <= 2).then_some((2 - chi) / 2)
    }
}

impl Solid {
    /// `V − E + F − R` over the whole solid, `R` the rings (inner loops of
    /// faces): 2 for one closed sphere-like shell, and `2 (S − H)` for `S`
    /// closed shells with `H` handles in all (Euler–Poincaré).
    #[must_use]
    pub fn euler_characteristic(&self) -> i64 {
        self.vertex_count() as i64 - self.edge_count() as i64 + self.face_count() as i64
            - self.ring_count() as i64
    }

    /// The smallest box holding every vertex.
    #[must_use]
    pub fn bounding_box(&self) -> Aabb {
        Aabb::from_points(self.vertices.values().map(|v| v.position))
    }

    /// The signed volume enclosed by the surface, by the divergence theorem:
    /// `⅙ Σ (a − r) · ((b − r) × (c − r))` over a fan triangulation of every
    /// face, with `r` the bounding-box centre. Positive for outward-oriented
    /// closed solids; for open surfaces it depends on `r` and means little.
    #[must_use]
    pub fn volume(&self) -> f64 {
        let r = self.bounding_box().center();
        self.faces
            .keys()
            .map(|f| self.face_volume_moment(f, r).0)
            .sum::<f64>()
            / 6.0
    }

    /// The total area of the faces (each face's Newell vector area).
    #[must_use]
    pub fn surface_area(&self) -> f64 {
        self.faces.keys().map(|f| self.face_area(f)).sum()
    }

    /// The area of one face: the length of the sum of its loops' Newell
    /// vector areas (rings run the other way, so their areas subtract).
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    #[must_use]
    pub fn face_area(&self, face: FaceId) -> f64 {
        let mut origin = None;
        let mut area = DVec3::ZERO;
        for l in self.face_loops(face) {
            let points: smallvec::SmallVec<[DVec3; 8]> =
                self.loop_vertices(l).map(|v| self.position(v)).collect();
            let o = *origin.get_or_insert(points[0]);
            area += newell_vector_area(&points, o);
        }
        area.length()
    }

    /// The centre of mass of the enclosed volume (uniform density), or
    /// `None` when the signed volume is zero.
    #[must_use]
    pub fn centroid(&self) -> Option<DVec3> {
        let r = self.bounding_box().center();
        let (volume, moment) = self
            .faces
            .keys()
            .map(|f| self.face_volume_moment(f, r))
            .fold((0.0, DVec3::ZERO), |(v, m), (dv, dm)| (v + dv, m + dm));
        (volume != 0.0).then(|| r + moment / (4.0 * volume))
    }

    /// Six times the signed volume of the cone from `r` over `face`, and
    /// twenty-four times its first moment about `r` (the factors are applied
    /// once, after summing, to round less). Each loop is fanned on its own:
    /// a ring, wound the other way, subtracts the cone over its hole.
    fn face_volume_moment(&self, face: FaceId, r: DVec3) -> (f64, DVec3) {
        let (mut volume, mut moment) = (0.0, DVec3::ZERO);
        for l in self.face_loops(face) {
            let mut corners = self.loop_vertices(l).map(|v| self.position(v) - r);
            let (Some(a), Some(mut b)) = (corners.next(), corners.next()) else {
                continue;
            };
            for c in corners {
                let v = a.dot(b.cross(c));
                volume += v;
                moment += v * (a + b + c);
                b = c;
            }
        }
        (volume, moment)
    }

    /// The connected components of the surface (faces joined through shared
    /// edges), in order of their first face.
    #[must_use]
    pub fn shells(&self) -> Vec<Shell> {
        let mut shell_of: slotmap::SecondaryMap<FaceId, usize> = slotmap::SecondaryMap::new();
        let mut count = 0;
        let mut stack = Vec::new();
        for start in self.faces.keys() {
            if shell_of.contains_key(start) {
                continue;
            }
            shell_of.insert(start, count);
            stack.push(start);
            while let Some(f) = stack.pop() {
                for n in self.face_neighbours(f) {
                    if !shell_of.contains_key(n) {
                        shell_of.insert(n, count);
                        stack.push(n);
                    }
                }
            }
            count += 1;
        }
        let r = self.bounding_box().center();
        let mut shells: Vec<Shell> = (0..count)
            .map(|_| Shell {
                faces: Vec::new(),
                vertex_count: 0,
                edge_count: 0,
                boundary_edge_count: 0,
                ring_count: 0,
                euler_characteristic: 0,
                signed_volume: 0.0,
            })
            .collect();
        for f in self.faces.keys() {
            let shell = &mut shells[shell_of[f]];
            shell.faces.push(f);
            shell.ring_count += self.faces[f].rings.len();
            shell.signed_volume += self.face_volume_moment(f, r).0;
        }
        let lone_face: std::collections::HashMap<VertexId, FaceId> = self
            .loops
            .values()
            .filter_map(|l| match l.start {
                LoopStart::Vertex(v) => Some((v, l.face)),
                LoopStart::Edge(_) => None,
            })
            .collect();
        for (id, v) in &self.vertices {
            let face = match v.edge {
                Some(e) => self.edges[e].left_face,
                None => lone_face[&id],
            };
            shells[shell_of[face]].vertex_count += 1;
        }
        for e in self.edges.values() {
            let shell = &mut shells[shell_of[e.left_face]];
            shell.edge_count += 1;
            shell.boundary_edge_count += usize::from(e.right_face.is_none());
        }
        for shell in &mut shells {
            shell.signed_volume /= 6.0;
            shell.euler_characteristic = shell.vertex_count as i64 - shell.edge_count as i64
                + shell.faces.len() as i64
                - shell.ring_count as i64;
        }
        shells
    }
}
