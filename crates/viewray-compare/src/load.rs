//! Reading image files into pixels: PNG (the golden images, and any render), and what a
//! student's ray tracer writes besides: PPM and PGM (Netpbm), OpenEXR.

use std::io;
use std::path::{Path, PathBuf};

use image::{DynamicImage, ImageFormat, ImageReader, RgbaImage};

/// The image formats [`load_image`] reads, as its messages name them.
pub const SUPPORTED_IMAGES: &str = "PNG, PPM/PGM (P2, P3, P5, P6) or OpenEXR";

/// The file-name extensions of the formats [`load_image`] reads, lowercase: a student's
/// `tower.ppm` answers the reference `tower.png`.
pub const IMAGE_EXTENSIONS: [&str; 5] = ["png", "ppm", "pgm", "pnm", "exr"];

/// Why an image file could not be read. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file could not be opened or read (missing, a directory, no permission).
    #[error("{}: cannot read the file: {source}", path.display())]
    Unreadable {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        #[source]
        source: io::Error,
    },
    /// The file does not start with the PNG signature.
    #[error("{}: not a PNG file (it does not start with the PNG signature)", path.display())]
    NotPng {
        /// The file.
        path: PathBuf,
    },
    /// The file is no image format viewray reads ([`load_image`]).
    #[error("{}: not an image viewray reads ({SUPPORTED_IMAGES})", path.display())]
    NotAnImage {
        /// The file.
        path: PathBuf,
    },
    /// The file starts like an image of `format` but its contents do not decode
    /// (truncated or corrupt).
    #[error("{}: the {format} does not decode: {source}", path.display())]
    Decode {
        /// The file.
        path: PathBuf,
        /// The format its first bytes announce: `PNG`, `PPM`, `OpenEXR`.
        format: &'static str,
        /// The decoder's reason.
        #[source]
        source: image::ImageError,
    },
}

/// The eight bytes every PNG file starts with.
const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];

/// Reads the PNG file at `path` and decodes it to RGBA8 pixels, sRGB-encoded as stored
/// (grey, palette, RGB and 16-bit PNGs are converted; a PNG without alpha is opaque).
///
/// The pixels are what get compared, never the file's bytes: two PNGs written with
/// different compression settings or chunks hold the same image.
///
/// # Errors
/// [`LoadError`] naming the file: unreadable, not a PNG (checked by signature, whatever
/// the file's extension), or not decodable.
pub fn load_png(path: impl AsRef<Path>) -> Result<RgbaImage, LoadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Unreadable {
        path: path.to_owned(),
        source,
    })?;
    decode_png(&bytes).map_err(|error| match error {
        DecodeError::NotPng => LoadError::NotPng {
            path: path.to_owned(),
        },
        DecodeError::Image(source) => LoadError::Decode {
            path: path.to_owned(),
            format: "PNG",
            source,
        },
    })
}

/// Reads the image file at `path`, whatever its supported format (told by its first
/// bytes, never by its name), and decodes it to RGBA8 pixels, sRGB-encoded:
///
/// - PNG: any bit depth and colour type, as [`load_png`];
/// - PPM and PGM (Netpbm `P2`, `P3`, `P5`, `P6`, with comments, any maxval up to 65535,
///   scaled to 8 bits; `P1`, `P4` and `P7` are read too): the values as written, taken as
///   sRGB-encoded, as an image viewer shows them;
/// - OpenEXR: linear light (what a renderer computes), encoded with the sRGB transfer
///   function, as `viewray render` encodes its PNGs.
///
/// # Errors
/// [`LoadError`] naming the file: unreadable, not an image of these formats (one line
/// naming them), or not decodable.
pub fn load_image(path: impl AsRef<Path>) -> Result<RgbaImage, LoadError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Unreadable {
        path: path.to_owned(),
        source,
    })?;
    let Some(format) = image_format(&bytes) else {
        return Err(LoadError::NotAnImage {
            path: path.to_owned(),
        });
    };
    let decode_error = |source| LoadError::Decode {
        path: path.to_owned(),
        format: format_name(format),
        source,
    };
    // The decoder's default limits (512 MiB of pixels) stop absurd headers.
    let image = ImageReader::with_format(io::Cursor::new(&bytes), format)
        .decode()
        .map_err(decode_error)?;
    Ok(match format {
        ImageFormat::OpenExr => encode_linear(&image),
        _ => image.into_rgba8(),
    })
}

/// The format the first bytes of a file announce, among those [`load_image`] reads.
fn image_format(bytes: &[u8]) -> Option<ImageFormat> {
    /// The OpenEXR magic number, 20000630 little-endian.
    const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];
    if bytes.starts_with(&PNG_SIGNATURE) {
        Some(ImageFormat::Png)
    } else if bytes.starts_with(&EXR_MAGIC) {
        Some(ImageFormat::OpenExr)
    } else if bytes.len() >= 3
        && bytes[0] == b'P'
        && (b'1'..=b'7').contains(&bytes[1])
        && bytes[2].is_ascii_whitespace()
    {
        Some(ImageFormat::Pnm)
    } else {
        None
    }
}

/// A format's name in messages.
fn format_name(format: ImageFormat) -> &'static str {
    match format {
        ImageFormat::Png => "PNG",
        ImageFormat::OpenExr => "OpenEXR",
        _ => "PPM/PGM",
    }
}

/// A linear-light image (OpenEXR) encoded as an 8-bit sRGB picture, alpha kept linear.
fn encode_linear(image: &DynamicImage) -> RgbaImage {
    let linear = image.to_rgba32f();
    RgbaImage::from_fn(linear.width(), linear.height(), |x, y| {
        let [r, g, b, a] = linear.get_pixel(x, y).0;
        let alpha = viewray_output::unit_to_u8(a);
        image::Rgba([
            viewray_output::linear_to_srgb8(r),
            viewray_output::linear_to_srgb8(g),
            viewray_output::linear_to_srgb8(b),
            alpha,
        ])
    })
}

enum DecodeError {
    NotPng,
    Image(image::ImageError),
}

fn decode_png(bytes: &[u8]) -> Result<RgbaImage, DecodeError> {
    if !bytes.starts_with(&PNG_SIGNATURE) {
        return Err(DecodeError::NotPng);
    }
    // The decoder's default limits (512 MiB of pixels) stop absurd headers.
    let reader = ImageReader::with_format(io::Cursor::new(bytes), ImageFormat::Png);
    let image = reader.decode().map_err(DecodeError::Image)?;
    Ok(image.into_rgba8())
}

/// [`decode_png`] with its error as a sentence.
pub(crate) fn decode_png_bytes(bytes: &[u8]) -> Result<RgbaImage, String> {
    decode_png(bytes).map_err(|error| match error {
        DecodeError::NotPng => "not a PNG file".to_owned(),
        DecodeError::Image(source) => source.to_string(),
    })
}
