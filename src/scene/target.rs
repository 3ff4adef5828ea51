//! What a point or ray query runs on: one OBJ mesh, or a CSG scene, loaded
//! from a path by one function and answered through one type.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use glam::DVec3;
use thiserror::Error;

use super::mesh_leaf::is_scene_path;
use super::{Scene, SceneError};
use crate::csg::{Containment, Spans, Stats};
use crate::geom::{Ray, Readable};
use crate::io::{ImportError, ImportOptions, ObjError, import};
use crate::mesh::{BuildError, PolygonSoup, RepeatedVertices, Solid, check_polygons};
use crate::query::{Accel, Method, QueryError, RayCrossings, SoupWinding};

/// Why a target could not be loaded or could not answer.
#[derive(Debug, Error)]
pub enum TargetError {
    /// The OBJ file could not be read (the message names it and the line).
    #[error(transparent)]
    Obj(#[from] ObjError),
    /// A mesh file of another format could not be read (the message names
    /// it and the place in it).
    #[error(transparent)]
    Import(ImportError),
    /// The mesh file's polygons do not make a winged-edge solid.
    #[error("{}: {source}", .file.display())]
    Build {
        /// The OBJ file.
        file: PathBuf,
        /// Why.
        source: BuildError,
    },
    /// The scene file could not be loaded (the message names it and the
    /// JSON path).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A query was refused: a non-finite point or an invalid ray (by its
    /// index in the batch), or a method the mesh does not allow.
    #[error("{}: {source}", .file.display())]
    Query {
        /// The mesh or scene file.
        file: PathBuf,
        /// Why.
        source: QueryError,
    },
}

/// A mesh or a scene, answering points and rays.
///
/// A mesh is built as a winged-edge solid but not validated, so that the
/// winding number can answer an open mesh; parity, normals and rays refuse
/// what they cannot answer. A mesh whose polygons cannot be a winged-edge
/// solid at all (an edge of three faces, faces wound against their
/// neighbours) still loads: the winding method answers it from its
/// triangles ([`SoupWinding`]), and everything else returns the build
/// error ([`Target::build_refusal`]). A scene's mesh leaves are validated
/// closed solids (see [`Scene`]).
///
/// # Invariants
///
/// `file` is the path it was loaded from; a mesh's accel was built from the
/// solid of that file.
#[derive(Debug)]
pub struct Target {
    file: PathBuf,
    kind: Kind,
}

#[derive(Debug)]
enum Kind {
    Mesh(Box<Accel>),
    Soup(Box<SoupMesh>),
    Scene(Scene),
}

/// A mesh that is no solid: why it did not build, its soup, and the soup's
/// triangles, built by the first winding query (parity, normals and rays
/// never pay for them).
#[derive(Debug)]
struct SoupMesh {
    refused: BuildError,
    soup: PolygonSoup,
    winding: OnceLock<Result<SoupWinding, BuildError>>,
}

/// A ray's answer from a [`Target`].
#[derive(Clone, Debug, PartialEq)]
pub enum RayAnswer {
    /// From a mesh: where the origin is and every boundary crossing.
    Crossings(RayCrossings),
    /// From a scene: whether the origin is inside and the spans inside the
    /// solid.
    Spans(Spans),
}

impl fmt::Display for RayAnswer {
    /// One line without its end: for a mesh, `inside`, `outside` or
    /// `boundary` for the origin, then each crossing's `t`; for a scene,
    /// `inside` or `outside` just after the origin, then each span as
    /// `[t0, t1]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RayAnswer::Crossings(c) => {
                f.write_str(c.origin.as_word())?;
                for h in &c.hits {
                    write!(f, " {:?}", h.t)?;
                }
            }
            RayAnswer::Spans(s) => {
                f.write_str(if s.origin_inside { "inside" } else { "outside" })?;
                for (a, b) in s.intervals() {
                    write!(f, " [{}, {}]", Readable(a), Readable(b))?;
                }
            }
        }
        Ok(())
    }
}

