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

/// An 8-bit RGB image, rows from the top: three bytes per pixel and
/// nothing per row (a 1 × 10⁷ image took 168 bytes per row when rows were
/// kept apart).
///
/// # Invariants
///
/// `bytes.len() == 3 × width × height`.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    bytes: Vec<u8>,
}

impl Image {
    /// An image from rows of pixels, or `None` if the count is not
    /// `width × height`.
    #[must_use]
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<[u8; 3]>) -> Option<Image> {
        let bytes = pixels.into_iter().flatten().collect();
        Image::from_rgb_bytes(width, height, bytes)
    }

    /// An image from its RGB bytes, rows from the top, or `None` if there
    /// are not `3 × width × height` of them.
    #[must_use]
    pub fn from_rgb_bytes(width: u32, height: u32, bytes: Vec<u8>) -> Option<Image> {
        (bytes.len() as u64 == 3 * u64::from(width) * u64::from(height)).then_some(Image {
            width,
            height,
            bytes,
        })
    }

    /// The RGB bytes, rows from the top.
    #[must_use]
    pub fn rgb_bytes(&self) -> &[u8] {
        &self.bytes
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
        (x < self.width && y < self.height).then(|| {
            let at = 3 * ((y as usize) * (self.width as usize) + x as usize);
            [self.bytes[at], self.bytes[at + 1], self.bytes[at + 2]]
        })
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
        let data = &self.bytes;
        let mut encoding = None;
        let written = crate::io::write_atomically(path, |file| {
            let mut encoder = png::Encoder::new(file, self.width, self.height);
            encoder.set_color(png::ColorType::Rgb);
            encoder.set_depth(png::BitDepth::Eight);
            let encoded = encoder.write_header().and_then(|mut writer| {
                writer.write_image_data(data)?;
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
