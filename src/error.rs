//! One error type for callers that do not need to tell the layers apart:
//! every layer's error converts into [`Error`] by `?`, and its message is
//! the layer's own (naming the file, line, JSON path, element ids or
//! values it refuses).

use thiserror::Error as ThisError;

/// Any error of the crate, wrapping the layer that raised it.
#[derive(Debug, ThisError)]
#[non_exhaustive]
pub enum Error {
    /// A plane could not be fitted.
    #[error(transparent)]
    Plane(#[from] crate::geom::PlaneError),
    /// A polygon could not be triangulated.
    #[error(transparent)]
    Triangulate(#[from] crate::geom::TriangulateError),
    /// A curve is refused.
    #[error(transparent)]
    Curve(#[from] crate::curve::CurveError),
    /// A soup is no solid.
    #[error(transparent)]
    Build(#[from] crate::mesh::BuildError),
    /// An Euler operator's pre-condition does not hold.
    #[error(transparent)]
    Euler(#[from] crate::mesh::EulerError),
    /// A solid's tables disagree.
    #[error(transparent)]
    Consistency(#[from] crate::mesh::ConsistencyError),
    /// A sweep, revolve or loft is refused.
    #[error(transparent)]
    Sweep(#[from] crate::shape::SweepError),
    /// An OBJ file cannot be read.
    #[error(transparent)]
    Obj(#[from] crate::io::ObjError),
    /// A mesh file of another format cannot be read.
    #[error(transparent)]
    Import(#[from] crate::io::ImportError),
    /// A mesh file cannot be written.
    #[error(transparent)]
    Export(#[from] crate::io::ExportError),
    /// A JSON document cannot be read.
    #[error(transparent)]
    Json(#[from] crate::io::JsonError),
    /// A query cannot be answered.
    #[error(transparent)]
    Query(#[from] crate::query::QueryError),
    /// Validation cannot run.
    #[error(transparent)]
    Validate(#[from] crate::validate::ValidateError),
    /// A boolean is refused.
    #[error(transparent)]
    Boolean(#[from] crate::boolean::BooleanError),
    /// A soup cannot be repaired.
    #[error(transparent)]
    Repair(#[from] crate::repair::RepairError),
    /// A CSG tree is malformed.
    #[error(transparent)]
    Csg(#[from] crate::csg::CsgError),
    /// A CSG tree cannot be evaluated into a solid.
    #[error(transparent)]
    Evaluate(#[from] crate::csg::EvaluateError),
    /// A volume cannot be integrated.
    #[error(transparent)]
    Volume(#[from] crate::csg::VolumeError),
    /// A field is refused or cannot be meshed.
    #[error(transparent)]
    Field(#[from] crate::field::FieldError),
    /// Octree cells cannot be built.
    #[error(transparent)]
    Cells(#[from] crate::cells::CellsError),
    /// A scene cannot be loaded.
    #[error(transparent)]
    Scene(#[from] crate::scene::SceneError),
    /// A file cannot be opened as a query target.
    #[error(transparent)]
    Target(#[from] crate::scene::TargetError),
    /// An image cannot be made or written.
    #[error(transparent)]
    Image(#[from] crate::render::ImageError),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `?` lifts each layer's error, and the message is the layer's own.
    #[test]
    fn layers_convert_by_question_mark() {
        fn load(path: &str) -> Result<crate::mesh::Solid, Error> {
            let import = crate::io::import_obj(
                std::path::Path::new(path),
                &crate::io::ObjOptions::default(),
            )?;
            Ok(crate::mesh::Solid::try_from_soup(&import.soup)?)
        }
        let err = load("no/such/file.obj").unwrap_err();
        assert!(matches!(err, Error::Obj(_)), "{err:?}");
        assert!(err.to_string().contains("no/such/file.obj"), "{err}");
    }
}
