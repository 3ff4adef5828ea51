//! The winding number of any polygon soup, built directly from its
//! polygons: for meshes that cannot be a winged-edge solid (an edge of
//! three or more faces, faces wound against their neighbours), on which
//! parity is undefined but the generalized winding number (Jacobson et al.
//! 2013) still answers.

use std::time::Instant;

use glam::DVec3;
use slotmap::SlotMap;

use crate::mesh::{BuildError, FaceId, PolygonSoup, RepeatedVertices, check_polygons};

use super::accel::fan::push_fan;
use super::{Accel, AccelStats, Containment, Method, QueryError};

/// Inside/outside by the generalized winding number of a polygon soup that
/// need not be a solid.
///
/// Each polygon is fanned into triangles exactly as [`Accel::new`] fans a
/// face (apex at the lexicographically smallest corner, exact input
/// coordinates), so on a soup that does build into a solid the triangles,
/// and the answers, are those of the solid's accel. Nothing else about the
/// soup matters: edges of any number of faces, faces wound against their
/// neighbours, self-intersections, holes and polygons that touch
/// themselves are all fine.
///
/// What [`SoupWinding::classify`] answers:
/// - a point exactly on a triangle is [`Containment::OnBoundary`] (exact);
/// - when every edge's uses cancel (each edge run as often one way as the
///   other: [`SoupWinding::open_edges`] is 0; two cubes sharing an edge),
///   the triangles form a closed cycle and the winding number is the exact
///   signed count of a `+x` ray's crossings: inside where it is positive;
/// - otherwise inside where the solid-angle sum
///   ([`SoupWinding::winding_number`]) exceeds ½, Jacobson et al.'s
///   threshold. On a closed surface with faces wound the wrong way that
///   is the right answer deep inside and far outside, but a flipped face
///   counts against the faces around it, so points near it may be judged
///   the other way; a fin (a face hanging off an edge) changes no answer
///   off itself, since one face adds less than ½ anywhere off its plane.
///
/// Parity is not offered: it needs a surface that closes, and a soup's
/// crossings along one ray need not agree with another ray's.
///
/// # Invariants
///
/// `accel` holds the fan triangles of every polygon of the soup it was
/// built from; the face of each triangle is a key of `polygons`, whose
/// value is the polygon's index in the soup; `accel.boundary_edges` is
/// [`SoupWinding::open_edges`].
#[derive(Clone, Debug)]
pub struct SoupWinding {
    accel: Accel,
    polygons: SlotMap<FaceId, usize>,
}

impl SoupWinding {
    /// Builds the triangles and the BVH of `soup` (the point grid follows on
    /// the first classification, as for [`Accel`]).
    ///
    /// # Errors
    ///
    /// The soup's numbers must make triangles:
    /// [`BuildError::NoPolygons`] for no polygon at all,
    /// [`BuildError::TooFewVertices`] for a polygon of fewer than three
    /// corners, [`BuildError::IndexOutOfRange`] and
    /// [`BuildError::NonFinitePosition`] (NaN or infinite) for a corner;
    /// the first in polygon order. No other variant is returned.
    pub fn try_new(soup: &PolygonSoup) -> Result<SoupWinding, BuildError> {
        let start = Instant::now();
        check_polygons(soup, RepeatedVertices::Allow)?;
        let corners: usize = soup.polygons.iter().map(|p| p.vertices.len()).sum();
        let mut polygons = SlotMap::with_capacity_and_key(soup.polygons.len());
        let (mut tris, mut faces) = (Vec::with_capacity(corners), Vec::with_capacity(corners));
        let mut ring: Vec<DVec3> = Vec::with_capacity(8);
        for (index, p) in soup.polygons.iter().enumerate() {
            let face = polygons.insert(index);
            ring.clear();
            ring.extend(p.vertices.iter().map(|&v| soup.positions[v]));
            push_fan(&mut ring, face, &mut tris, &mut faces);
        }
        let open = open_edges(soup);
        Ok(SoupWinding {
            accel: Accel::from_triangles(tris, faces, open, start),
            polygons,
        })
    }

    /// How many polygons the soup has.
    #[must_use]
    pub fn polygon_count(&self) -> usize {
        self.polygons.len()
    }

    /// How many edges (unordered pairs of distinct soup vertices that
    /// follow each other in a polygon) are run more often one way than the
    /// other: edges of one face, a fin's edges, the edges of a face wound
    /// against its neighbours. 0 means the polygons form a closed cycle,
    /// and classification then uses the exact crossing count.
    #[must_use]
    pub fn open_edges(&self) -> usize {
        self.accel.boundary_edges
    }

    /// The bounding box of the polygons' corners.
    #[must_use]
    pub fn bounds(&self) -> crate::geom::Aabb {
        self.accel.bounds()
    }

    /// Size and build time, as for [`Accel::stats`].
    #[must_use]
    pub fn stats(&self) -> AccelStats {
        self.accel.stats()
    }

    /// The generalized winding number of the soup's triangles around `p`;
    /// see [`Accel::winding_number`].
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate.
    pub fn winding_number(&self, p: DVec3) -> Result<f64, QueryError> {
        self.accel.winding_number(p)
    }