impl Target {
    /// Loads `path`: a scene file when [`is_scene_path`] says so, else an
    /// OBJ mesh, as a solid when its polygons build into one, else as a
    /// soup whose triangles answer the winding method.
    ///
    /// # Errors
    ///
    /// [`TargetError`] naming the file (and the OBJ line or JSON path); for
    /// a mesh whose numbers do not even make triangles (no polygon, a
    /// polygon of fewer than three corners, an index out of range, a NaN
    /// coordinate), the build error.
    pub fn try_load(path: &Path) -> Result<Target, TargetError> {
        Target::try_load_with(path, &ImportOptions::default())
    }

    /// [`Target::try_load`], a mesh read as `options` say (its format
    /// given, say); with a format given, a `.json` path is read as a mesh;
    /// a scene's leaves also allowed inside `options.allowed_roots`.
    ///
    /// # Errors
    ///
    /// As [`Target::try_load`].
    pub fn try_load_with(path: &Path, options: &ImportOptions) -> Result<Target, TargetError> {
        let kind = if is_scene_path(path) && options.format.is_none() {
            Kind::Scene(Scene::from_file_with(path, options)?)
        } else {
            let soup = match import(path, options) {
                Ok(import) => import.soup,
                Err(ImportError::Obj(e)) => return Err(TargetError::Obj(e)),
                Err(e) => return Err(TargetError::Import(e)),
            };
            match Solid::try_from_soup(&soup) {
                Ok(solid) => Kind::Mesh(Box::new(Accel::new(&solid))),
                // Numbers that make triangles: the winding number answers.
                Err(refused) if check_polygons(&soup, RepeatedVertices::Allow).is_ok() => {
                    Kind::Soup(Box::new(SoupMesh {
                        refused,
                        soup,
                        winding: OnceLock::new(),
                    }))
                }
                Err(refused) => {
                    return Err(TargetError::Build {
                        file: path.to_path_buf(),
                        source: refused,
                    });
                }
            }
        };
        Ok(Target {
            file: path.to_path_buf(),
            kind,
        })
    }

    /// The file it was loaded from.
    #[must_use]
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The scene, if it is one.
    #[must_use]
    pub fn scene(&self) -> Option<&Scene> {
        match &self.kind {
            Kind::Scene(scene) => Some(scene),
            Kind::Mesh(_) | Kind::Soup(_) => None,
        }
    }

    /// Why a mesh could not be built into a winged-edge solid, when it
    /// could not: only [`Method::Winding`] answers it then (parity is
    /// undefined), from its triangles.
    #[must_use]
    pub fn build_refusal(&self) -> Option<&BuildError> {
        match &self.kind {
            Kind::Soup(mesh) => Some(&mesh.refused),
            Kind::Mesh(_) | Kind::Scene(_) => None,
        }
    }

    fn build_error(&self, refused: &BuildError) -> TargetError {
        TargetError::Build {
            file: self.file.clone(),
            source: refused.clone(),
        }
    }

    fn query_error(&self, source: QueryError) -> TargetError {
        TargetError::Query {
            file: self.file.clone(),
            source,
        }
    }

