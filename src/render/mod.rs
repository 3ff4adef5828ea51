//! Ray-cast images of a CSG scene: one camera ray per pixel, the first hit's
//! normal, Lambert shading with the scene's light, and shadow rays only when
//! the scene asks for them.

mod camera;
mod image;
mod shade;

pub use camera::Camera;
pub use image::{Image, ImageError};
pub use shade::{RenderOptions, render};
