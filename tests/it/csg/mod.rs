//! Ray-cast CSG: trees, polyhedral leaves and where they touch, rays at the
//! edge of `f64`, scene files (field, sweep, revolve and loft leaves) and
//! rendering.

mod exact_contacts;
mod mesh;
mod ray_range;
mod render;
mod scene_fields;
mod scene_paths;
mod scene_solids;
mod tree;
