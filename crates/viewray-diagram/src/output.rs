//! PNG encoding and atomic file writes.

use std::io::{self, Write as _};
use std::path::Path;

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

/// Writes `bytes` to `path` through a temporary file in the same directory that is
/// renamed over `path` once complete: readers see the old file or the new one, never a
/// partial one, and a failure leaves no stray file behind.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".viewray-figure-").suffix(".tmp");
    // The temporary file is private (0600) by default; a figure is an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut file = builder.tempfile_in(directory)?;
    file.write_all(bytes)?;
    file.as_file().sync_all()?;
    file.persist(path).map_err(|e| e.error)?;
    Ok(())
}
