//! Indexed polygon soups: positions plus polygons that index them.
//!
//! A soup is what files hold and what builders produce before topology is
//! known. [`Solid::try_from_soup`](super::Solid::try_from_soup) turns one
//! into a winged-edge solid.

use glam::DVec3;
use smallvec::SmallVec;

use super::FaceAttributes;

/// One polygon of a soup: vertex indices (counter-clockwise seen from
/// outside) and the attributes its face will carry.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polygon {
    /// 0-based indices into [`PolygonSoup::positions`].
    pub vertices: SmallVec<[usize; 4]>,
    /// Origin and labels, carried onto the face.
    pub attributes: FaceAttributes,
}

impl Polygon {
    /// A polygon with the given vertex indices and no attributes.
    #[must_use]
    pub fn new(vertices: impl IntoIterator<Item = usize>) -> Polygon {
        Polygon {
            vertices: vertices.into_iter().collect(),
            attributes: FaceAttributes::default(),
        }
    }
}

/// Positions plus polygons indexing them.
///
/// No invariants: a soup may hold anything a file can (bad indices,
/// non-finite positions, non-manifold edges). Building a solid checks it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PolygonSoup {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// The polygons.
    pub polygons: Vec<Polygon>,
}

impl PolygonSoup {
    /// A soup from positions and index lists (no attributes).
    #[must_use]
    pub fn new<P: AsRef<[usize]>>(
        positions: Vec<DVec3>,
        polygons: impl IntoIterator<Item = P>,
    ) -> PolygonSoup {
        PolygonSoup {
            positions,
            polygons: polygons
                .into_iter()
                .map(|p| Polygon::new(p.as_ref().iter().copied()))
                .collect(),
        }
    }

    /// The positions of a polygon's vertices, or `None` if an index is out of
    /// range.
    #[must_use]
    pub fn polygon_positions(&self, polygon: &Polygon) -> Option<SmallVec<[DVec3; 8]>> {
        polygon
            .vertices
            .iter()
            .map(|&i| self.positions.get(i).copied())
            .collect()
    }
}

impl super::Solid {
    /// The solid as a soup: its vertices in table order, one polygon per
    /// face (the face's loop, counter-clockwise seen from outside), each
    /// polygon carrying its face's attributes.
    /// [`Solid::try_from_soup`](super::Solid::try_from_soup) of the result
    /// builds the same solid (same counts, faces in the same order). Linear
    /// in the size of the solid.
    #[must_use]
    pub fn to_soup(&self) -> PolygonSoup {
        let mut index = slotmap::SecondaryMap::with_capacity(self.vertex_count());
        let positions = self
            .vertices()
            .enumerate()
            .map(|(i, (id, v))| {
                index.insert(id, i);
                v.position
            })
            .collect();
        let polygons = self
            .faces()
            .map(|(f, face)| Polygon {
                vertices: self.face_vertices(f).map(|v| index[v]).collect(),
                attributes: face.attributes.clone(),
            })
            .collect();
        PolygonSoup {
            positions,
            polygons,
        }
    }
}
