//! The one PNG encoder: 8-bit RGB or RGBA, fixed settings, no ancillary chunks.
//!
//! A file holds `IHDR`, `IDAT` and `IEND` only (no time, no text, no gamma or colour
//! profile chunk), and the encoder's settings are fixed per [`Compression`], so the same
//! pixels always give the same bytes: a re-run changes no file, and a golden image is
//! rewritten only when its pixels change. The stored values are sRGB-encoded, as PNG
//! viewers assume without a colour chunk (see [`crate::color`]).

use std::io::{self, Write};

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ImageBuffer, ImageEncoder as _, PixelWithColorType};

/// How hard the encoder works. It never changes the pixels, only the file's size and the
/// time it takes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Compression {
    /// zlib's default level with adaptive filtering: what renders, figures and reports
    /// are written with.
    #[default]
    Balanced,
    /// The smallest file the encoder can make, several times slower: for files that
    /// are committed, such as golden images.
    Smallest,
    /// The quickest encoding, a larger file: for images looked at once and thrown away,
    /// such as the live playground's frames, where encoding time is part of the wait.
    Fast,
}

/// Writes `image` to `out` as a PNG.
///
/// The pixel type decides the colour type: `image::Rgb<u8>` is stored as RGB,
/// `image::Rgba<u8>` as RGBA (straight alpha), `image::Luma<u8>` as grey.
///
/// # Errors
/// `InvalidInput` for an image with a zero width or height (a PNG holds at least one
/// pixel); any error of `out`.
pub fn write_png<P>(
    out: impl Write,
    image: &ImageBuffer<P, Vec<u8>>,
    compression: Compression,
) -> io::Result<()>
where
    P: PixelWithColorType<Subpixel = u8>,
{
    let (width, height) = image.dimensions();
    if width == 0 || height == 0 {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "cannot encode a {width}x{height} image as PNG: both sides must be at least 1 pixel"
            ),
        ));
    }
    let compression = match compression {
        Compression::Balanced => CompressionType::Default,
        Compression::Smallest => CompressionType::Best,
        Compression::Fast => CompressionType::Fast,
    };
    PngEncoder::new_with_quality(out, compression, FilterType::Adaptive)
        .write_image(image.as_raw(), width, height, P::COLOR_TYPE)
        .map_err(|error| match error {
            image::ImageError::IoError(error) => error,
            other => io::Error::other(other),
        })
}

/// [`write_png`] into memory: the PNG file's bytes.
///
/// # Errors
/// `InvalidInput` for an image with a zero width or height.
pub fn encode_png<P>(
    image: &ImageBuffer<P, Vec<u8>>,
    compression: Compression,
) -> io::Result<Vec<u8>>
where
    P: PixelWithColorType<Subpixel = u8>,
{
    let mut bytes = Vec::new();
    write_png(&mut bytes, image, compression)?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use image::{Rgb, RgbImage, Rgba, RgbaImage};

    use super::*;

    /// The chunk types of a PNG file, in order.
    fn chunks(png: &[u8]) -> Vec<String> {
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let mut chunks = Vec::new();
        let mut at = 8;
        while at < png.len() {
            let length = u32::from_be_bytes(png[at..at + 4].try_into().unwrap()) as usize;
            chunks.push(String::from_utf8_lossy(&png[at + 4..at + 8]).into_owned());
            at += 12 + length;
        }
        chunks
    }

    #[test]
    fn pixels_round_trip_and_only_the_three_critical_chunks_are_written() {
        let rgb = RgbImage::from_fn(5, 3, |x, y| Rgb([x as u8 * 50, y as u8 * 100, 7]));
        let rgba = RgbaImage::from_fn(4, 2, |x, y| Rgba([x as u8, y as u8, 9, 128]));
        for compression in [
            Compression::Balanced,
            Compression::Smallest,
            Compression::Fast,
        ] {
            let png = encode_png(&rgb, compression).unwrap();
            assert_eq!(chunks(&png), ["IHDR", "IDAT", "IEND"]);
            let decoded = image::load_from_memory(&png).unwrap();
            assert_eq!(decoded.color(), image::ColorType::Rgb8);
            assert_eq!(decoded.to_rgb8(), rgb);

            let png = encode_png(&rgba, compression).unwrap();
            assert_eq!(chunks(&png), ["IHDR", "IDAT", "IEND"]);
            let decoded = image::load_from_memory(&png).unwrap();
            assert_eq!(decoded.color(), image::ColorType::Rgba8);
            assert_eq!(decoded.to_rgba8(), rgba);
        }
    }

    #[test]
    fn the_same_pixels_give_the_same_bytes() {
        let image = RgbImage::from_fn(64, 64, |x, y| Rgb([(x * y) as u8, x as u8, y as u8]));
        let first = encode_png(&image, Compression::Balanced).unwrap();
        assert_eq!(encode_png(&image, Compression::Balanced).unwrap(), first);
        let mut streamed = Vec::new();
        write_png(&mut streamed, &image, Compression::Balanced).unwrap();
        assert_eq!(streamed, first);
    }

    #[test]
    fn an_empty_image_is_refused() {
        for (width, height) in [(0, 10), (10, 0), (0, 0)] {
            let error =
                encode_png(&RgbaImage::new(width, height), Compression::Balanced).unwrap_err();
            assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
            assert_eq!(
                error.to_string(),
                format!(
                    "cannot encode a {width}x{height} image as PNG: both sides must be at least 1 pixel"
                )
            );
        }
    }
}
