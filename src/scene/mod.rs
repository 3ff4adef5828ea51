//! Scene files: a CSG tree plus optional camera, light and shadows, in
//! JSON; and [`Target`], a mesh or a scene that answers point and ray
//! queries.
//!
//! ```text
//! {"root": NODE, "camera": {...}, "light": {...}, "shadows": false}   (camera, light, shadows optional)
//! NODE := {"mesh": "relative/path.obj"}
//!       | {"halfspace": {"point": [x,y,z], "normal": [x,y,z]}}
//!       | {"box": {"min": [x,y,z], "max": [x,y,z]}}
//!       | {"sphere": {"center": [x,y,z], "radius": r}}
//!       | {"cylinder": {"base": [x,y,z], "axis": [x,y,z], "radius": r}}   (axis: base to top)
//!       | {"sweep": {...}} | {"revolve": {...}} | {"loft": {...}}     (solids from profiles and curves: solid_leaf.rs)
//!       | {"union": [NODE, ...]} | {"intersection": [NODE, ...]} | {"difference": [NODE, NODE, ...]}
//!       | {"transform": {"translate": [..], "rotate_deg": [rx,ry,rz], "scale": [..]}, "child": NODE}
//!       | {"field": FIELD | "relative/path.json"}  (a field document, meshed by marching cubes)
//!       | {"scene": "relative/path.json"}       (the root of another scene file)
//! camera := {"eye": [x,y,z], "look_at": [x,y,z], "up": [x,y,z], "fov_deg": f}   (up, fov_deg optional)
//! light  := {"direction": [x,y,z]} | {"position": [x,y,z]}, plus optional "ambient": a in [0, 1]
//! ```
//!
//! A transform scales, then rotates (about x, then y, then z, in degrees),
//! then translates; each part is optional. Mesh paths are relative to the
//! scene file. Unknown keys and bad values are errors naming the JSON path,
//! e.g. `root.difference[1].sphere.radius`.
//!
//! # Paths
//!
//! A file a leaf names (mesh, field document, included scene) must
//! resolve, symbolic links followed, inside the naming scene file's folder
//! or the working directory, or inside a folder of
//! [`ImportOptions::allowed_roots`](crate::io::ImportOptions::allowed_roots)
//! ([`SceneError::PathOutside`] otherwise), and must be a regular file
//! ([`SceneError::NotRegularFile`]: a FIFO or a device is refused before
//! it is opened). Messages quote input only in short, escaped excerpts.
//!
//! # Limits
//!
//! Hostile files are refused quickly, with the limit named in the error:
//! JSON nested deeper than [`MAX_JSON_DEPTH`] (the JSON reader's own
//! limit), nodes nested deeper than [`MAX_NODE_DEPTH`] counting through
//! included files, more than [`MAX_NODES`] nodes in all (each inclusion
//! counted again), included files nested deeper than
//! [`MAX_INCLUDE_DEPTH`], and a file that includes itself, directly or
//! through others (paths compared after canonicalization). The camera,
//! light and shadows of an included scene are ignored; a mesh named twice
//! is read and validated once. A field leaf is meshed at its document's
//! `resolution` (default [`DEFAULT_FIELD_RESOLUTION`], at most
//! [`MAX_FIELD_RESOLUTION`]) and must validate as a closed solid; `FIELD`
//! is the document format of `wingedge::field` (blobs and field operators).
//!
//! # Files
//!
//! `json.rs` reads values with their JSON paths, `node.rs` the tree's
//! nodes, `reader.rs` files and inclusions, `leaf_path.rs` the path
//! policy of leaves, `limits.rs` counts against the limits, `mesh_leaf.rs` loads and validates OBJ leaves, `solid_leaf.rs` builds
//! and validates sweep, revolve and loft leaves, `field_leaf.rs` meshes
//! field leaves, `view.rs` the
//! camera and light, `load.rs` assembles a [`Scene`], `target.rs` is the
//! mesh-or-scene [`Target`].

mod error;
mod field_leaf;
mod json;
mod leaf_path;
mod limits;
mod load;
mod mesh_leaf;
mod node;
mod reader;
mod solid_leaf;
mod target;
mod view;

pub use error::SceneError;
pub use field_leaf::{DEFAULT_FIELD_RESOLUTION, MAX_FIELD_RESOLUTION};
pub use limits::{MAX_INCLUDE_DEPTH, MAX_JSON_DEPTH, MAX_NODE_DEPTH, MAX_NODES};
pub use load::Scene;
pub use mesh_leaf::is_scene_path;
pub use solid_leaf::DEFAULT_TOLERANCE;
pub use target::{RayAnswer, Target, TargetError};
pub use view::{CameraSpec, DEFAULT_AMBIENT, LightSpec};