    /// Classifies `points`, in order: a mesh by `method` (all cores), a
    /// scene by its tree (`method` is not used; `stats` counts its work).
    ///
    /// # Errors
    ///
    /// [`TargetError::Query`] for a non-finite point (its index) or a
    /// method the mesh does not allow (normals on a non-convex solid,
    /// parity on an open one); [`TargetError::Build`] for any method but the
    /// winding number on a mesh that is no solid.
    pub fn classify(
        &self,
        points: &[DVec3],
        method: Method,
        stats: &mut Stats,
    ) -> Result<Vec<Containment>, TargetError> {
        match &self.kind {
            Kind::Mesh(accel) => accel
                .classify_batch(points, method)
                .map_err(|e| self.query_error(e)),
            Kind::Soup(mesh) if method == Method::Winding => {
                // The numbers were checked at load; should they not make
                // triangles after all, the build error stands.
                let winding = mesh
                    .winding
                    .get_or_init(|| SoupWinding::try_new(&mesh.soup))
                    .as_ref()
                    .map_err(|_| self.build_error(&mesh.refused))?;
                winding
                    .classify_batch(points)
                    .map_err(|e| self.query_error(e))
            }
            Kind::Soup(mesh) => Err(self.build_error(&mesh.refused)),
            Kind::Scene(scene) => {
                if let Some(index) = points.iter().position(|p| !p.is_finite()) {
                    let point = points[index];
                    return Err(self.query_error(QueryError::NonFinitePoint { index, point }));
                }
                Ok(points
                    .iter()
                    .map(|&p| scene.csg.classify_point(p, stats))
                    .collect())
            }
        }
    }

