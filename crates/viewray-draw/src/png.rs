//! PNG encoding.

use std::io;

use image::{ExtendedColorType, ImageEncoder as _, RgbaImage};

/// Encodes `pixels` as an RGBA8 PNG with no ancillary chunks (no time, no text), so equal
/// pixels always give equal bytes.
///
/// # Errors
/// `InvalidInput` for an image with a zero width or height, which PNG cannot hold.
pub(crate) fn encode_png(pixels: &RgbaImage) -> io::Result<Vec<u8>> {
    if pixels.width() == 0 || pixels.height() == 0 {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "cannot encode a {}x{} image as PNG: both sides must be at least 1 pixel",
                pixels.width(),
                pixels.height()
            ),
        ));
    }
    let mut bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut bytes)
        .write_image(
            pixels.as_raw(),
            pixels.width(),
            pixels.height(),
            ExtendedColorType::Rgba8,
        )
        .map_err(io::Error::other)?;
    Ok(bytes)
}
