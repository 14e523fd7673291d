//! Reading PNG files into pixels.

use std::io;
use std::path::{Path, PathBuf};

use image::{ImageFormat, ImageReader, RgbaImage};

/// Why a PNG file could not be read. Every variant names the file.
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
    /// The file starts like a PNG but its contents do not decode (truncated or corrupt).
    #[error("{}: the PNG does not decode: {source}", path.display())]
    Decode {
        /// The file.
        path: PathBuf,
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
            source,
        },
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
