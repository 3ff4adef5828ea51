//! An RGB image and its PNG encoding.

use std::path::{Path, PathBuf};

use thiserror::Error;

/// Why an image could not be written.
#[derive(Debug, Error)]
pub enum ImageError {
    /// The file could not be created or written.
    #[error("{file}: cannot write: {source}")]
    Io {
        /// The output file.
        file: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The PNG encoder refused the data.
    #[error("{file}: PNG encoding failed: {message}")]
    Encode {
        /// The output file.
        file: PathBuf,
        /// The encoder's message.
        message: String,
    },
}

/// An 8-bit RGB image, rows from the top.
///
/// # Invariants
///
/// `pixels.len() == width × height`.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<[u8; 3]>,
}

impl Image {
    /// An image from rows of pixels, or `None` if the count is not
    /// `width × height`.
    #[must_use]
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> Option<Image> {
        (pixels.len() as u64 == u64::from(width) * u64::from(height)).then_some(Image {
            width,
            height,
            pixels,
        })
    }

    /// The width in pixels.
    #[must_use]
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The height in pixels.
    #[must_use]
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The pixel at column `x`, row `y`, or `None` outside the image.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        (x < self.width && y < self.height)
            .then(|| self.pixels[(y as usize) * (self.width as usize) + x as usize])
    }

    /// Writes the image as a PNG file, atomically
    /// ([`write_atomically`](crate::io::write_atomically)).
    ///
    /// # Errors
    ///
    /// [`ImageError`] naming the file.
    pub fn write_png(&self, path: &Path) -> Result<(), ImageError> {
        let io = |source| ImageError::Io {
            file: path.to_path_buf(),
            source,
        };
        let encode = |e: png::EncodingError| ImageError::Encode {
            file: path.to_path_buf(),
            message: e.to_string(),
        };
        let data: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        let mut encoding = None;
        let written = crate::io::write_atomically(path, |file| {
            let mut encoder = png::Encoder::new(file, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            let encoded = encoder.write_header().and_then(|mut writer| {
                writer.write_image_data(&data)?;
                writer.finish()
            });
            encoded.map_err(|e| {
                let refusal = std::io::Error::other(e.to_string());
                encoding = Some(e);
                refusal
            })
        });
        match (written, encoding) {
            (Ok(()), _) => Ok(()),
            (Err(_), Some(e)) if !matches!(e, png::EncodingError::IoError(_)) => Err(encode(e)),
            (Err(e), _) => Err(io(e)),
        }
    }
}
