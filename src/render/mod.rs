//! Images: ray-cast pictures of a CSG scene (one camera ray per pixel, the
//! first hit's normal, Lambert shading with the scene's light, and shadow
//! rays only when the scene asks for them), and pictures of a validation
//! report ([`render_defects`]: the polygon soup rasterized with its defects
//! marked, for meshes that are no solid).

mod camera;
mod defects;
mod font;
mod image;
mod raster;
mod shade;

pub use camera::Camera;
pub use defects::{
    DefectImageError, DefectImageOptions, DefectMark, MAX_DEFECT_IMAGE_PIXELS, defect_colour,
    defect_mark, render_defects,
};
pub use image::{Image, ImageError};
pub use shade::{RenderOptions, render};