    /// Answers `rays`, in order: a mesh's crossings (all cores) or a
    /// scene's spans (`stats` counts the scene's work).
    ///
    /// # Errors
    ///
    /// [`TargetError::Query`] for an invalid ray (its index: a non-finite
    /// origin or direction, or a zero direction), a scene's ray whose answer
    /// `f64` cannot hold ([`crate::csg::Csg::try_spans`]) or an open mesh;
    /// [`TargetError::Build`] for a mesh that is no solid.
    pub fn rays(&self, rays: &[Ray], stats: &mut Stats) -> Result<Vec<RayAnswer>, TargetError> {
        match &self.kind {
            Kind::Mesh(accel) => accel
                .ray_crossings_batch(rays)
                .map(|answers| answers.into_iter().map(RayAnswer::Crossings).collect())
                .map_err(|e| self.query_error(e)),
            Kind::Soup(mesh) => Err(self.build_error(&mesh.refused)),
            Kind::Scene(scene) => rays
                .iter()
                .enumerate()
                .map(|(index, r)| {
                    scene
                        .csg
                        .try_spans_at(index, r, stats)
                        .map(RayAnswer::Spans)
                        .map_err(|e| self.query_error(e))
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fixture(path: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
    }

    fn x_ray(y: f64, z: f64) -> Ray {
        Ray::new(DVec3::new(-3.0, y, z), DVec3::X)
    }

    #[test]
    fn a_mesh_answers_by_its_solid() {
        let target = Target::try_load(&fixture("fixtures/valid/cube.obj")).unwrap();
        assert!(target.scene().is_none());
        let mut stats = Stats::default();
        let points = [DVec3::ZERO, DVec3::splat(3.0), DVec3::new(1.0, 0.0, 0.0)];
        for method in [Method::Parity, Method::Normals, Method::Winding] {
            assert_eq!(
                target.classify(&points, method, &mut stats).unwrap(),
                [
                    Containment::Inside,
                    Containment::Outside,
                    Containment::OnBoundary
                ]
            );
        }
        let answers = target.rays(&[x_ray(0.75, 0.75)], &mut stats).unwrap();
        assert_eq!(answers[0].to_string(), "outside 2.0 4.0");
        // A mesh does no CSG work.
        assert_eq!(stats, Stats::default());
    }

    #[test]
    fn a_scene_answers_by_its_tree() {
        let target = Target::try_load(&fixture("fixtures/scenes/drilled_cube.json")).unwrap();
        assert!(target.scene().is_some());
        let mut stats = Stats::default();
        // The drills remove the centre; the wall between them stays.
        let points = [DVec3::ZERO, DVec3::splat(0.9), DVec3::splat(3.0)];
        assert_eq!(
            target
                .classify(&points, Method::Parity, &mut stats)
                .unwrap(),
            [
                Containment::Outside,
                Containment::Inside,
                Containment::Outside
            ]
        );
        let answers = target
            .rays(&[x_ray(0.75, 0.75), x_ray(0.0, 0.0)], &mut stats)
            .unwrap();
        assert_eq!(answers[0].to_string(), "outside [2, 4]");
        assert_eq!(answers[1].to_string(), "outside");
        assert!(stats.primitive_ray_tests > 0, "{stats}");
    }

    #[test]
    fn refusals_name_the_file_and_the_query() {
        let scene = fixture("fixtures/scenes/drilled_cube.json");
        let target = Target::try_load(&scene).unwrap();
        let mut stats = Stats::default();
        let e = target
            .classify(
                &[DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0)],
                Method::Parity,
                &mut stats,
            )
            .unwrap_err();
        assert!(
            matches!(
                e,
                TargetError::Query {
                    source: QueryError::NonFinitePoint { index: 1, .. },
                    ..
                }
            ),
            "{e}"
        );
        assert!(e.to_string().starts_with(&scene.display().to_string()));
        let e = target
            .rays(
                &[x_ray(0.0, 0.0), Ray::new(DVec3::ZERO, DVec3::ZERO)],
                &mut stats,
            )
            .unwrap_err();
        assert!(
            matches!(
                e,
                TargetError::Query {
                    source: QueryError::InvalidRay { index: 1, .. },
                    ..
                }
            ),
            "{e}"
        );

        // An open mesh loads (the winding number answers it) but has no
        // parity and no crossings.
        let hole = fixture("tests/bad_inputs/hole.obj");
        let target = Target::try_load(&hole).unwrap();
        let inside = DVec3::splat(0.1);
        assert!(
            target
                .classify(&[inside], Method::Winding, &mut stats)
                .is_ok()
        );
        let e = target.rays(&[x_ray(0.1, 0.1)], &mut stats).unwrap_err();
        assert!(
            matches!(
                e,
                TargetError::Query {
                    source: QueryError::NotClosed { .. },
                    ..
                }
            ),
            "{e}"
        );
        assert!(
            e.to_string().contains("hole.obj: the solid is not closed"),
            "{e}"
        );

        // A mesh that is no solid (three faces on an edge) loads: the
        // winding number answers it, everything else is its build error.
        let fin = fixture("fixtures/soups/fin.obj");
        let target = Target::try_load(&fin).unwrap();
        assert!(matches!(
            target.build_refusal(),
            Some(BuildError::NonManifoldEdge { .. })
        ));
        assert_eq!(
            target
                .classify(&[DVec3::splat(0.5)], Method::Winding, &mut stats)
                .unwrap(),
            [Containment::Inside]
        );
        for e in [
            target
                .classify(&[DVec3::splat(0.5)], Method::Parity, &mut stats)
                .unwrap_err(),
            target
                .classify(&[DVec3::splat(0.5)], Method::Normals, &mut stats)
                .unwrap_err(),
            target.rays(&[x_ray(0.5, 0.5)], &mut stats).unwrap_err(),
        ] {
            assert!(matches!(e, TargetError::Build { .. }), "{e}");
            assert!(e.to_string().contains("fin.obj: edge 1–2"), "{e}");
        }
        assert!(
            Target::try_load(&fixture("fixtures/valid/cube.obj"))
                .unwrap()
                .build_refusal()
                .is_none()
        );

        let missing = fixture("tests/bad_inputs/missing.obj");
        let e = Target::try_load(&missing).unwrap_err();
        assert!(matches!(e, TargetError::Obj(_)), "{e}");
        assert!(e.to_string().contains("missing.obj: cannot read"), "{e}");
        let e = Target::try_load(&fixture("tests/bad_inputs/negative_radius.json")).unwrap_err();
        assert!(matches!(e, TargetError::Scene(_)), "{e}");
        assert!(
            e.to_string()
                .contains("root.difference[1].sphere.radius: expected a positive number"),
            "{e}"
        );
    }
}