    /// [`SoupWinding::winding_number`] for every point, in order, on all
    /// cores.
    ///
    /// # Errors
    ///
    /// The first non-finite point, by index.
    pub fn winding_number_batch(&self, points: &[DVec3]) -> Result<Vec<f64>, QueryError> {
        self.accel.winding_number_batch(points)
    }

    /// Inside, outside or on the soup's triangles, by the winding number
    /// (see [`SoupWinding`] for what that means here).
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate.
    pub fn classify(&self, p: DVec3) -> Result<Containment, QueryError> {
        self.accel.classify_with(p, Method::Winding)
    }

    /// [`SoupWinding::classify`] for every point, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first non-finite point, by index.
    pub fn classify_batch(&self, points: &[DVec3]) -> Result<Vec<Containment>, QueryError> {
        self.accel.classify_batch(points, Method::Winding)
    }
}

/// How many edges of `soup` are run more often one way than the other
/// (each polygon's consecutive corners; a corner repeated in a row makes no
/// edge).
fn open_edges(soup: &PolygonSoup) -> usize {
    let mut runs: Vec<(usize, usize, i32)> = Vec::new();
    for p in &soup.polygons {
        let n = p.vertices.len();
        for (i, &a) in p.vertices.iter().enumerate() {
            let b = p.vertices[(i + 1) % n];
            match a.cmp(&b) {
                std::cmp::Ordering::Less => runs.push((a, b, 1)),
                std::cmp::Ordering::Greater => runs.push((b, a, -1)),
                std::cmp::Ordering::Equal => {}
            }
        }
    }
    runs.sort_unstable();
    runs.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1))
        .filter(|uses| uses.iter().map(|u| u.2).sum::<i32>() != 0)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Solid, builders};

    fn soup_of(solid: &Solid) -> PolygonSoup {
        let ids: Vec<_> = solid.vertices().map(|(id, _)| id).collect();
        let positions = ids.iter().map(|&id| solid.position(id)).collect();
        let polygons: Vec<Vec<usize>> = solid
            .faces()
            .map(|(f, _)| {
                solid
                    .face_vertices(f)
                    .map(|v| ids.iter().position(|&id| id == v).unwrap())
                    .collect()
            })
            .collect();
        PolygonSoup::new(positions, polygons)
    }

    #[test]
    fn a_solid_as_a_soup_answers_as_its_accel() {
        let solid = builders::l_prism();
        let soup = SoupWinding::try_new(&soup_of(&solid)).unwrap();
        let accel = Accel::new(&solid);
        assert_eq!(soup.open_edges(), 0);
        assert_eq!(soup.polygon_count(), solid.face_count());
        assert_eq!(soup.stats().triangles, accel.stats().triangles);
        let points: Vec<DVec3> = (0..343)
            .map(|i| DVec3::new((i % 7) as f64, (i / 7 % 7) as f64, (i / 49) as f64) * 0.5 - 0.25)
            .collect();
        assert_eq!(
            soup.classify_batch(&points).unwrap(),
            accel.classify_batch(&points, Method::Winding).unwrap()
        );
        assert_eq!(
            soup.winding_number_batch(&points).unwrap(),
            accel.winding_number_batch(&points).unwrap()
        );
    }

    #[test]
    fn edges_that_do_not_cancel_are_counted() {
        let cube = soup_of(&builders::cube());
        let mut open_box = cube.clone();
        open_box.polygons.pop();
        assert_eq!(open_edges(&open_box), 4);
        let mut flipped = cube.clone();
        flipped.polygons[0].vertices.reverse();
        assert_eq!(open_edges(&flipped), 4);
        // A corner repeated in a row makes no edge.
        let mut repeated = cube;
        let first = repeated.polygons[0].vertices[0];
        repeated.polygons[0].vertices.insert(0, first);
        assert_eq!(open_edges(&repeated), 0);
        assert!(SoupWinding::try_new(&repeated).is_ok());
    }

    #[test]
    fn bad_numbers_are_refused() {
        let cube = soup_of(&builders::cube());
        let empty = PolygonSoup::new(cube.positions.clone(), Vec::<Vec<usize>>::new());
        assert_eq!(
            SoupWinding::try_new(&empty).unwrap_err(),
            BuildError::NoPolygons
        );
        let mut nan = cube.clone();
        nan.positions[2].y = f64::NAN;
        assert!(matches!(
            SoupWinding::try_new(&nan),
            Err(BuildError::NonFinitePosition { vertex: 2, .. })
        ));
        let mut far = cube.clone();
        far.polygons[1].vertices[0] = 99;
        assert!(matches!(
            SoupWinding::try_new(&far),
            Err(BuildError::IndexOutOfRange {
                polygon: 1,
                index: 99,
                ..
            })
        ));
        let mut two = cube;
        two.polygons[3].vertices.truncate(2);
        assert!(matches!(
            SoupWinding::try_new(&two),
            Err(BuildError::TooFewVertices {
                polygon: 3,
                count: 2,
                ..
            })
        ));
        let soup = SoupWinding::try_new(&soup_of(&builders::cube())).unwrap();
        assert!(matches!(
            soup.classify(DVec3::new(0.0, f64::NAN, 0.0)),
            Err(QueryError::NonFinitePoint { .. })
        ));
        assert!(matches!(
            soup.classify_batch(&[DVec3::ZERO, DVec3::splat(f64::INFINITY)]),
            Err(QueryError::NonFinitePoint { index: 1, .. })
        ));
    }
}
